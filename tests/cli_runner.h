// Running the tessera executable from a test: its exit code, stdout and stderr.
#pragma once

#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace tessera::test {

struct CliResult {
  int exit_code;
  std::string out, err;
};

// A directory of this test process's own (tests may run in parallel processes).
// The name also holds the process's start time: PIDs are reused, and a directory that a finished test
// process left behind handed its files to a later process of the same PID (a fake harness's call log
// that had three lines too many).
inline std::filesystem::path cli_temp_dir() {
  static const std::string name = "tessera-test-" + std::to_string(::getpid()) + "-" +
                                  std::to_string(std::chrono::system_clock::now().time_since_epoch().count());
  const auto dir = std::filesystem::temp_directory_path() / name;
  std::filesystem::create_directories(dir);
  return dir;
}

inline std::string slurp(const std::filesystem::path& p) {
  std::ifstream in(p);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

// Runs `tessera ARGS` through the shell (args are shell words).
inline CliResult run_cli(const std::string& args) {
  const auto dir = cli_temp_dir();
  const std::string cmd =
      std::string(TESSERA_BIN) + " " + args + " >" + (dir / "out").string() + " 2>" + (dir / "err").string();
  const int status = std::system(cmd.c_str());
  return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, slurp(dir / "out"), slurp(dir / "err")};
}

}  // namespace tessera::test
