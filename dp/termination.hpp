// How a solve ended, the same way for every solver (a section, a journey, a frontier, and the
// many-train solves of fleet/), as Ceres reports it: CONVERGENCE when the result meets every
// target (it comes to rest at its stop and runs in its time, within kStopTolerance_m and
// kTimeTolerance_s), NO_CONVERGENCE when the search ended (budget or bracket) before it met
// every target, FAILURE when there is no result at all (no run that arrives at its stop, no
// timetable the model could price).
//
// Usable, one rule for every summary's IsSolutionUsable(): a result is usable when it keeps
// every constraint of its problem (each stop within kStopTolerance_m, each running time within
// kTimeTolerance_s, the fleet's headway and trip-time limits); only a usable result is written
// and the program exits 0 with it. FAILURE is never usable, CONVERGENCE always. NO_CONVERGENCE
// is usable where the solver's budget stop keeps every constraint, as Ceres's
// IsSolutionUsable (anything but FAILURE): a fleet search stopped by its time or move budget
// holds a timetable within every limit and states its proven gap. A single-train time search
// has no such stop: its NO_CONVERGENCE is a run that arrives but misses its time, a broken
// constraint, so it is not usable. is_usable() below is that rule in code.
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

// The rule above: budget_stop_keeps_constraints is true for a solver whose NO_CONVERGENCE
// still keeps every constraint (a fleet search stopped by its budget), false for one whose
// NO_CONVERGENCE misses a target (the single-train time searches).
inline bool is_usable(Termination t, bool budget_stop_keeps_constraints = false) {
  return t == Termination::CONVERGENCE ||
         (budget_stop_keeps_constraints && t == Termination::NO_CONVERGENCE);
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
