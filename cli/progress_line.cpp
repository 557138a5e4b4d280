#include "cli/progress_line.hpp"

#include <unistd.h>

#include <algorithm>
#include <cstdio>

namespace ecorail::cli {

namespace {
constexpr double kRedrawEvery_s = 0.2;
}  // namespace

bool Progress::stderr_is_terminal() {
  return isatty(STDERR_FILENO) == 1;
}

Progress::Progress(std::string label, bool quiet)
    : label_(std::move(label)),
      enabled_(!quiet && stderr_is_terminal()),
      start_(std::chrono::steady_clock::now()),
      last_draw_(start_ - std::chrono::seconds(1)) {}

Progress::~Progress() {
  if (!enabled_ || drawn_width_ == 0) return;
  // Clear the line so the report that follows starts on a clean one.
  std::fprintf(stderr, "\r%*s\r", static_cast<int>(drawn_width_), "");
  std::fflush(stderr);
}

std::string Progress::line(const std::string& label, const char* stage, int done, int total,
                           double elapsed_s) {
  char buf[256];
  if (total > 0) {
    std::snprintf(buf, sizeof buf, "%s: %s %d/%d, %.1f s", label.c_str(), stage, done, total,
                  elapsed_s);
  } else if (done > 0) {
    std::snprintf(buf, sizeof buf, "%s: %s %d, %.1f s", label.c_str(), stage, done, elapsed_s);
  } else {  // a stage that counts nothing (building the grids, the cruise polish)
    std::snprintf(buf, sizeof buf, "%s: %s, %.1f s", label.c_str(), stage, elapsed_s);
  }
  std::string text = buf;
  if (total > 0 && done > 0 && done < total) {
    const double left_s = elapsed_s * double(total - done) / double(done);
    std::snprintf(buf, sizeof buf, ", about %.0f s left", left_s);
    text += buf;
  }
  return text;
}

void Progress::update(const char* stage, int done, int total) {
  if (!enabled_) return;
  const std::lock_guard<std::mutex> lock(mutex_);
  const auto now = std::chrono::steady_clock::now();
  const bool last = total > 0 && done >= total;
  // The first finished step of a count is drawn whatever the clock says: it is the first line
  // with a time-left estimate, and a ladder of two layers would otherwise show none between
  // its start and its end.
  const bool first_step = total > 1 && done == 1 && !first_step_drawn_;
  // A new stage is drawn at once: a short stage (a cruise polish after a quick search, the
  // searches of a short journey) is seen, not hidden by the 0.2 s between redraws.
  const bool new_stage =
      std::find(stages_drawn_.begin(), stages_drawn_.end(), stage) == stages_drawn_.end();
  if (new_stage) stages_drawn_.emplace_back(stage);
  if (!last && !first_step && !new_stage &&
      std::chrono::duration<double>(now - last_draw_).count() < kRedrawEvery_s) {
    return;
  }
  first_step_drawn_ = first_step_drawn_ || first_step;
  last_draw_ = now;
  const std::string text =
      line(label_, stage, done, total, std::chrono::duration<double>(now - start_).count());
  // Pad over what a longer previous line left behind.
  const int pad = drawn_width_ > text.size() ? static_cast<int>(drawn_width_ - text.size()) : 0;
  std::fprintf(stderr, "\r%s%*s", text.c_str(), pad, "");
  std::fflush(stderr);
  drawn_width_ = text.size() + static_cast<std::size_t>(pad);
}

dp::ProgressFn Progress::callback() {
  if (!enabled_) return {};
  return [this](const char* stage, int done, int total) { update(stage, done, total); };
}

}  // namespace ecorail::cli
