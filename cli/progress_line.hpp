// A progress line on stderr for long runs: "ecorail frontier: point 12/61, 8.1 s, about 33 s
// left". It is shown only when stderr is a terminal and --quiet was not given, so logs, pipes
// and scripts never see it; the line is rewritten in place (carriage return), at most every
// 0.2 s (but at once when a stage is reported for the first time), and cleared when the Progress
// ends. The estimate of time left is elapsed time times the share of work not yet done, given only
// when the total is known.
#pragma once

#include <chrono>
#include <mutex>
#include <string>
#include <vector>

#include "dp/progress_callback.hpp"

namespace ecorail::cli {

class Progress {
 public:
  // label: the command, e.g. "ecorail frontier". quiet: --quiet was given.
  Progress(std::string label, bool quiet);
  ~Progress();
  Progress(const Progress&) = delete;
  Progress& operator=(const Progress&) = delete;

  bool enabled() const { return enabled_; }
  // Records stage, done out of total (0: unknown) and redraws the line when due.
  void update(const char* stage, int done, int total);
  // A dp::ProgressFn that forwards to update (empty when the line is not shown, so the library
  // skips the calls); the Progress must outlive the computation.
  dp::ProgressFn callback();

  // The text of the line (no carriage return), for tests: elapsed and, with a known total and
  // some work done, the estimate of time left.
  static std::string line(const std::string& label, const char* stage, int done, int total,
                          double elapsed_s);
  // True when stderr is a terminal (isatty).
  static bool stderr_is_terminal();

 private:
  std::string label_;
  bool enabled_;
  std::chrono::steady_clock::time_point start_, last_draw_;
  std::size_t drawn_width_ = 0;
  bool first_step_drawn_ = false;          // the first finished step of a count is always drawn
  std::vector<std::string> stages_drawn_;  // each stage's first report is always drawn
  std::mutex mutex_;
};

}  // namespace ecorail::cli
