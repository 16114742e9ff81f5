// The full `tessera` command line: every command. Built into the commands module that the launcher
// (launcher_main.cpp) loads through cli_module.cpp.
#include "tools/cli/cli_app.h"
#include "tools/cli/commands.h"

namespace tessera::cli {

namespace {

Runner add_bench_commands(CLI::App& app) {
  static constexpr BenchAdder kMore[] = {add_bench_view_command, add_bench_load_command};
  return add_bench_command(app, kMore);
}

}  // namespace

int run_cli(int argc, char** argv) {
  static constexpr CommandEntry kCommands[] = {{"pattern", add_pattern_command},
                                               {"oracle-compare", add_oracle_command},
                                               {"bench", add_bench_commands},
                                               {"analyze", add_analyze_command},
                                               {"tessellate", add_tessellate_command},
                                               {"render", add_render_command},
                                               {"accuracy", add_accuracy_command},
                                               {"make-cage", add_make_cage_command},
                                               {"diff", add_diff_command},
                                               {"check", add_check_command},
                                               {"view", add_view_command},
                                               {"bake", add_bake_command},
                                               {"optimize", add_optimize_command}};
  return run_app(argc, argv, kCommands, idiff_arguments);
}

}  // namespace tessera::cli
