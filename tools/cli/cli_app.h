// The command-line frame every `tessera` binary shares: global flags (-q, -v, --version), checks made
// before CLI11 parses (empty values, unknown commands), CLI11's parse, the chosen command's run, and
// errors turned into one line on stderr and an exit code (cli_common.h). The commands themselves are
// the caller's: the full tool registers them all (cli_main.cpp), the start-up launcher only those it
// can run without image I/O (launcher_main.cpp).
#pragma once

#include <functional>
#include <span>
#include <string>
#include <vector>

#include "tools/cli/commands.h"

namespace tessera::cli {

struct CommandEntry {
  const char* name;
  Runner (*add)(CLI::App& app);
};

// `arguments` turns argv into the words CLI11 parses (the full tool rewrites idiff's spellings).
int run_app(int argc, char** argv, std::span<const CommandEntry> commands,
            const std::function<std::vector<std::string>(int, char**)>& arguments);

// The version line `tessera --version` prints.
std::string version_line();

}  // namespace tessera::cli
