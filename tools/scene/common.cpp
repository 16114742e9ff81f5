#include "tools/scene/common.h"

#include "pipeline/framebuffer.h"
#include "shaders_cpp/image_io/atomic_file.h"

#include <dlfcn.h>

#include <algorithm>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <filesystem>
#include <regex>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iostream>

namespace tessera::scene {
namespace {
int g_verbosity = 0;  // set once by main before any command runs
}

void set_verbosity(int level) { g_verbosity = level; }
int verbosity() { return g_verbosity; }
void log_info(std::string_view message) {
  if (g_verbosity >= 0) std::cerr << "tessera: " << message << "\n";
}
void log_debug(std::string_view message) {
  if (g_verbosity >= 1) std::cerr << "tessera: " << message << "\n";
}

std::optional<float> parse_float(std::string_view text) {
  if (text.empty() || text.size() > 64) return std::nullopt;
  const std::string s(text);
  if (std::isspace(static_cast<unsigned char>(s.front()))) return std::nullopt;
  errno = 0;
  char* end = nullptr;
  const float value = std::strtof(s.c_str(), &end);
  if (end != s.c_str() + s.size()) return std::nullopt;
  // strtof reports overflow with ERANGE and +-HUGE_VALF; an explicit "inf" is fine.
  if (errno == ERANGE && std::isinf(value)) return std::nullopt;
  return value;
}

std::vector<float> parse_float_list(std::string_view text, std::string_view what) {
  std::vector<float> values;
  std::size_t start = 0;
  while (true) {
    const std::size_t comma = text.find(',', start);
    const std::string_view token =
        text.substr(start, comma == std::string_view::npos ? std::string_view::npos : comma - start);
    const auto value = parse_float(token);
    if (!value)
      throw UsageError(std::string(what) + ": '" + std::string(token) +
                       "' is not a number (use e.g. 4, 3.5, nan, inf, -0)");
    values.push_back(*value);
    if (comma == std::string_view::npos) break;
    start = comma + 1;
  }
  return values;
}

void write_file_atomically(const std::string& path, const std::function<void(const std::string&)>& write) {
  // The pipeline's write_atomically returns errors; `write` here throws, and its exception (a
  // UsageError, an InputError, ...) is the one to report.
  std::exception_ptr failure;
  const std::string error = write_atomically(path, [&](const std::string& temp) -> std::string {
    try {
      write(temp);
      return {};
    } catch (...) {
      failure = std::current_exception();
      return "failed";
    }
  });
  if (failure) std::rethrow_exception(failure);
  if (!error.empty()) throw InputError(error);
}

void write_text_atomically(const std::string& path, const std::string& text) {
  write_file_atomically(path, [&](const std::string& temp) {
    std::ofstream out(temp, std::ios::binary);
    out << text;
    out.close();
    if (!out) throw InputError(path + ": write failed");
  });
}

std::pair<int, int> parse_size(const std::string& text, const std::string& what, int lo, int hi) {
  const std::regex re(R"((\d{1,6})x(\d{1,6}))");
  std::smatch m;
  if (!std::regex_match(text, m, re)) throw UsageError(what + ": expected AxB, got '" + text + "'");
  const int a = std::stoi(m[1]), b = std::stoi(m[2]);
  if (a < lo || b < lo || a > hi || b > hi)
    throw UsageError(what + ": " + text + " is outside " + std::to_string(lo) + ".." + std::to_string(hi) +
                     " per side");
  return {a, b};
}

std::string shared_data_file(const std::string& name, const std::string& option) {
  namespace fs = std::filesystem;
  // Beside the tessera binary (share/tessera/ next to bin/), or beside the shared object this code is
  // in when a host process loaded it (the Python package keeps its data in its own directory).
  std::vector<fs::path> places;
  std::error_code error;
  const fs::path exe = fs::read_symlink("/proc/self/exe", error);
  if (!error) places.push_back(exe.parent_path().parent_path() / "share" / "tessera" / name);
  Dl_info info{};
  if (dladdr(reinterpret_cast<void*>(&shared_data_file), &info) != 0 && info.dli_fname != nullptr) {
    const fs::path module = fs::absolute(info.dli_fname, error).parent_path();
    places.push_back(module / name);
    places.push_back(module.parent_path() / "share" / "tessera" / name);
  }
  for (const fs::path& p : places)
    if (fs::is_regular_file(p, error)) return p.string();
  throw InputError((places.empty() ? fs::path(name) : places.front()).string() +
                   ": tessera's shipped data file is missing (reinstall tessera, or give " + option + ")");
}

std::string cage_or_shipped_frog(const std::string& cage) {
  return cage.empty() ? shared_data_file("monsterfrog_mapped_00.obj", "--cage") : cage;
}

std::pair<int, int> parse_resolution(const std::string& text) {
  return parse_size(text, "--resolution", 1, kMaxRenderTargetSize);
}

DeviceOptions device_options(int threads) {
  if (threads < 0 || threads > 1024) throw UsageError("--threads: must be in 0..1024 (0 = all)");
  DeviceOptions o;
  o.threads = threads;
  return o;
}

void check_output_paths(const std::vector<OutputPath>& outputs, const std::vector<std::string>& inputs) {
  namespace fs = std::filesystem;
  const auto canonical = [](const std::string& p) {
    std::error_code ec;
    const fs::path c = fs::weakly_canonical(fs::absolute(p), ec);
    return ec ? fs::absolute(p).lexically_normal() : c;
  };
  for (std::size_t i = 0; i < outputs.size(); ++i) {
    const OutputPath& o = outputs[i];
    if (o.path.empty()) continue;
    if (o.path == "-") throw UsageError(o.option + " -: results go to files (give a path; stdout is not supported)");
    const fs::path c = canonical(o.path);
    if (fs::is_directory(c)) throw UsageError(o.option + " " + o.path + ": a directory, not a file");
    const fs::path dir = c.parent_path();
    if (!fs::is_directory(dir))
      throw UsageError(o.option + " " + o.path + ": directory '" + dir.string() + "' does not exist");
    for (std::size_t j = 0; j < i; ++j)
      if (!outputs[j].path.empty() && canonical(outputs[j].path) == c)
        throw UsageError(o.option + " and " + outputs[j].option + " name one file: " + o.path);
    for (const std::string& in : inputs)
      if (!in.empty() && canonical(in) == c)
        throw UsageError(o.option + " " + o.path + ": that is an input of this command (it would be overwritten)");
  }
}

namespace {
// Optimal string alignment distance: insertions, deletions, substitutions and swaps of neighbours.
std::size_t edit_distance(std::string_view a, std::string_view b) {
  std::vector<std::vector<std::size_t>> d(a.size() + 1, std::vector<std::size_t>(b.size() + 1));
  for (std::size_t i = 0; i <= a.size(); ++i) d[i][0] = i;
  for (std::size_t j = 0; j <= b.size(); ++j) d[0][j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i)
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t cost = a[i - 1] == b[j - 1] ? 0 : 1;
      d[i][j] = std::min({d[i - 1][j] + 1, d[i][j - 1] + 1, d[i - 1][j - 1] + cost});
      if (i > 1 && j > 1 && a[i - 1] == b[j - 2] && a[i - 2] == b[j - 1])
        d[i][j] = std::min(d[i][j], d[i - 2][j - 2] + 1);
    }
  return d[a.size()][b.size()];
}
}  // namespace

std::string closest_name(std::string_view word, const std::vector<std::string>& candidates) {
  const std::size_t limit = std::clamp<std::size_t>(word.size() / 3, 1, 3);
  std::size_t best = limit + 1;
  std::string found;
  bool tie = false;
  for (const std::string& c : candidates) {
    const std::size_t d = edit_distance(word, c);
    if (d < best) {
      best = d, found = c, tie = false;
    } else if (d == best && c != found) {
      tie = true;
    }
  }
  return best <= limit && !tie ? found : std::string();
}

std::string did_you_mean(std::string_view word, const std::vector<std::string>& candidates) {
  const std::string c = closest_name(word, candidates);
  return c.empty() ? std::string() : "; did you mean " + c + "?";
}

std::optional<std::pair<std::string, std::string>> unconverted_option(const std::string& message) {
  static const std::regex kConvert(R"(Could not convert: --([a-z-]+) = (.*))");
  std::smatch m;
  if (!std::regex_match(message, m, kConvert)) return std::nullopt;
  const std::string value = m[2].str().size() > 40 ? m[2].str().substr(0, 40) + "..." : m[2].str();
  return std::pair{m[1].str(), value};
}

}  // namespace tessera::scene
