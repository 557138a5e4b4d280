// The separation check of `ecorail timetable evaluate|optimise` (question 2.2): flags, and the
// step that runs every train of the timetable together with safe separation
// (service/service_simulator.hpp), prints what it found, adds a "separation" block to the
// energy JSON and queues the speed-distance profiles in the command's output batch. cli/ only
// parses and prints; the work is in service/.
#pragma once

#include <CLI/CLI.hpp>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "data/atomic_file.hpp"
#include "dp/section_library.hpp"
#include "fleet/fleet_pattern.hpp"

namespace ecorail::cli {

struct ServiceArgs {
  bool separation = false;
  double train_length_m = 0.0;
  double safety_margin_m = 0.0;
  double braking_m_s2 = 0.0;
  std::string follower = "reoptimise";
  std::string profiles_csv, profile_plot;
  double profile_step_s = 1.0;
  int profile_train = 0;  // 1-based; 0: the train with the least separation margin
  bool wanted() const { return separation || !profiles_csv.empty() || !profile_plot.empty(); }
};

void add_service_options(CLI::App* cmd, ServiceArgs& a);
// Before any work: the output targets can be written, the flags make sense.
void check_service_args(const ServiceArgs& a);

// Whatever the queued outputs need until the batch is committed.
struct ServiceRun;
// Runs the check when asked (else returns nothing): prints the summary and each place where
// the cap binds, adds energy["separation"], queues the profile outputs in batch.
std::shared_ptr<ServiceRun> run_service_check(const ServiceArgs& a,
                                              const dp::SectionLibrary& library,
                                              const fleet::FleetPattern& pattern,
                                              const std::vector<int>& departures_s,
                                              nlohmann::json& energy, data::OutputBatch& batch);

}  // namespace ecorail::cli
