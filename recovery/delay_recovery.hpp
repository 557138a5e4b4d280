// Delay recovery (question 3.1): train i leaves station A_j late by D seconds. It may run the
// later sections faster, down to each section's flat-out time, shorten dwells down to the
// minimum dwell, and may not leave a station before its timetabled departure. The objective is
// lexicographic. First, back on time (arrival no later than planned) at the earliest station:
// that is the first station a flat-out run with minimum dwells reaches in time, since no
// driving reaches any station sooner. Second, the least traction energy over the recovery
// sections: the time left (planned arrival there minus the late departure minus the minimum
// dwells) is split over those sections by the exact convex allocation of recovery/allocation.hpp
// on their energy-time frontiers (one time price; the no-early-departure constraint, which can
// only bind at the last intermediate stop, is enforced exactly by re-allocating with it active),
// and each section is then solved for its new running time and re-simulated. Beside it the seed
// paper's rule: flat out section by section until the delay is gone, the section that closes it
// run in exactly the time that does. A delay no station absorbs is run flat out with minimum
// dwells to the last station and the final lateness reported (recovered = false). Every energy
// and time reported is a forward re-simulation. Followers: the next train's planned run is
// scanned against the late train's actual run under the separation cap (service/separation.hpp);
// when it would come closer than its braking distance the follower is driven behind it, back on
// time by the dynamic programme of service/follower.hpp over a grid of its section runs (waiting
// at a stop where the line ahead is not clear), and checked in turn; the chain stops at the first
// train that is not held up. Lateness first (DelayRecoveryOptions::lateness_first) puts the total
// lateness of the late train and its followers before the energy.
#pragma once

#include <limits>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "base/error.hpp"
#include "dp/progress_callback.hpp"
#include "dp/section_library.hpp"
#include "dp/termination.hpp"
#include "physics/trip.hpp"
#include "recovery/allocation.hpp"
#include "recovery/plan.hpp"
#include "service/service_simulator.hpp"

namespace ecorail::recovery {

inline service::ServiceOptions delay_service_options() {
  service::ServiceOptions o;
  o.mode = service::FollowerMode::Wait;
  return o;
}

// The longest delay recover_delay takes (s): three hours; a longer one is a disruption (the
// plan is recast), not a delay to recover.
inline constexpr double kMaxDelay_s = 10800.0;

struct DelayRecoveryOptions {
  double min_dwell_s = 30.0;           // a stop's dwell never goes below min(this, planned)
  double on_time_tolerance_s = 0.05;   // re-simulated arrival within this of the plan is on time
  double flat_out_threshold_s = 0.02;  // a time this close to the minimum is run flat out
  AllocationOptions allocation;
  bool check_followers = true;
  int max_followers = 5;  // followers simulated at most, behind the late train
  // A held-up follower is driven back on time (service::FollowerRecovery; false: it waits,
  // then runs its plan, faster only where the wait made it late in that section).
  bool recover_followers = true;
  // The runs a held-up follower chooses from on each section: energy-optimal runs for running
  // times from flat out every follower_time_step_s up to follower_slower_s above the planned
  // time (within the frontier), and the planned run.
  double follower_time_step_s = 2.0;
  double follower_slower_s = 10.0;
  // Candidate runs solved lazily, only those a state the follower's programme keeps would drive
  // (service::FollowerRecovery::solve; the same path), one section at a time: less CPU (the
  // worst 600 s delays of bench/delay_worst_case.sh about 17 % less user time) but, on two idle
  // cores, more wall time than solving every candidate up front with sections side by side
  // (largest of 24 cases 11.1 s against 8.9 s), so off by default.
  bool lazy_follower_solves = false;
  // Lateness first: minimise the total arrival lateness of the late train and its followers,
  // then the energy (the late train flat out up to the last section before the station where
  // it is back on time, that section as slow as keeps the total lateness least). false: the
  // late train's earliest station back on time, then its least energy (the exact recovery).
  bool lateness_first = false;
  // Separation (the cap) and how a held-up follower is driven: it waits at the stop, then runs
  // the section faster for the time left (FollowerMode::Wait, delay_service_options()).
  service::ServiceOptions service = delay_service_options();
  // Told "recovery" (the late train; 0 of 1, then 1 of 1) and "follower" (done of
  // max_followers) as the work goes; may be empty.
  dp::ProgressFn progress;
  // The file the plan was read from ("" for a plan made in memory): the context of an error
  // about the plan.
  std::string plan_file;
  // Checks every field; on failure writes one sentence naming the field into *error.
  bool IsValid(std::string* error) const;
};

// Bad input to recover_delay (unknown train, the last station, a negative delay, a plan the
// train cannot run): an ecorail::Error of kind kBadInput whose context names the argument
// (field "train", "station", "delay", "frontier-span" or "plan"; for "plan" also the file,
// DelayRecoveryOptions::plan_file). what() says what was expected.
class DelayInputError : public std::invalid_argument, public Error {
 public:
  DelayInputError(std::string field, const std::string& message, std::string file = {})
      : std::invalid_argument(message),
        Error(ErrorKind::kBadInput, ErrorContext{std::move(file), 0, std::move(field)}) {}
  const std::string& field() const { return context().field; }
};

struct RecoverySection {
  std::size_t index = 0;  // section index in the plan (station index of its start)
  std::string from, to;
  double min_time_s = 0.0;
  double planned_time_s = 0.0, new_time_s = 0.0, rule_time_s = 0.0;        // re-simulated
  double plan_energy_kJ = 0.0, new_energy_kJ = 0.0, rule_energy_kJ = 0.0;  // traction
  double marginal_kJ_per_s = 0.0;  // -dE/dT at the new time, by the frontier (inf: flat out)
  bool flat_out = false;           // new run is the flat-out run
  double planned_arrival_s = 0.0, new_arrival_s = 0.0;
  double planned_dwell_s = 0.0, new_dwell_s = 0.0;  // at the arrival stop (0 at the last)
  double new_departure_s = 0.0;                     // from the section's first stop
};

// One train after the delay: where it is back on time.
struct AffectedTrain {
  int train = 0;                   // 0-based
  bool never_late = false;         // held up, but never late by more than the tolerance
  std::string back_on_time_at;     // "" when not back on time by the last station
  double max_lateness_s = 0.0;     // largest arrival lateness over its stops
  double final_lateness_s = 0.0;   // at the station where it is back on time, or the last
  std::vector<double> lateness_s;  // arrival lateness per station (0 at the first)
};

struct FollowerCheck {
  int train = 0;  // 0-based
  int behind = 0;
  bool affected = false;  // its planned run would exceed the cap behind the train ahead
  // Its planned run behind the train ahead's actual run (cap - v, least; negative: exceeded).
  double planned_run_margin_kmh = 0.0;
  // Its planned run behind the train ahead's planned run (the plan's own margin).
  double plan_margin_kmh = 0.0;
  // Its actual run (the planned one when not affected) behind the train ahead's actual run.
  double min_speed_margin_kmh = 0.0;
  double min_distance_margin_m = 0.0;  // gap less the braking distance, least
  double min_gap_m = 0.0;
  double station_wait_s = 0.0;    // waited at stops for the line ahead to clear, in total
  double headway_s = 0.0;         // its planned departure after the train ahead's
  double traction_kJ = 0.0;       // its actual run over the whole line, re-simulated
  double plan_traction_kJ = 0.0;  // its planned run
  double lateness_sum_s = 0.0;    // sum over its arrivals of the lateness (0 when on time)
};

struct DelayRecoverySummary {
  dp::Termination termination = dp::Termination::FAILURE;
  int train = 0;
  std::string station;
  double delay_s = 0.0;
  bool recovered = false;
  std::string back_on_time_at;  // "" : not recovered
  double final_lateness_s = 0.0;
  int sections = 0;
  double recovery_energy_kJ = 0.0, plan_energy_kJ = 0.0, rule_energy_kJ = 0.0;
  int followers_checked = 0, followers_affected = 0;
  double min_follower_margin_kmh = 0.0;  // NaN when no follower
  // The knock-on cascade: the followers held up in a row behind the late train, whether it
  // ends within the followers driven (false: the last one driven was still held up), the
  // lateness of its last train at the last station, and whether the plan absorbs it (false: a
  // follower waits at its stops longer than its headway behind the train ahead).
  int cascade_trains = 0;
  bool cascade_ends = true;
  double cascade_final_lateness_s = 0.0;
  bool plan_absorbs = true;
  // "energy-first" (the exact recovery) or "lateness-first"; the sum over the late train and
  // its held-up followers of their arrival lateness at every stop; in lateness-first mode the
  // energy-first recovery's traction and total lateness beside it (NaN otherwise).
  std::string recovery_mode = "energy-first";
  double total_lateness_s = 0.0;
  double energy_first_energy_kJ = std::numeric_limits<double>::quiet_NaN();
  double energy_first_total_lateness_s = std::numeric_limits<double>::quiet_NaN();
  double wall_s = 0.0;
  std::vector<std::string> warnings;

  std::string BriefReport() const;
  std::string FullReport() const;
  bool IsSolutionUsable() const { return dp::is_usable(termination); }
};

struct DelayRecoveryResult {
  std::vector<RecoverySection> sections;  // from the late departure to the recovery station
  AllocationSummary allocation;           // empty when no allocation was needed
  std::vector<AffectedTrain> trains;      // the late train first, then held-up followers
  std::vector<FollowerCheck> followers;
  // The whole-line actual runs of the trains in `trains`, in the same order (empty when no
  // follower was checked).
  std::vector<physics::Trip> train_trips;
  physics::Trip recovery_trip;  // the late train over the recovery sections, on the clock
  physics::Trip rule_trip;      // the rule's run over the same sections
  physics::Trip planned_trip;   // the plan over the same sections
  DelayRecoverySummary summary;
};

// train: 0-based index into plan.trains; station: index of the late departure (not the last).
// The library holds the plan's sections in order (library.size() == plan.sections()); store
// (may be null) keeps frontiers between runs. DelayInputError for bad input; std::runtime_error
// when a section cannot be solved for its time (never a result that misses its time).
DelayRecoveryResult recover_delay(const dp::SectionLibrary& library, const Plan& plan,
                                  std::size_t train, std::size_t station, double delay_s,
                                  const DelayRecoveryOptions& options,
                                  dp::FrontierStore* store = nullptr);

}  // namespace ecorail::recovery
