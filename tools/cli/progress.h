// Progress of long work on stderr, as command-line tools show it: a bar redrawn in place when stderr is
// a terminal, a plain line every few seconds otherwise (CI logs), nothing with -q. Work that ends within
// its first half second shows nothing at all, so short commands stay quiet; with -v all of it shows.
// A log gets a last line when the work is done, counting every pass (a render of quads and triangles
// draws two).
//
// Not thread-safe: updates come one at a time (the Device calls its progress hook after each round of
// chunks, in order, from whichever thread rasterized it; the draw's pipeline orders those calls).
// Progress only reads counters; it cannot change a result.
#pragma once

#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <mutex>
#include <string>
#include <thread>

#include "shaders_cpp/render/subd_model.h"

namespace tessera::cli {

class Progress {
 public:
  // `what` names the work ("render", "frames"); `unit` what is counted ("patches", "images").
  Progress(std::string what, std::string unit, std::uint64_t total);
  Progress(const Progress&) = delete;
  Progress& operator=(const Progress&) = delete;
  ~Progress() { finish(); }

  // `done` of `total` (a new total restarts the count: a render may draw several passes).
  void update(std::uint64_t done, std::uint64_t total);
  void advance(std::uint64_t n) { update(done_ + n, total_); }
  // Erases the bar (the terminal's line is left clean for what follows). Idempotent.
  void finish();

 private:
  using Clock = std::chrono::steady_clock;
  std::string what_, unit_;
  std::uint64_t done_ = 0, total_ = 0;
  std::uint64_t earlier_ = 0;  // done in the passes before this one
  int pass_ = 1;
  Clock::time_point start_ = Clock::now(), last_shown_{};
  bool terminal_ = false, shown_ = false, finished_ = false;
};

// The steps of one job that has no count to show ("preparing frog.obj": reading, topology, patches,
// ...): on a terminal a step that has run for a second is shown as one line redrawn in place with its
// elapsed time; in a log a step that has run five seconds gets a line, and another every five seconds;
// nothing with -q, every step with -v. A watcher thread does the showing, so a step that never returns control is
// still reported; step() only records which step runs (from the thread doing the work).
class StepProgress {
 public:
  explicit StepProgress(std::string what);
  StepProgress(const StepProgress&) = delete;
  StepProgress& operator=(const StepProgress&) = delete;
  ~StepProgress() { finish(); }

  void step(const char* name);
  // step() as a PrepareStep, for load_subd_model and prepare_scene. Valid while this object lives.
  PrepareStep hook() {
    return [this](const char* name) { step(name); };
  }
  // Stops the watcher and clears the terminal's line. Idempotent.
  void finish();

 private:
  using Clock = std::chrono::steady_clock;
  void watch();

  std::string what_;
  bool terminal_ = false;
  std::mutex mutex_;
  std::condition_variable wake_;
  std::string current_;  // guarded by mutex_, as are the three below
  Clock::time_point step_start_ = Clock::now();
  bool done_ = false, shown_ = false;
  std::thread watcher_;
};

}  // namespace tessera::cli
