#include "output/speed_plot.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>
#include <stdexcept>

#include "data/atomic_file.hpp"
#include "physics/units.hpp"

namespace ecorail::output {

namespace {

struct RegimeStyle {
  physics::Regime regime;
  bool dwelling;
  const char* colour;
  const char* label;
};

// Warm colours for traction, blue for coasting, greens for braking, grey for standing.
constexpr RegimeStyle kRegimeStyles[] = {
    {physics::Regime::FullTraction, false, "#d62728", "full traction"},
    {physics::Regime::PartialTraction, false, "#ff7f0e",
     "speed hold (cruise, limit), partial traction"},
    {physics::Regime::Coast, false, "#1f77b4", "coast"},
    {physics::Regime::PartialBrake, false, "#8fd175", "partial brake"},
    {physics::Regime::FullBrake, false, "#2ca02c", "full brake"},
    {physics::Regime::Coast, true, "#7f7f7f", "dwell"},
};

double x_of(const TimelinePoint& p, PlotAxis axis) {
  return axis == PlotAxis::Time ? p.t_s : p.s_m;
}

}  // namespace

std::string regime_colour(physics::Regime regime, bool dwelling) {
  for (const auto& s : kRegimeStyles) {
    if (s.dwelling == dwelling && (dwelling || s.regime == regime)) return s.colour;
  }
  return "#000000";
}

std::vector<SpeedPlotRow> speed_plot_rows(const Timeline& timeline, PlotAxis axis) {
  const double min_dx = axis == PlotAxis::Time ? 0.05 : 0.5;
  const double min_dv_kmh = 0.1;
  std::vector<SpeedPlotRow> rows;
  for (std::size_t i = 0; i < timeline.size(); ++i) {
    const TimelinePoint& p = timeline[i];
    const bool section_end = i + 1 == timeline.size() || timeline[i + 1].section != p.section;
    SpeedPlotRow r{x_of(p, axis),
                   units::ms_to_kmh(p.v_ms),
                   units::ms_to_kmh(p.speed_limit_ms),
                   p.gradient_permille,
                   p.regime,
                   p.dwelling};
    if (!rows.empty() && !section_end && p.v_ms > 0.0 && !p.dwelling) {
      const SpeedPlotRow& last = rows.back();
      if (r.x - last.x < min_dx && std::abs(r.speed_kmh - last.speed_kmh) < min_dv_kmh &&
          r.regime == last.regime && !last.dwelling) {
        continue;
      }
    }
    rows.push_back(r);
  }
  return rows;
}

std::vector<StationMark> station_marks(const Timeline& timeline,
                                       const std::vector<std::string>& names, PlotAxis axis) {
  std::vector<StationMark> marks;
  if (timeline.empty()) return marks;
  marks.push_back({"", x_of(timeline.front(), axis), x_of(timeline.front(), axis)});
  for (std::size_t i = 0; i < timeline.size(); ++i) {
    const TimelinePoint& p = timeline[i];
    const bool last_of_section = i + 1 == timeline.size() || timeline[i + 1].section != p.section;
    if (!p.dwelling && (last_of_section || (i + 1 < timeline.size() && timeline[i + 1].dwelling))) {
      marks.push_back({"", x_of(p, axis), x_of(p, axis)});  // arrival
    }
    if (p.dwelling) marks.back().depart_x = x_of(p, axis);
  }
  if (names.size() == marks.size()) {
    for (std::size_t i = 0; i < marks.size(); ++i) marks[i].name = names[i];
  }
  return marks;
}

double speed_axis_max_kmh(const std::vector<SpeedPlotRow>& rows) {
  double top = 0.0;
  for (const auto& r : rows) top = std::max({top, r.speed_kmh, r.limit_kmh});
  // 15 % headroom, rounded up to 10 km/h: the highest limit never lies on the frame.
  return std::max(10.0, std::ceil(top * 1.15 / 10.0) * 10.0);
}

std::string speed_plot_data(const std::vector<SpeedPlotRow>& rows) {
  std::string out = "# x speed_kmh limit_kmh gradient_permille regime_rgb\n";
  char buf[160];
  for (const auto& r : rows) {
    const unsigned rgb = static_cast<unsigned>(
        std::stoul(regime_colour(r.regime, r.dwelling).substr(1), nullptr, 16));
    std::snprintf(buf, sizeof buf, "%.3f %.4f %.4f %.3f %u\n", r.x, r.speed_kmh, r.limit_kmh,
                  r.gradient_permille, rgb);
    out += buf;
  }
  return out;
}

std::string speed_plot_script(const std::vector<SpeedPlotRow>& rows,
                              const std::vector<StationMark>& stations, const std::string& title,
                              const SpeedPlotLabels& labels, PlotFormat format,
                              const std::filesystem::path& output_file) {
  const bool time_axis = labels.x_axis == PlotAxis::Time;
  std::ostringstream gp;
  gp.precision(10);
  gp << gnuplot_terminal(format, 1100, 750) << "set output " << gnuplot_quote(output_file.string())
     << "\n";
  std::string full_title = title;
  if (!labels.objective.empty()) full_title += "\nobjective: " + labels.objective;
  gp << "set multiplot title " << gnuplot_quote(full_title) << "\n"
     << "set lmargin at screen 0.08\nset rmargin at screen 0.74\nset grid xtics ytics\n";
  const double x_lo = rows.empty() ? 0.0 : rows.front().x;
  const double x_hi = rows.empty() ? 1.0 : std::max(rows.back().x, x_lo + 1.0);
  gp << "set xrange [" << x_lo << ":" << x_hi << "]\n";
  // Stations: a dotted line through both panels, dwells shaded, names along the top.
  std::string tics;
  for (const auto& st : stations) {
    gp << "set arrow from " << st.arrive_x << ", graph 0 to " << st.arrive_x
       << ", graph 1 nohead lc rgb '#555555' dt 3 back\n";
    if (st.depart_x > st.arrive_x) {
      gp << "set arrow from " << st.depart_x << ", graph 0 to " << st.depart_x
         << ", graph 1 nohead lc rgb '#555555' dt 3 back\n"
         << "set object rect from " << st.arrive_x << ", graph 0 to " << st.depart_x
         << ", graph 1 fc rgb '#ececec' fs solid 1.0 noborder behind\n";
    }
    if (!st.name.empty()) {
      tics += (tics.empty() ? "" : ", ") + gnuplot_quote_tic_label(st.name) + " " +
              std::to_string(0.5 * (st.arrive_x + st.depart_x));
    }
  }
  if (!tics.empty()) gp << "set link x2\nset x2tics (" << tics << ") out nomirror\n";
  gp << "set xtics nomirror\n";
  // Upper panel: speed by regime over the limits; station marks at standstill.
  // The key sits in the right margin: a key placed "at" a screen position is silently dropped
  // by gnuplot when it does not fit the canvas from there.
  gp << "set size 1,0.64\nset origin 0,0.30\nset key outside right top\n"
     << "set ylabel " << gnuplot_quote("speed (km/h)")
     << "\nset yrange [0:" << speed_axis_max_kmh(rows) << "]\n"
     << "set format x ''\n";
  gp << "$stations << EOD\n";
  for (const auto& st : stations) gp << st.arrive_x << " 0\n";
  gp << "EOD\n";
  gp << "plot 'profile.dat' using 1:3 with steps lw 1.5 dt 2 lc rgb '#000000' title "
     << gnuplot_quote("speed limit")
     << ", 'profile.dat' using 1:2:5 with lines lw 2.5 lc rgb variable notitle";
  for (const auto& s : kRegimeStyles) {
    gp << ", NaN with lines lw 2.5 lc rgb '" << s.colour << "' title " << gnuplot_quote(s.label);
  }
  gp << ", $stations using 1:2 with points pt 7 ps 1.2 lc rgb '#000000' title "
     << gnuplot_quote("station") << "\n";
  // Lower panel: gradient.
  gp << "unset x2tics\nunset title\nset size 1,0.30\nset origin 0,0.0\nset format x '%g'\n"
     << "set autoscale y\nset key outside right top\n"
     << "set xlabel "
     << gnuplot_quote(time_axis ? "time from departure (s)" : "distance from departure (m)")
     << "\nset ylabel " << gnuplot_quote("gradient (per mille)") << "\n"
     << "plot 'profile.dat' using 1:4 with steps lw 1.5 lc rgb '#555555' title "
     << gnuplot_quote("gradient (+ = uphill)") << "\nunset multiplot\n";
  return gp.str();
}

void write_speed_plot_file(const std::filesystem::path& file, const Timeline& timeline,
                           const std::string& title, const SpeedPlotLabels& labels,
                           PlotFormat format) {
  if (const std::string problem = gnuplot_problem(format); !problem.empty()) {
    throw std::runtime_error(problem);
  }
  const auto rows = speed_plot_rows(timeline, labels.x_axis);
  const auto marks = station_marks(timeline, labels.stations, labels.x_axis);
  run_gnuplot(
      speed_plot_script(rows, marks, title, labels, format, std::filesystem::absolute(file)),
      {{"profile.dat", speed_plot_data(rows)}});
  check_plot_complete(file, format);
}

void write_speed_plot(const std::filesystem::path& path, const Timeline& timeline,
                      const std::string& title, const SpeedPlotLabels& labels) {
  const auto format = plot_format_for(path);
  if (!format) {
    throw std::runtime_error("cannot write " + path.string() +
                             ": a plot file name ends in .svg or .png");
  }
  data::produce_atomically(path, [&](const std::filesystem::path& tmp) {
    write_speed_plot_file(tmp, timeline, title, labels, *format);
  });
}

void write_speed_plot_svg(const std::filesystem::path& path, const Timeline& timeline,
                          const std::string& title) {
  write_speed_plot(path, timeline, title, {});
}

}  // namespace ecorail::output
