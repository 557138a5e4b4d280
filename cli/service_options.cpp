#include "cli/service_options.hpp"

#include <cmath>
#include <cstdio>

#include "cli/errors.hpp"
#include "cli/output_options.hpp"
#include "data/csv_reader.hpp"
#include "data/input_error.hpp"
#include "output/separation_json.hpp"
#include "output/service_profiles.hpp"
#include "service/pattern_service.hpp"
#include "service/profiles.hpp"
#include "service/service_simulator.hpp"

namespace ecorail::cli {

struct ServiceRun {
  service::ServiceResult result;
  std::vector<std::vector<service::ProfilePoint>> profiles;
  std::vector<service::ProfilePoint> chosen;
  int chosen_train = 0;
};

namespace {

service::ServiceOptions service_options(const ServiceArgs& a) {
  service::ServiceOptions o;
  o.separation.train_length_m = a.train_length_m;
  o.separation.safety_margin_m = a.safety_margin_m;
  o.separation.braking_m_s2 = a.braking_m_s2;
  const auto mode = service::follower_mode_from_name(a.follower);
  if (!mode) bad("--follower", "supervise, reoptimise or wait; got '" + a.follower + "'");
  o.mode = *mode;
  std::string why;
  if (!o.IsValid(&why))
    throw_on_flag(why, {{"train_length_m", "--train-length"},
                        {"safety_margin_m", "--safety-margin"},
                        {"braking_m_s2", "--braking"}});
  return o;
}

}  // namespace

void add_service_options(CLI::App* cmd, ServiceArgs& a) {
  cmd->add_flag("--separation", a.separation,
                "simulate every train together with safe separation v <= sqrt(2 L b)");
  cmd->add_option("--train-length", a.train_length_m, "train length for the separation (m)")
      ->capture_default_str();
  cmd->add_option("--safety-margin", a.safety_margin_m, "separation safety margin (m)")
      ->capture_default_str();
  cmd->add_option("--braking", a.braking_m_s2,
                  "separation braking b (m/s^2; 0: max braking force at 10 km/h / mass)")
      ->capture_default_str();
  cmd->add_option("--follower", a.follower,
                  "where waiting at the stop would make a follower late: reoptimise "
                  "(energy-optimal under the cap), supervise (planned control, braked) or wait "
                  "(wait, then the run for the time left)")
      ->capture_default_str();
  cmd->add_option("--profiles", a.profiles_csv,
                  "every train's speed-distance profile, long format (CSV)");
  cmd->add_option("--profile-step", a.profile_step_s, "time step of the profiles (s)")
      ->capture_default_str();
  cmd->add_option("--profile-plot", a.profile_plot,
                  "one train's speed-distance profile with its separation cap (.svg or .png)");
  cmd->add_option("--profile-train", a.profile_train,
                  "train of --profile-plot (1-based; 0: the least separation margin)")
      ->capture_default_str();
}

void check_service_args(const ServiceArgs& a) {
  service_options(a);
  if (!(a.profile_step_s >= 0.01 && a.profile_step_s <= 60.0))
    bad("--profile-step", "0.01 to 60 s; got " + data::format_number(a.profile_step_s));
  if (a.profile_train < 0) bad("--profile-train", "a train number >= 1 (0: the least margin)");
  check_output_targets(
      {{"--profiles", a.profiles_csv, false}, {"--profile-plot", a.profile_plot, true}});
}

std::shared_ptr<ServiceRun> run_service_check(const ServiceArgs& a,
                                              const dp::SectionLibrary& library,
                                              const fleet::FleetPattern& pattern,
                                              const std::vector<int>& departures_s,
                                              nlohmann::json& energy, data::OutputBatch& batch) {
  if (!a.wanted()) return nullptr;
  const service::ServiceOptions o = service_options(a);
  if (a.profile_train > static_cast<int>(departures_s.size()))
    bad("--profile-train", "a train of the timetable, 1 to " + std::to_string(departures_s.size()));
  auto run = std::make_shared<ServiceRun>();
  const std::vector<double> departures(departures_s.begin(), departures_s.end());
  run->result = service::simulate_service(
      library, service::plan_from_running_times(library, pattern.running_times_s, pattern.dwells_s),
      departures, o);
  const service::ServiceResult& r = run->result;
  const service::ServiceSummary& sm = r.summary;
  std::printf("separation (b = %.4g m/s^2, train length %.0f m, margin %.0f m): %s\n",
              r.braking_m_s2, a.train_length_m, a.safety_margin_m, sm.BriefReport().c_str());
  for (std::size_t k = 0; k < r.planned_binding.size(); ++k)
    for (const auto& c : r.planned_binding[k])
      std::printf("  cap binds: train %zu, %.0f-%.0f s, %.0f-%.0f m, worst margin %.2f km/h\n",
                  k + 1, c.from_s, c.to_s, c.from_m, c.to_m, c.worst_margin_kmh);
  energy["separation"] = output::separation_json(r, o);
  if (!energy["separation"]["cap_binds_at_plan"].get<bool>())
    std::printf("  the cap never binds at the planned timetable\n");
  for (const auto& e : r.events)
    std::printf(
        "  train %d section %d: %s (waits %.2f s at the stop, arrives %.2f s late); planned %.1f "
        "kJ, braked by the cap %.1f kJ (%.2f s late)%s\n",
        e.train + 1, e.section + 1, e.driven.c_str(), e.station_wait_s, e.late_s,
        e.planned_cost_J / 1e3, e.supervised_cost_J / 1e3, e.supervised_late_s,
        std::isfinite(e.reoptimised_cost_J)
            ? (", re-optimised " + data::format_number(e.reoptimised_cost_J / 1e3) + " kJ (" +
               data::format_number(e.reoptimised_late_s) + " s late)")
                  .c_str()
            : "");
  if (sm.cap_exceeded)
    throw std::runtime_error("a simulated train exceeds the separation cap: " + sm.BriefReport());
  if (!a.profiles_csv.empty()) {
    for (std::size_t k = 0; k < r.trips.size(); ++k)
      run->profiles.push_back(
          service::speed_profile(r.trips, k, r.braking_m_s2, o.separation, a.profile_step_s));
    batch.add(a.profiles_csv,
              [run](std::ostream& out) { output::write_profiles_csv(out, run->profiles); });
  }
  if (!a.profile_plot.empty()) {
    run->chosen_train =
        a.profile_train > 0 ? a.profile_train - 1 : std::max(0, sm.min_margin_train);
    run->chosen = service::speed_profile(r.trips, run->chosen_train, r.braking_m_s2, o.separation,
                                         std::min(a.profile_step_s, 0.5));
    const auto format = *output::plot_format_for(a.profile_plot);
    batch.add_produced(a.profile_plot, [run, format](const std::filesystem::path& f) {
      output::write_profile_plot(f, format, run->chosen,
                                 "Train " + std::to_string(run->chosen_train + 1) +
                                     ": speed, separation cap and line limit");
    });
  }
  return run;
}

}  // namespace ecorail::cli
