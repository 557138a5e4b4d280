// How a solve ended, the same way for every solver (a section, a journey, a frontier, and the
// many-train solves of timetable/), as Ceres reports it: CONVERGENCE when the result meets every
// target (it comes to rest at its stop and runs in its time, within kStopTolerance_m and
// kTimeTolerance_s), NO_CONVERGENCE when the search ended (budget or bracket) with a result that
// arrives but misses its time, FAILURE when there is no result that arrives at its stop. Only
// CONVERGENCE is usable: a run that misses its stop or its time is never written as a result.
// Each summary that carries a Termination also has IsSolutionUsable(), BriefReport() (one line)
// and FullReport() (problem, search, timing, result, warnings), in kJ, s and km/h.
#pragma once

#include <cstddef>
#include <optional>
#include <string_view>

namespace ecorail::dp {

enum class Termination { CONVERGENCE, NO_CONVERGENCE, FAILURE };

// Names to and from text, in one place: "CONVERGENCE", "NO_CONVERGENCE", "FAILURE".
inline std::string_view termination_name(Termination t) {
  switch (t) {
    case Termination::CONVERGENCE:
      return "CONVERGENCE";
    case Termination::NO_CONVERGENCE:
      return "NO_CONVERGENCE";
    case Termination::FAILURE:
      return "FAILURE";
  }
  return "FAILURE";
}
inline std::optional<Termination> termination_from_name(std::string_view name) {
  for (Termination t :
       {Termination::CONVERGENCE, Termination::NO_CONVERGENCE, Termination::FAILURE}) {
    if (termination_name(t) == name) return t;
  }
  return std::nullopt;
}

inline bool is_usable(Termination t) {
  return t == Termination::CONVERGENCE;
}

// The last word of a BriefReport: CONVERGENCE, WARNINGS (usable, but with warnings such as a
// small overspeed), or the termination when the result is not usable.
inline std::string_view status_word(Termination t, std::size_t warning_count) {
  if (!is_usable(t)) return termination_name(t);
  return warning_count == 0 ? "CONVERGENCE" : "WARNINGS";
}

// The termination of a result from whether it arrives at its stop(s) and meets its time.
inline Termination termination_of(bool arrives, bool time_met) {
  if (!arrives) return Termination::FAILURE;
  return time_met ? Termination::CONVERGENCE : Termination::NO_CONVERGENCE;
}

}  // namespace ecorail::dp
