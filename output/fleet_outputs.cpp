#include "output/fleet_outputs.hpp"

#include <xlsxwriter.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>
#include <stdexcept>
#include <string>

#include "fleet/windowed_classes.hpp"
#include "output/quiet_stderr.hpp"

namespace ecorail::output {

namespace {

constexpr double kJ = 1e-3;

}  // namespace

void write_timetable_csv(std::ostream& out, const FleetTimetable& tt) {
  std::vector<TimetableCsvRow> rows;
  for (std::size_t k = 0; k < tt.departures_s.size(); ++k) {
    const physics::Trip trip = tt.train_trip(k);
    const auto stops = trip.stops();
    for (std::size_t j = 0; j < stops.size(); ++j)
      rows.push_back({k + 1, tt.stations.at(j), stops[j].position_m, stops[j].arrival_s,
                      stops[j].departure_s, stops[j].dwell_s});
  }
  write_timetable_csv(out, rows);
}

void write_timetable_xlsx(const std::filesystem::path& file, const FleetTimetable& tt,
                          const nlohmann::json& energy) {
  lxw_workbook* wb = workbook_new(file.c_str());
  if (wb == nullptr) throw std::runtime_error("cannot create workbook " + file.string());
  lxw_worksheet* ws = workbook_add_worksheet(wb, "timetable");
  lxw_format* bold = workbook_add_format(wb);
  format_set_bold(bold);
  const char* head[] = {"train", "station", "position_m", "arrival_s", "departure_s", "dwell_s"};
  for (int c = 0; c < 6; ++c) worksheet_write_string(ws, 0, c, head[c], bold);
  worksheet_freeze_panes(ws, 1, 0);
  worksheet_set_column(ws, 0, 5, 13, nullptr);
  lxw_row_t row = 1;
  for (std::size_t k = 0; k < tt.departures_s.size(); ++k) {
    const auto stops = tt.train_trip(k).stops();
    for (std::size_t j = 0; j < stops.size(); ++j, ++row) {
      worksheet_write_number(ws, row, 0, static_cast<double>(k + 1), nullptr);
      worksheet_write_string(ws, row, 1, tt.stations.at(j).c_str(), nullptr);
      worksheet_write_number(ws, row, 2, stops[j].position_m, nullptr);
      worksheet_write_number(ws, row, 3, stops[j].arrival_s, nullptr);
      worksheet_write_number(ws, row, 4, stops[j].departure_s, nullptr);
      worksheet_write_number(ws, row, 5, stops[j].dwell_s, nullptr);
    }
  }
  lxw_worksheet* es = workbook_add_worksheet(wb, "energy");
  worksheet_write_string(es, 0, 0, "quantity", bold);
  worksheet_write_string(es, 0, 1, "value", bold);
  worksheet_freeze_panes(es, 1, 0);
  worksheet_set_column(es, 0, 0, 28, nullptr);
  worksheet_set_column(es, 1, 1, 18, nullptr);
  lxw_row_t r = 1;
  for (const auto& [key, value] : energy.items()) {
    if (value.is_number()) {
      worksheet_write_string(es, r, 0, key.c_str(), nullptr);
      worksheet_write_number(es, r++, 1, value.get<double>(), nullptr);
    } else if (value.is_string()) {
      worksheet_write_string(es, r, 0, key.c_str(), nullptr);
      worksheet_write_string(es, r++, 1, value.get<std::string>().c_str(), nullptr);
    }
  }
  lxw_error closed;
  {
    const QuietStderr quiet;  // libxlsxwriter prints its own "[ERROR]" lines; we report once
    closed = workbook_close(wb);
  }
  if (closed != LXW_NO_ERROR)
    throw std::runtime_error("cannot write workbook " + file.string() + ": " +
                             lxw_strerror(closed));
}

nlohmann::json fleet_energy_json(const energy::FleetEvaluation& ev, const fleet::FleetProblem& p) {
  nlohmann::json j;
  j["model"] = ev.model;
  if (!ev.overlap_variant.empty()) j["overlap_variant"] = ev.overlap_variant;
  j["time_step_s"] = ev.time_step_s;
  j["trains"] = p.trains;
  j["substation_energy_kJ"] = ev.total.substation_J() * kJ;
  j["traction_energy_kJ"] = ev.total.traction_J * kJ;
  j["regen_energy_kJ"] = ev.total.regen_J * kJ;
  j["used_regen_kJ"] = ev.total.used_regen_J * kJ;
  j["used_fraction_of_regen"] =
      ev.total.regen_J > 0 ? ev.total.used_regen_J / ev.total.regen_J : 0.0;
  std::vector<int> headways;
  for (std::size_t k = 1; k < ev.departures_s.size(); ++k)
    headways.push_back(ev.departures_s[k] - ev.departures_s[k - 1]);
  j["headways_s"] = headways;
  j["departures_s"] = ev.departures_s;
  if (p.windowed()) {
    // Question 2.2's classes: each headway's class by the clock, and the ranges.
    nlohmann::json windows = nlohmann::json::array(), classes = nlohmann::json::array();
    for (const auto& w : p.peak_windows) windows.push_back({w.from_s, w.to_s});
    for (std::size_t k = 1; k < ev.departures_s.size(); ++k)
      classes.push_back(
          fleet::is_peak_headway(p.peak_windows, ev.departures_s[k - 1], ev.departures_s[k])
              ? "peak"
              : "offpeak");
    j["peak_windows_s"] = windows;
    j["peak_headway_range_s"] = {p.peak_headway_min_s, p.peak_headway_max_s};
    j["offpeak_headway_range_s"] = {p.headway_min_s, p.headway_max_s};
    j["headway_classes"] = classes;
  }
  nlohmann::json trains = nlohmann::json::array();
  for (std::size_t k = 0; k < ev.per_train.size(); ++k) {
    const auto& e = ev.per_train[k];
    trains.push_back({{"train", k + 1},
                      {"departure_s", ev.departures_s[k]},
                      {"traction_energy_kJ", e.traction_J * kJ},
                      {"regen_energy_kJ", e.regen_J * kJ},
                      {"used_regen_kJ", e.used_regen_J * kJ}});
  }
  j["per_train"] = trains;
  if (!ev.per_section.empty()) {
    nlohmann::json sections = nlohmann::json::array();
    for (std::size_t s = 0; s < ev.per_section.size(); ++s) {
      const auto& e = ev.per_section[s];
      sections.push_back({{"section", s + 1},
                          {"traction_energy_kJ", e.traction_J * kJ},
                          {"regen_energy_kJ", e.regen_J * kJ},
                          {"used_regen_kJ", e.used_regen_J * kJ},
                          {"substation_energy_kJ", e.substation_J() * kJ}});
    }
    j["per_section"] = sections;
  }
  return j;
}

void write_train_diagram(const std::filesystem::path& file, PlotFormat format,
                         const FleetTimetable& tt, double from_s, double to_s,
                         const std::string& title) {
  std::ostringstream data;
  // Each train's run sampled every 5 s (and at every stop), hours against km; blank lines
  // separate trains.
  for (std::size_t k = 0; k < tt.departures_s.size(); ++k) {
    const physics::Trip trip = tt.train_trip(k);
    if (trip.arrival_s() < from_s || trip.departure_s() > to_s) continue;
    for (double t = trip.departure_s(); t < trip.arrival_s(); t += 5.0)
      data << t / 3600.0 << ' ' << trip.state_at(t).position_m / 1000.0 << '\n';
    data << trip.arrival_s() / 3600.0 << ' ' << trip.length_m() / 1000.0 << "\n\n";
  }
  std::ostringstream gp;
  gp << gnuplot_terminal(format, 1400, 800) << "set output "
     << gnuplot_quote(std::filesystem::absolute(file).string()) << "\n"
     << "set title " << gnuplot_quote(title) << "\n"
     << "set xlabel " << gnuplot_quote("clock time (h)") << "\n"
     << "set ylabel " << gnuplot_quote("distance from the first station (km)") << "\n"
     << "set xrange [" << from_s / 3600.0 << ":" << to_s / 3600.0 << "]\n"
     << "set yrange [0:" << tt.positions_m.back() / 1000.0 * 1.02 << "]\n"
     << "set grid xtics\nunset key\nset ytics ()\n";
  for (const auto& w : tt.peak_windows)  // peak windows shaded behind the lines
    gp << "set object rect from " << w.from_s / 3600.0 << ", graph 0 to " << w.to_s / 3600.0
       << ", graph 1 fc rgb '#fde0c5' fs solid 1.0 noborder behind\n";
  for (std::size_t j = 0; j < tt.stations.size(); ++j) {
    gp << "set ytics add (" << gnuplot_quote_tic_label(tt.stations[j]) << " "
       << tt.positions_m[j] / 1000.0 << ")\n";
  }
  gp << "set grid ytics\nplot 'diagram.dat' using 1:2 with lines lw 1 lc rgb '#1f77b4'\n";
  run_gnuplot(gp.str(), {{"diagram.dat", data.str()}});
  check_plot_complete(file, format);
}

void write_power_plot(const std::filesystem::path& file, PlotFormat format,
                      const energy::PowerBalance::Trace& trace, const std::string& title) {
  // At most about 3000 points a curve: the bins are averaged in groups (means of means keep
  // the energy), so a long window stays readable and the file small.
  const std::size_t n = trace.traction_W.size();
  const std::size_t group = std::max<std::size_t>(1, n / 3000);
  std::ostringstream data;
  for (std::size_t i = 0; i < n; i += group) {
    const std::size_t end = std::min(n, i + group);
    double tr = 0, rg = 0, us = 0;
    for (std::size_t j = i; j < end; ++j)
      tr += trace.traction_W[j], rg += trace.regen_W[j], us += trace.used_W[j];
    const double c = static_cast<double>(end - i) * 1e6;
    const double t = trace.start_s + 0.5 * static_cast<double>(i + end) * trace.step_s;
    data << t << ' ' << tr / c << ' ' << rg / c << ' ' << us / c << ' ' << (tr - us) / c << '\n';
  }
  std::ostringstream gp;
  gp << gnuplot_terminal(format, 1400, 700) << "set output "
     << gnuplot_quote(std::filesystem::absolute(file).string()) << "\n"
     << "set title " << gnuplot_quote(title) << "\n"
     << "set xlabel " << gnuplot_quote("clock time (s)") << "\n"
     << "set ylabel " << gnuplot_quote("power (MW)") << "\n"
     << "set key outside right\nset grid\n"
     << "plot 'power.dat' using 1:2 with lines lw 1 lc rgb '#d62728' title "
     << gnuplot_quote("traction") << ", '' using 1:3 with lines lw 1 lc rgb '#2ca02c' title "
     << gnuplot_quote("regenerated") << ", '' using 1:4 with lines lw 2 lc rgb '#9467bd' title "
     << gnuplot_quote("used regenerated") << ", '' using 1:5 with lines lw 1 dt 2 lc rgb "
     << "'#000000' title " << gnuplot_quote("substation") << "\n";
  run_gnuplot(gp.str(), {{"power.dat", data.str()}});
  check_plot_complete(file, format);
}

void add_network_json(nlohmann::json& j, const power::NetworkEvaluation& n) {
  nlohmann::json subs = nlohmann::json::array();
  for (const auto& s : n.substations) {
    subs.push_back({{"name", s.name},
                    {"position_m", s.position_m},
                    {"energy_kJ", s.energy_J * kJ},
                    {"peak_power_kW", s.peak_power_W * kJ},
                    {"peak_current_A", s.peak_current_A}});
  }
  j["substations"] = subs;
  j["substation_energy_kJ"] = n.substation_J * kJ;
  j["line_losses_kJ"] = n.line_losses_J * kJ;
  j["traction_input_kJ"] = n.traction_input_J * kJ;
  j["auxiliary_kJ"] = n.auxiliary_J * kJ;
  j["used_regen_kJ"] = n.used_regen_J * kJ;
  j["used_fraction_of_regen"] = n.regen_J > 0 ? n.used_regen_J / n.regen_J : 0.0;
  j["curtailed_regen_kJ"] = n.curtailed_regen_J * kJ;
  j["curtailed_traction_kJ"] = n.curtailed_traction_J * kJ;
  j["min_train_voltage_V"] = n.min_train_voltage_V;
  j["max_train_voltage_V"] = n.max_train_voltage_V;
  j["curtailment"] = {{"instants", n.instants},
                      {"regen_curtailed_instants", n.regen_curtailed_instants},
                      {"traction_curtailed_instants", n.traction_curtailed_instants},
                      {"no_solution_at_full_demand_instants", n.no_solution_instants},
                      {"unsolved_instants", n.unsolved_instants}};
  j["max_balance_error_fraction"] = n.max_balance_error_fraction;
  if (j.contains("per_train") && j["per_train"].size() == n.train_curtailed_regen_J.size()) {
    for (std::size_t k = 0; k < n.train_curtailed_regen_J.size(); ++k) {
      j["per_train"][k]["curtailed_regen_kJ"] = n.train_curtailed_regen_J[k] * kJ;
      j["per_train"][k]["curtailed_traction_kJ"] = n.train_curtailed_traction_J[k] * kJ;
    }
  }
}

void write_substation_plot(const std::filesystem::path& file, PlotFormat format,
                           const power::SubstationTrace& trace, const std::string& title) {
  // As the power plot: at most about 3000 points a curve, bins averaged in groups.
  const std::size_t n = trace.power_W.empty() ? 0 : trace.power_W.front().size();
  const std::size_t group = std::max<std::size_t>(1, n / 3000);
  std::ostringstream data;
  for (std::size_t i = 0; i < n; i += group) {
    const std::size_t end = std::min(n, i + group);
    data << trace.start_s + 0.5 * static_cast<double>(i + end) * trace.step_s;
    for (const auto& series : trace.power_W) {
      double sum = 0.0;
      for (std::size_t j = i; j < end; ++j) sum += series[j];
      data << ' ' << sum / (static_cast<double>(end - i) * 1e6);
    }
    data << '\n';
  }
  std::ostringstream gp;
  gp << gnuplot_terminal(format, 1400, 700) << "set output "
     << gnuplot_quote(std::filesystem::absolute(file).string()) << "\n"
     << "set title " << gnuplot_quote(title) << "\n"
     << "set xlabel " << gnuplot_quote("clock time (s)") << "\n"
     << "set ylabel " << gnuplot_quote("substation output power (MW)") << "\n"
     << "set key outside right\nset grid\nplot ";
  for (std::size_t i = 0; i < trace.names.size(); ++i) {
    gp << (i == 0 ? "'substations.dat'" : ", ''") << " using 1:" << i + 2
       << " with lines lw 1 title " << gnuplot_quote(trace.names[i]);
  }
  gp << "\n";
  run_gnuplot(gp.str(), {{"substations.dat", data.str()}});
  check_plot_complete(file, format);
}

void write_voltage_plot(const std::filesystem::path& file, PlotFormat format,
                        const power::LoadFlowResult& flow, const power::PowerSupply& supply,
                        const std::vector<int>& train_numbers, const std::string& title) {
  std::ostringstream line, subs, trains;
  for (const auto& node : flow.nodes) {
    line << node.position_m / 1000.0 << ' ' << node.voltage_V << '\n';
    if (node.substation >= 0) subs << node.position_m / 1000.0 << ' ' << node.voltage_V << '\n';
    if (node.train >= 0) trains << node.position_m / 1000.0 << ' ' << node.voltage_V << '\n';
  }
  if (flow.nodes.empty()) line << "0 0\n";
  if (subs.str().empty()) subs << "0 NaN\n";
  if (trains.str().empty()) trains << "0 NaN\n";
  std::ostringstream gp;
  gp << gnuplot_terminal(format, 1400, 700) << "set output "
     << gnuplot_quote(std::filesystem::absolute(file).string()) << "\n"
     << "set title " << gnuplot_quote(title) << "\n"
     << "set xlabel " << gnuplot_quote("distance from the first station (km)") << "\n"
     << "set ylabel " << gnuplot_quote("line voltage (V)") << "\n"
     << "set key outside right\nset grid\n";
  for (const auto& node : flow.nodes) {
    if (node.train < 0 || node.train >= static_cast<int>(train_numbers.size())) continue;
    gp << "set label " << gnuplot_quote("train " + std::to_string(train_numbers[node.train] + 1))
       << " at " << node.position_m / 1000.0 << "," << node.voltage_V << " offset 0.5,0.8\n";
  }
  gp << "plot 'line.dat' using 1:2 with lines lw 2 lc rgb '#1f77b4' title "
     << gnuplot_quote("line voltage") << ", 'subs.dat' using 1:2 with points pt 5 ps 1.5 "
     << "lc rgb '#000000' title " << gnuplot_quote("substations")
     << ", 'trains.dat' using 1:2 with points pt 7 ps 1.5 lc rgb '#d62728' title "
     << gnuplot_quote("trains") << ", " << supply.max_train_voltage_V
     << " with lines dt 2 lc rgb '#2ca02c' title " << gnuplot_quote("max train voltage") << ", "
     << supply.min_train_voltage_V << " with lines dt 2 lc rgb '#ff7f0e' title "
     << gnuplot_quote("min train voltage") << "\n";
  run_gnuplot(gp.str(),
              {{"line.dat", line.str()}, {"subs.dat", subs.str()}, {"trains.dat", trains.str()}});
  check_plot_complete(file, format);
}

}  // namespace ecorail::output
