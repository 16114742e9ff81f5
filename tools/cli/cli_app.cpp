#include "tools/cli/cli_app.h"

#include <algorithm>
#include <exception>
#include <iostream>
#include <map>

#include "tools/scene/common.h"

namespace tessera::cli {

using namespace scene;

std::string version_line() { return std::string("tessera 0.1.0 (") + kBuildIsa + ")"; }

namespace {

// Words users reach for that name a concept under another option: what a misspelling search cannot find.
const std::map<std::string, std::string>& option_aliases() {
  static const std::map<std::string, std::string> aliases = {
      {"--samples", "--msaa"},
      {"--spp", "--msaa"},
      {"--aa", "--msaa"},
      {"--antialias", "--msaa"},
      {"--multisample", "--msaa"},
      {"--size", "--resolution"},
      {"--res", "--resolution"},
      {"--width", "--resolution"},
      {"--height", "--resolution"},
      {"--eye", "--camera-position"},
      {"--camera", "--camera-position"},
      {"--position", "--camera-position"},
      {"--target", "--camera-target"},
      {"--look-at", "--camera-target"},
      {"--lookat", "--camera-target"},
      {"--up", "--camera-up"},
      {"--output", "-o"},
      {"--out", "-o"},
      {"--subdivision", "--scheme"},
      {"--method", "--scheme"},
      {"--tess-factor", "--factor"},
      {"--tessfactor", "--factor"},
      {"--level", "--factor"},
      {"--mode", "--view"},
      {"--spacing", "--partitioning"},
      {"--jobs", "--threads"},
      {"-j", "--threads"},
      {"--two-sided-lighting", "--two-sided"},
      {"--double-sided", "--two-sided"},
      {"--no-cull", "--two-sided"},
  };
  return aliases;
}

// The names an app's options answer to ("--msaa", "-o").
std::vector<std::string> option_names(const CLI::App& app) {
  std::vector<std::string> names;
  for (const CLI::Option* o : app.get_options()) {
    for (const std::string& l : o->get_lnames()) names.push_back("--" + l);
    for (const std::string& s : o->get_snames()) names.push_back("-" + s);
  }
  return names;
}

// For arguments CLI11 did not expect: the first unknown option of the command and what it likely
// meant, in one line that points at the command's own help.
std::string unexpected_arguments(const CLI::App& app, const std::vector<std::string>& args, const std::string& command,
                                 const std::string& what) {
  const std::string help = " (see tessera " + (command.empty() ? std::string() : command + " ") + "--help)";
  if (command.empty()) return what + help;
  std::vector<std::string> known = option_names(app);
  const std::vector<std::string> own = option_names(*app.get_subcommand(command));
  known.insert(known.end(), own.begin(), own.end());
  for (std::size_t i = 1; i < args.size(); ++i) {
    const std::string& a = args[i];
    if (a.size() < 2 || a[0] != '-' || (a[1] >= '0' && a[1] <= '9') || a[1] == '.') continue;  // -0.5 is a value
    const std::string name = a.substr(0, a.find('='));
    if (std::find(known.begin(), known.end(), name) != known.end()) continue;
    std::string hint;
    if (const auto it = option_aliases().find(name);
        it != option_aliases().end() && std::find(own.begin(), own.end(), it->second) != own.end())
      hint = "; did you mean " + it->second + "?";
    else
      hint = did_you_mean(name, own);
    return "tessera " + command + ": unknown option " + name + hint + help;
  }
  return "tessera " + command + ": " + what + help;
}

}  // namespace

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

  // The first word that names a command (top-level flags may come first), or empty.
  const auto named_command = [&](const std::vector<std::string>& args) {
    for (std::size_t i = 1; i < args.size(); ++i)
      if (runners.count(args[i])) return args[i];
    return std::string();
  };
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
      std::vector<std::string> list;
      for (const auto& [name, runner] : runners) names += (names.empty() ? "" : ", ") + name, list.push_back(name);
      throw CLI::ValidationError("'" + args[1] + "' is not a command" + did_you_mean(args[1], list) + " (" + names +
                                 ")");
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
  } catch (const CLI::ConversionError& e) {
    // CLI11 says "Could not convert: --two-sided = maybe": name the option and the command's help.
    const std::string command = named_command(arguments(argc, argv));
    const std::string text = one_line_message(e.what());
    const auto bad = unconverted_option(text);
    const std::string prefix = command.empty() ? "tessera" : "tessera " + command;
    std::cerr << prefix << ": " << (bad ? "--" + bad->first + ": cannot read '" + bad->second + "'" : text) << " (see "
              << prefix << " --help)\n";
    return kExitUsage;
  } catch (const CLI::ExtrasError& e) {
    const std::vector<std::string> args = arguments(argc, argv);
    const std::string command = named_command(args);
    std::cerr << unexpected_arguments(app, args, command, one_line_message(e.what())) << "\n";
    return kExitUsage;
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
