// Progress of a long computation, reported to whoever asked for it: the library calls a
// ProgressFn (stage, done, total) as work completes and never prints. total is 0 when the amount
// of work is not known in advance (a running-time search stops when it meets its time). The
// program turns these calls into a progress line on a terminal (cli/progress_line.hpp). A
// ProgressFn may be called from several threads at once; it must be thread-safe.
#pragma once

#include <functional>

namespace ecorail::dp {

using ProgressFn = std::function<void(const char* stage, int done, int total)>;

// Calls fn if it is set.
inline void report_progress(const ProgressFn& fn, const char* stage, int done, int total) {
  if (fn) fn(stage, done, total);
}

}  // namespace ecorail::dp
