// Example 3: the advisor in a closed loop. Builds the policy table of A6 -> A7 for a 110 s
// timetable with a small lambda ladder (-2, 0, +2 s), saves it, loads it back into an Advisor
// (which checks the line and train checksums), and drives the physics simulator with the advisor
// as its ControlLaw: once with the train the table was made for, once with a train 5 % heavier
// following the nominal layer, and once more with the ladder keeping time. The plant always
// follows its own speed envelope (braking-curve supervision), which is what makes it stop at the
// platform whatever the advice. Exits 1 if a run misses the stop by 1 m or exceeds a limit.
//
//   example_03_advisor_closed_loop [table.bin]   (without a path the table is a temporary file)
#include <cmath>
#include <cstdio>
#include <filesystem>

#include "data/line_loader.hpp"
#include "data/route_builder.hpp"
#include "data/train_io.hpp"
#include "dp/time_target.hpp"
#include "physics/units.hpp"
#include "policy/advisor.hpp"

using namespace ecorail;

namespace {

constexpr double kTimetable_s = 110.0;

// Runs the plant (train + its own envelope) with the advisor in the loop. With time keeping, the
// layer is re-chosen every 10 m as the one whose expected time-to-go best fits the time left.
physics::SimulationResult drive(const policy::Advisor& advisor, const physics::Train& plant_train,
                                const data::Line& line, bool keep_time, bool print) {
  const physics::Route route = data::build_route(line, "A6", "A7", plant_train);
  const physics::SpeedEnvelope envelope(plant_train, route);
  const physics::Motion plant(plant_train, route, envelope);
  double clock_s = 0.0, s_prev = 0.0, v_prev = 0.0, chosen_at = -1e9, next_print = 0.0;
  int layer = advisor.layer();
  const physics::ControlLaw law = [&](double s, double v) {
    if (s > s_prev && v + v_prev > 0.0) clock_s += 2.0 * (s - s_prev) / (v + v_prev);
    s_prev = s;
    v_prev = v;
    if (keep_time && s - chosen_at >= 10.0) {
      layer = advisor.layer_for_time(s, v, kTimetable_s - clock_s);
      chosen_at = s;
    }
    const policy::Advice a = advisor.advise(layer, s, v);
    if (print && s >= next_print) {
      std::printf(
          "  %7.1f m %6.2f km/h t %6.2f s: %-12s %-16s %8.1f kN, expect %6.2f s and "
          "%7.1f kJ to go\n",
          s, units::ms_to_kmh(v), clock_s, std::string(physics::control_name(a.control)).c_str(),
          std::string(physics::regime_name(a.regime)).c_str(), units::N_to_kN(a.force_N),
          a.time_to_go_s, units::J_to_kJ(a.energy_to_go_J));
      next_print += 150.0;
    }
    return a.control;
  };
  return physics::simulate(plant, law, {}, {});
}

bool report(const char* name, const physics::SimulationResult& sim) {
  const double overspeed_kmh = units::ms_to_kmh(std::max(0.0, sim.max_overspeed_ms));
  std::printf(
      "%-34s traction %8.1f kJ, running time %7.3f s (%+.3f s), stop error %+.4f m, "
      "max overspeed %.4f km/h\n",
      name, units::J_to_kJ(sim.energy.traction_work_J), sim.running_time_s,
      sim.running_time_s - kTimetable_s, sim.stop_error_m, overspeed_kmh);
  return std::abs(sim.stop_error_m) < 1.0 && overspeed_kmh < 0.01;
}

}  // namespace

int main(int argc, char** argv) {
  const std::filesystem::path path =
      argc > 1 ? std::filesystem::path(argv[1])
               : std::filesystem::temp_directory_path() / "ecorail_example_03_A6_A7.bin";
  const data::Line line = data::default_line();
  const physics::Train train = data::default_train();

  // 1. The table: engine, lambda for each running time of the ladder, one layer each.
  const physics::Route route = data::build_route(line, "A6", "A7", train);
  const dp::SectionEngine engine(train, route, {});
  policy::PolicyTable table =
      policy::make_policy_table(engine, line.name, line.checksum(), data::train_checksum(train));
  double optimum_kJ = 0.0;
  for (double offset : {-2.0, 0.0, 2.0}) {
    const dp::TimeSearchResult found = dp::solve_for_time(engine, kTimetable_s + offset, {});
    if (offset == 0.0) optimum_kJ = units::J_to_kJ(found.run.sim.energy.traction_work_J);
    policy::PolicyLayer layer = policy::build_policy_layer(engine, found.run.lambda);
    layer.time_offset_s = offset;
    layer.target_time_s = kTimetable_s + offset;
    table.layers.push_back(std::move(layer));
  }
  policy::save_policy(table, path);
  std::printf("policy table %s: %d stages, %d nodes, %zu layers, %ju bytes\n",
              path.string().c_str(), table.stage_count(), table.node_count(), table.layers.size(),
              static_cast<std::uintmax_t>(std::filesystem::file_size(path)));

  // 2. On board: load and check against the line and train in use.
  const policy::Advisor advisor = policy::Advisor::load(path, line, train);
  std::printf("optimal run (solve_for_time): traction %.1f kJ in %.3f s\n", optimum_kJ,
              kTimetable_s);

  // 3. Closed loops.
  bool ok = true;
  std::printf("nominal train, nominal layer (advice every 150 m):\n");
  ok &= report("nominal train", drive(advisor, train, line, false, true));
  physics::Train heavy = train;
  heavy.mass_kg *= 1.05;
  ok &= report("5 % heavier, nominal layer", drive(advisor, heavy, line, false, false));
  ok &= report("5 % heavier, ladder keeping time", drive(advisor, heavy, line, true, false));
  try {
    policy::Advisor wrong = policy::Advisor::load(path, line, heavy);
    ok = false;
  } catch (const policy::PolicyMismatchError& e) {
    std::printf("loading the table for the heavier train is refused: %s\n", e.what());
  }
  if (argc <= 1) std::filesystem::remove(path);  // keep the table only when asked for a path
  return ok ? 0 : 1;
}
