#include "tools/cli/cli_app.h"

#include <algorithm>
#include <exception>
#include <iostream>
#include <map>

#include "tools/scene/common.h"

namespace tessera::cli {

std::string version_line() { return std::string("tessera 0.1.0 (") + kBuildIsa + ")"; }

int run_app(int argc, char** argv, std::span<const CommandEntry> commands,
            const std::function<std::vector<std::string>(int, char**)>& arguments) {
  CLI::App app{"tessera: a deterministic CPU implementation of the Direct3D 11 tessellation pipeline"};
  app.require_subcommand(1);
  bool quiet = false, verbose = false;
  app.add_flag("-q,--quiet", quiet, "only errors on stderr");
  app.add_flag("-v,--verbose", verbose, "more detail on stderr");
  app.set_version_flag("--version", version_line());
  std::map<std::string, Runner> runners;
  for (const CommandEntry& c : commands) runners[c.name] = c.add(app);
  // Options given to the top level apply wherever they are written.
  for (CLI::App* sub : app.get_subcommands({})) sub->fallthrough();

  try {
    std::vector<std::string> args = arguments(argc, argv);
    // Before CLI11, which reads "" as 0 for a number and calls an unknown command a missing one.
    for (std::size_t i = 1; i < args.size(); ++i) {
      const std::string& a = args[i];
      if (a.size() > 1 && a[0] == '-' && a.back() == '=')
        throw CLI::ValidationError(a.substr(0, a.size() - 1) + ": an empty value");
      if (a.empty() && i > 1 && args[i - 1].size() > 1 && args[i - 1][0] == '-')
        throw CLI::ValidationError(args[i - 1] + ": an empty value");
    }
    if (args.size() > 1 && !args[1].empty() && args[1][0] != '-' && !runners.count(args[1])) {
      std::string names;
      for (const auto& [name, runner] : runners) names += (names.empty() ? "" : ", ") + name;
      throw CLI::ValidationError("'" + args[1] + "' is not a command (" + names + ")");
    }
    // CLI11 takes the arguments last to first.
    args.erase(args.begin());
    std::reverse(args.begin(), args.end());
    app.parse(args);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForVersion& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    std::cerr << "tessera: " << one_line_message(e.what()) << " (see tessera --help)\n";
    return kExitUsage;
  } catch (const UsageError& e) {
    // A value a setting's reader refused (tools/scene/render_settings.h), named as the command would.
    const auto parsed = app.get_subcommands();
    std::cerr << "tessera" << (parsed.empty() ? "" : " " + parsed.front()->get_name()) << ": "
              << one_line_message(e.what()) << "\n";
    return kExitUsage;
  }
  set_verbosity(quiet ? -1 : verbose ? 1 : 0);
  const std::string name = app.get_subcommands().front()->get_name();
  try {
    return runners.at(name)();
  } catch (const UsageError& e) {
    std::cerr << "tessera " << name << ": " << one_line_message(e.what()) << "\n";
    return kExitUsage;
  } catch (const InputError& e) {
    std::cerr << "tessera " << name << ": " << one_line_message(e.what()) << "\n";
    return kExitFailure;
  } catch (const std::exception& e) {
    std::cerr << "tessera " << name << ": " << one_line_message(e.what()) << "\n";
    return kExitFailure;
  }
}

}  // namespace tessera::cli
