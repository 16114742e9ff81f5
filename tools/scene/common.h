// What every `tessera` subcommand shares: exit codes, logging, number-list parsing, and writing
// output files atomically (a temporary in the same directory, then rename: a failed run never
// leaves a half-written file behind).
#pragma once

#include <functional>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "pipeline/device.h"
#include "shaders_cpp/cage/one_line.h"
#include "shaders_cpp/lod/subd_factors.h"

namespace tessera::scene {

// The instruction set this build was compiled for (TESSERA_ISA in CMakeLists.txt): benchmark reports
// name it, since timings depend on it (the images do not).
inline constexpr const char* kBuildIsa =
#if defined(__AVX512F__) && defined(__AVX512VL__) && defined(__AVX512BW__) && defined(__AVX512DQ__)
    "x86-64-v4";
#elif defined(__AVX2__)
    "x86-64-v3";
#else
    "baseline";
#endif

// Exit codes: 0 ok, 1 bad input or failed check, 2 usage error.
inline constexpr int kExitOk = 0;
inline constexpr int kExitFailure = 1;
inline constexpr int kExitUsage = 2;

// A usage error (bad flag value, wrong count): reported as one line, exit 2.
struct UsageError : std::runtime_error {
  using std::runtime_error::runtime_error;
};
// Runs `f` and returns what it returns; a setting the factor policy refuses (FactorSettingError,
// lod/subd_factors.h) is the user's to fix: it leaves as a UsageError with the same text.
template <class F>
decltype(auto) with_usage_errors(F&& f) {
  try {
    return f();
  } catch (const FactorSettingError& e) {
    throw UsageError(e.what());
  }
}

// Bad input data or a failed check: reported as one line, exit 1.
struct InputError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// An error message as the CLI prints it: one_line_message (shaders_cpp/cage/one_line.h), which the
// readers below use for what their libraries say.
using tessera::one_line_message;

// CLI11's "Could not convert: --factor = abc" as the option without its dashes and the value
// ("factor", "abc"; a value over 40 characters cut there), or nullopt for any other text.
std::optional<std::pair<std::string, std::string>> unconverted_option(const std::string& message);

// The candidate a user most likely meant by `word` (a misspelt command, option or name): the one at the
// smallest edit distance (Damerau: a swap of two neighbours counts one), if that distance is at most a
// third of the word's length (at least 1, at most 3) and no other candidate is as close; else empty.
std::string closest_name(std::string_view word, const std::vector<std::string>& candidates);
// "; did you mean NAME?" for closest_name, or empty.
std::string did_you_mean(std::string_view word, const std::vector<std::string>& candidates);

// -q: -1, default 0, -v: 1. Logs go to stderr.
void set_verbosity(int level);
int verbosity();
void log_info(std::string_view message);
void log_debug(std::string_view message);

// Parses one float the way a user writes it: decimal, hex-float, nan, inf, -inf, -0.
// Returns nullopt on anything else (empty, trailing characters, out of float range).
std::optional<float> parse_float(std::string_view text);
// Parses "A,B,C" into floats; throws UsageError naming `what` and the bad token.
std::vector<float> parse_float_list(std::string_view text, std::string_view what);

// Writes a file through `write(path_of_temporary)`, then renames it over `path`.
// `write` throws on failure; the temporary is removed and the exception propagates.
void write_file_atomically(const std::string& path, const std::function<void(const std::string&)>& write);

// write_file_atomically for a text that is already complete in memory.
void write_text_atomically(const std::string& path, const std::string& text);

// Outputs of one command, refused before any work (UsageError naming the option): "-" (no command
// writes its results to stdout through -o), two outputs on one path, an output that is one of the
// command's inputs, and an output whose directory does not exist. Empty paths are skipped.
struct OutputPath {
  std::string option, path;
};
void check_output_paths(const std::vector<OutputPath>& outputs, const std::vector<std::string>& inputs);

// A data file shipped with tessera (the default cage of `bench frog`): share/tessera/<name> beside
// the binary's directory, in the build tree as in an installed tree. Throws InputError when absent,
// naming the file and `option`, the option that names another file instead.
std::string shared_data_file(const std::string& name, const std::string& option);
// The cage a benchmark draws: `cage` (its --cage), or the shipped monster frog when that is empty.
std::string cage_or_shipped_frog(const std::string& cage);

// "AxB" for option `what`, each side in lo..hi; throws UsageError naming the option.
std::pair<int, int> parse_size(const std::string& text, const std::string& what, int lo, int hi);
// "WIDTHxHEIGHT" for --resolution, each side 1..kMaxRenderTargetSize (framebuffer.h).
std::pair<int, int> parse_resolution(const std::string& text);

// Device options for --threads N (0 = all hardware threads; 0..1024, else UsageError).
DeviceOptions device_options(int threads);

}  // namespace tessera::scene
