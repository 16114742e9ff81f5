#include "tools/cli/progress.h"

#include <unistd.h>

#include <cstdio>
#include <iostream>

#include "tools/scene/common.h"

namespace tessera::cli {

using namespace scene;

namespace {
constexpr double kQuietSeconds = 0.5;    // shorter work shows nothing
constexpr double kTerminalPeriod = 0.1;  // bar redraws
constexpr double kPlainPeriod = 5.0;     // lines in a log
constexpr int kBarWidth = 30;
}  // namespace

Progress::Progress(std::string what, std::string unit, std::uint64_t total)
    : what_(std::move(what)), unit_(std::move(unit)), total_(total), terminal_(::isatty(STDERR_FILENO) == 1) {}

void Progress::update(std::uint64_t done, std::uint64_t total) {
  if (finished_ || verbosity() < 0) return;
  if (total != total_ || done < done_) {
    if (done_ > 0) ++pass_, earlier_ += done_;
    total_ = total;
  }
  done_ = done;
  const auto now = Clock::now();
  const double elapsed = std::chrono::duration<double>(now - start_).count();
  if (elapsed < (verbosity() >= 1 ? 0.0 : kQuietSeconds)) return;  // -v shows all of it
  const double since = std::chrono::duration<double>(now - last_shown_).count();
  if (shown_ && since < (terminal_ ? kTerminalPeriod : kPlainPeriod)) return;
  last_shown_ = now;
  shown_ = true;
  const double fraction = total_ > 0 ? std::min(1.0, double(done_) / double(total_)) : 0.0;
  char line[256];
  const std::string pass = pass_ > 1 ? " (pass " + std::to_string(pass_) + ")" : "";
  if (terminal_) {
    const int filled = int(fraction * kBarWidth + 0.5);
    const std::string bar = std::string(std::size_t(filled), '#') + std::string(std::size_t(kBarWidth - filled), '.');
    std::snprintf(line, sizeof line, "\rtessera: %s [%s] %3d%% %llu/%llu %s%s, %.1f s\033[K", what_.c_str(),
                  bar.c_str(), int(fraction * 100.0), static_cast<unsigned long long>(done_),
                  static_cast<unsigned long long>(total_), unit_.c_str(), pass.c_str(), elapsed);
    std::cerr << line << std::flush;
  } else {
    std::snprintf(line, sizeof line, "tessera: %s %d%% (%llu/%llu %s%s), %.1f s\n", what_.c_str(),
                  int(fraction * 100.0), static_cast<unsigned long long>(done_),
                  static_cast<unsigned long long>(total_), unit_.c_str(), pass.c_str(), elapsed);
    std::cerr << line << std::flush;
  }
}

void Progress::finish() {
  if (finished_) return;
  finished_ = true;
  if (!shown_) return;
  if (terminal_) {
    std::cerr << "\r\033[K" << std::flush;
  } else {
    const double elapsed = std::chrono::duration<double>(Clock::now() - start_).count();
    char line[256];
    // The whole work, not its last pass: a render of two patch groups counts both.
    if (pass_ > 1)
      std::snprintf(line, sizeof line, "tessera: %s done (%llu %s in %d passes), %.1f s\n", what_.c_str(),
                    static_cast<unsigned long long>(earlier_ + done_), unit_.c_str(), pass_, elapsed);
    else
      std::snprintf(line, sizeof line, "tessera: %s done (%llu/%llu %s), %.1f s\n", what_.c_str(),
                    static_cast<unsigned long long>(done_), static_cast<unsigned long long>(total_), unit_.c_str(),
                    elapsed);
    std::cerr << line << std::flush;
  }
}

StepProgress::StepProgress(std::string what) : what_(std::move(what)), terminal_(::isatty(STDERR_FILENO) == 1) {
  if (verbosity() >= 0) watcher_ = std::thread([this] { watch(); });
}

void StepProgress::step(const char* name) {
  const std::lock_guard lock(mutex_);
  current_ = name;
  step_start_ = Clock::now();
  if (verbosity() >= 1) std::cerr << "tessera: " << what_ << ": " << current_ << "\n" << std::flush;
  wake_.notify_one();
}

void StepProgress::watch() {
  // A terminal shows a step once it has run a second; a log, once it has run as long as a line of its
  // own is worth (kPlainPeriod), so that a slow build's log is not filled with steps of a second or two.
  const double show_after = terminal_ ? 1.0 : kPlainPeriod;
  std::unique_lock lock(mutex_);
  std::string last_step;
  double last_shown = 0.0;
  while (!done_) {
    wake_.wait_for(lock, std::chrono::milliseconds(terminal_ ? 200 : 500));
    if (done_ || current_.empty() || verbosity() >= 1) continue;  // -v has a line per step already
    const double elapsed = std::chrono::duration<double>(Clock::now() - step_start_).count();
    if (elapsed < show_after) continue;
    const bool new_step = current_ != last_step;
    if (!terminal_ && !new_step && elapsed - last_shown < kPlainPeriod) continue;
    char line[256];
    std::snprintf(line, sizeof line, terminal_ ? "\rtessera: %s: %s, %.1f s\033[K" : "tessera: %s: %s, %.1f s\n",
                  what_.c_str(), current_.c_str(), elapsed);
    std::cerr << line << std::flush;
    shown_ = true;
    last_step = current_;
    last_shown = elapsed;
  }
}

void StepProgress::finish() {
  {
    const std::lock_guard lock(mutex_);
    if (done_) return;
    done_ = true;
    wake_.notify_one();
  }
  if (watcher_.joinable()) watcher_.join();
  if (shown_ && terminal_) std::cerr << "\r\033[K" << std::flush;
}

}  // namespace tessera::cli
