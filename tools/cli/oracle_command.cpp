// `tessera oracle-compare`: checks the tessellator against dumps of the D3D11 reference as Mesa's
// llvmpipe runs it (tools/oracle/run_oracle.sh makes them), and writes golden digests for tests.
#include <fstream>
#include <iostream>
#include <memory>

#include "tools/cli/commands.h"
#include "tools/scene/common.h"
#include "tools/scene/json_output.h"
#include "tools/verify/oracle.h"

namespace tessera::cli {

using namespace scene;

namespace {

struct OracleOptions {
  std::string dump;
  std::string write_golden;
  int golden_every = 1;
  bool json = false;
};

int run_oracle(const OracleOptions& o) {
  std::ifstream in(o.dump);
  if (!in) throw InputError(o.dump + ": cannot open");
  std::vector<oracle::Capture> captures;
  std::string error;
  if (!oracle::read_dump(in, captures, error)) throw InputError(o.dump + ": " + error);
  if (captures.empty()) throw InputError(o.dump + ": no cases in the dump");
  std::size_t set_match = 0, order_match = 0;
  std::vector<std::string> golden;
  for (std::size_t i = 0; i < captures.size(); ++i) {
    const auto& cap = captures[i];
    const auto ours = oracle::tessera_primitives(cap.c);
    const auto cmp = oracle::compare(cap.primitives, ours);
    set_match += cmp.set_equal;
    order_match += cmp.order_equal;
    if (!cmp.set_equal)
      std::cerr << "MISMATCH " << cap.c.line << ": " << cmp.detail << "\n";
    else if (!cmp.order_equal)
      log_debug("order differs: " + cap.c.line);
    if (!o.write_golden.empty() && i % std::size_t(o.golden_every) == 0)
      golden.push_back(oracle::golden_line(cap.c, oracle::digest(cap.primitives)));
  }
  if (!o.write_golden.empty()) {
    std::string text =
        "# Digests of the D3D11 reference tessellator's output, captured from Mesa llvmpipe by "
        "tools/oracle/run_oracle.sh.\n"
        "# Regenerate only with tools/regen_golden.sh. Format: <tessref case line> => <primitives> <ordered fnv64> "
        "<set fnv64>\n";
    for (const auto& line : golden) text += line + "\n";
    write_text_atomically(o.write_golden, text);
    log_info("wrote " + std::to_string(golden.size()) + " golden digests to " + o.write_golden);
  }
  if (o.json)
    std::cout << json_text(Json{{"cases", captures.size()}, {"set_match", set_match}, {"order_match", order_match}})
              << "\n";
  else
    std::cout << captures.size() << " cases: " << set_match << " match as primitive sets, " << order_match
              << " also in the same order\n";
  return set_match == captures.size() ? kExitOk : kExitFailure;
}

}  // namespace

Runner add_oracle_command(CLI::App& app) {
  auto o = std::make_shared<OracleOptions>();
  CLI::App* cmd =
      app.add_subcommand("oracle-compare", "Compare the tessellator with a dump of the D3D11 reference (llvmpipe)");
  cmd->footer("Make dumps with tools/oracle/run_oracle.sh (needs Mesa's llvmpipe and ../shared/bench/tessref.cpp).");
  cmd->add_option("dump", o->dump, "tessref output")->required();
  cmd->add_option("--write-golden", o->write_golden, "write the reference's digests to this file (tests read them)");
  cmd->add_option("--golden-every", o->golden_every, "keep every Nth case in the golden file")
      ->check(CLI::PositiveNumber);
  cmd->add_flag("--json", o->json, "print the summary as JSON");
  return [o] { return run_oracle(*o); };
}

}  // namespace tessera::cli
