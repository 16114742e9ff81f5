// The `tessera` subcommands. Each registers its options on a CLI11 subcommand and runs after
// parsing; run() returns the exit code (cli_common.h) and throws UsageError/InputError for
// one-line errors.
#pragma once

#include <CLI/CLI.hpp>

#include <functional>
#include <span>
#include <string>
#include <vector>

namespace tessera::cli {

using Runner = std::function<int()>;

// Each returns the function that runs the subcommand once CLI11 has parsed its options.
Runner add_pattern_command(CLI::App& app);
Runner add_oracle_command(CLI::App& app);
// `bench` with its benchmarks, and `more` registered under it (benchmarks of libraries above this one:
// bench view, from tools/viewer/).
using BenchAdder = Runner (*)(CLI::App& bench);
Runner add_bench_command(CLI::App& app, std::span<const BenchAdder> more = {});
Runner add_analyze_command(CLI::App& app);
Runner add_tessellate_command(CLI::App& app);
Runner add_render_command(CLI::App& app);
Runner add_accuracy_command(CLI::App& app);
Runner add_make_cage_command(CLI::App& app);
Runner add_diff_command(CLI::App& app);
Runner add_check_command(CLI::App& app);
Runner add_view_command(CLI::App& app);
Runner add_bake_command(CLI::App& app);
Runner add_optimize_command(CLI::App& app);
// The whole command line: every command (cli_main.cpp). Returns the exit code.
int run_cli(int argc, char** argv);
// argv with `tessera diff`'s idiff spellings (-fail, -od, ...) turned into CLI11's (--fail, --od).
std::vector<std::string> idiff_arguments(int argc, char** argv);
// Registered under `bench`; its runner returns -1 when `bench torus` was not the chosen subcommand.
Runner add_bench_torus_command(CLI::App& bench);
Runner add_bench_subd_command(CLI::App& bench);
Runner add_bench_dolly_command(CLI::App& bench);
Runner add_bench_scaling_command(CLI::App& bench);
Runner add_bench_view_command(CLI::App& bench);  // tools/cli/bench_view.cpp
Runner add_bench_load_command(CLI::App& bench);  // tools/cli/bench_load.cpp

}  // namespace tessera::cli
