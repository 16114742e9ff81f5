// The commands module's one exported symbol: the launcher (launcher_main.cpp) finds it with dlsym.
#include "tools/cli/commands.h"

extern "C" __attribute__((visibility("default"))) int tessera_cli_main(int argc, char** argv) {
  return tessera::cli::run_cli(argc, argv);
}
