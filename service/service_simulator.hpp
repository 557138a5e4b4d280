// Many trains on one line, simulated together (question 2.2). Every train departs at its
// timetabled time and is driven by its planned control (each section's energy-optimal control
// program and the planned dwells), in clock order, while the simulator supervises the moving
// cap v <= sqrt(2 L b) behind the train ahead's *actual* run (separation.hpp; v_line is the
// speed envelope). A train whose planned run stays under that cap at every sample is exactly
// its planned run (the supervisor acts only when a step would end above the cap), so only the
// trains where it would bind are simulated again. For those, two answers are given: the
// planned control braked by the supervisor (and, once slowed below the planned speed, full
// traction where the plan coasts or holds, so a train the cap stopped drives on), and (by default)
// the section re-optimised: the energy-optimal run under the time-dependent cap for the running
// time left to the planned arrival (dp/capped_section.hpp: a forward DP whose state carries clock
// time, waiting at the platform included, then the fine re-simulation under the same cap). A late
// arrival is carried on: the next departure is the planned one or the arrival plus the planned
// dwell, whichever is later. The result gives every train's actual run as a physics::Trip (so the
// energy models, timetables and plots read it like a planned one), the minimum separation margin
// over all trains and times, and each place where the cap binds. The delay and Monte Carlo work
// builds on the same entry point with departures and plans of its own.
#pragma once

#include <string>
#include <vector>

#include "dp/capped_section.hpp"
#include "dp/journey.hpp"
#include "dp/progress_callback.hpp"
#include "dp/section_library.hpp"
#include "dp/termination.hpp"
#include "physics/trip.hpp"
#include "service/separation.hpp"

namespace ecorail::service {

// What every train is told to do: a control program per section and a dwell per intermediate
// stop; trip is that plan simulated, departing at 0.
struct ServicePlan {
  std::vector<physics::ControlProgram> programs;
  std::vector<double> dwells_s;
  std::vector<physics::SimulationResult> runs;  // each program simulated from rest
  physics::Trip trip;
};

// The plan of a pattern: the energy-optimal split of trip_time_s - sum(dwells) over the
// sections (the fleet's default pattern, fleet/fleet_pattern.hpp, solved the same way).
ServicePlan optimal_split_plan(const dp::SectionLibrary& library,
                               const std::vector<double>& dwells_s, double trip_time_s,
                               const dp::JourneyOptions& options);
// The plan of given programs with their runs already simulated (each run the program's on its
// section; not checked).
ServicePlan plan_from_runs(const dp::SectionLibrary& library,
                           std::vector<physics::ControlProgram> programs,
                           std::vector<physics::SimulationResult> runs,
                           std::vector<double> dwells_s);
// The plan of given programs (each simulated on its section).
ServicePlan plan_from_programs(const dp::SectionLibrary& library,
                               std::vector<physics::ControlProgram> programs,
                               std::vector<double> dwells_s);

// How a held-up follower drives a section where waiting at the stop would make it late:
// Supervised: its planned control braked by the supervisor; Reoptimised: the capped DP; Wait:
// it only waits at the stop and then runs the section library's run for the time left (no
// drive under the cap: what the delay and Monte Carlo commands use, a DP costs seconds).
enum class FollowerMode { Supervised, Reoptimised, Wait };

struct ServiceOptions {
  SeparationOptions separation;
  FollowerMode mode = FollowerMode::Reoptimised;
  dp::CappedSectionOptions capped;
  double resim_step_m = 0.05;
  // A held-up follower leaves earlier and drives under the cap (the capped DP, or the
  // supervisor) only when that could bring its arrival forward by more than this (s) against
  // waiting at the stop: the DP costs seconds a section.
  double redrive_gain_s = 0.05;
  // Called after each train ("service", trains done, trains): a long service shows its
  // progress, and a caller may stop it by throwing from here.
  dp::ProgressFn progress;
  bool IsValid(std::string* error) const;
};

// One section of one train where the cap bound its planned control.
struct CapEvent {
  int train = 0;                    // 0-based, in departure order
  int section = 0;                  // 0-based
  CapStretch first_binding;         // where the planned control first met the cap
  double planned_cost_J = 0.0;      // the planned run, alone on the line
  double supervised_cost_J = 0.0;   // planned control braked by the supervisor
  double supervised_late_s = 0.0;   // its arrival after the planned arrival
  double reoptimised_cost_J = 0.0;  // NaN in supervised mode
  double reoptimised_late_s = 0.0;
  double reoptimised_wait_s = 0.0;  // of that, waiting at the platform
  std::string report;               // the capped DP's brief report
  // What the follower did (service/follower.hpp): the wait at the stop that keeps its planned
  // run clear of the train ahead, the lateness that wait gives, how the section was driven
  // ("waited": the wait, then the planned run; "waited, then faster": the wait, then the
  // section library's run for the time left; "reoptimised" or "supervised": leaving earlier
  // under the cap; "recovered" or "waited, then recovered": the run a FollowerRecovery chose,
  // its energy in reoptimised_cost_J) and its arrival's lateness.
  double station_wait_s = 0.0;
  double waited_late_s = 0.0;
  std::string driven = "waited";
  double late_s = 0.0;
  bool faster_tried = false;  // a faster run for the time left after the wait was tried
};

struct ServiceSummary {
  int trains = 0;
  int trains_resimulated = 0;
  double min_speed_margin_kmh = 1e300;  // over all trains and times, the final runs
  double min_distance_margin_m = 1e300;
  double min_gap_m = 1e300;
  int min_margin_train = -1;
  double min_margin_at_s = 0.0, min_margin_at_m = 0.0;
  bool cap_exceeded = false;  // a final run above the cap anywhere (never expected)
  double max_late_s = 0.0;    // latest arrival at a stop after the plan
  // CONVERGENCE when every final run keeps the cap and never closes on the train ahead
  // (min_gap_m >= 0); FAILURE otherwise, which no result may pass for a timetable.
  dp::Termination termination = dp::Termination::FAILURE;
  std::string BriefReport() const;
  // The termination, then the brief report.
  std::string FullReport() const;
};

struct ServiceResult {
  std::vector<physics::Trip> trips;  // actual runs, on the clock
  // Where the planned runs (before any re-simulation) met the cap: one entry per train
  // and stretch, and per section re-simulated an event.
  std::vector<std::vector<CapStretch>> planned_binding;
  std::vector<CapEvent> events;
  ServiceSummary summary;
  double braking_m_s2 = 0.0;  // b used
};

// The planned control of one section under a moving cap, as the supervisor drives it: the
// cap brakes the train where it would end a step above it, and a train the cap has slowed (or
// held at rest) drives on with full traction wherever its planned control would coast or hold
// below the planned speed at that place (by more than 0.5 m/s), as a driver catches up with
// the plan (a planned coast alone would never restart a train the cap stopped). planned is the
// program's own run without the cap.
physics::SimulationResult drive_planned(const dp::SectionEngine& engine,
                                        const physics::ControlProgram& program,
                                        const physics::SimulationResult& planned,
                                        const physics::SpeedCap& cap, double start_clock_s,
                                        double step_m);

ServiceResult simulate_service(const dp::SectionLibrary& library, const ServicePlan& plan,
                               const std::vector<double>& departures_s,
                               const ServiceOptions& options);

// One train behind a given whole-line leader trip: the actual run of a train planned to depart
// at departure_s (service/follower.hpp's drive_follower, its trip only). events receives the
// sections where the planned run would have come too close.
physics::Trip run_follower(const dp::SectionLibrary& library, const ServicePlan& plan,
                           const physics::Trip& leader, double departure_s,
                           const ServiceOptions& options, double braking_m_s2, int train,
                           std::vector<CapEvent>* events);

}  // namespace ecorail::service
