// Speed plot of a run, drawn by gnuplot as SVG or PNG (chosen by the file name): the driven
// speed coloured by regime (full traction, cruise/limit holding, coast, braking, dwell) over the
// speed limits in the upper panel, the gradient profile in the lower one, against distance or
// time. Stations are marked on the speed axis at 0 km/h and named along the top; dwells are
// shaded in the time view; the title names the objective. The preparation of the data and of
// the script is separate from running gnuplot so that it can be tested without it.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "output/gnuplot.hpp"
#include "output/timeline.hpp"

namespace ecorail::output {

enum class PlotAxis { Distance, Time };

struct SpeedPlotLabels {
  // Departure, intermediate stops..., arrival: one more than the sections of the timeline.
  // Any other count leaves the station marks unnamed.
  std::vector<std::string> stations;
  std::string objective;  // shown under the title when not empty
  PlotAxis x_axis = PlotAxis::Distance;
};

// One plotted point.
struct SpeedPlotRow {
  double x = 0.0;  // m or s from departure
  double speed_kmh = 0.0, limit_kmh = 0.0, gradient_permille = 0.0;
  physics::Regime regime = physics::Regime::Coast;
  bool dwelling = false;
};

// A station on the plot: where the train arrives and departs (equal on the distance axis and
// for the end stations).
struct StationMark {
  std::string name;
  double arrive_x = 0.0, depart_x = 0.0;
};

// The timeline thinned for plotting: a point is dropped only when it is within 0.5 m (distance
// view) or 0.05 s (time view) of the last kept one, changes the speed by less than 0.1 km/h and
// the regime not at all; every standstill and every section's last point is kept.
std::vector<SpeedPlotRow> speed_plot_rows(const Timeline& timeline, PlotAxis axis);
std::vector<StationMark> station_marks(const Timeline& timeline,
                                       const std::vector<std::string>& names, PlotAxis axis);
// Upper end of the speed axis: clear of the highest limit and the highest speed.
double speed_axis_max_kmh(const std::vector<SpeedPlotRow>& rows);
// "#rrggbb" of a regime (dwell: grey).
std::string regime_colour(physics::Regime regime, bool dwelling);
// The gnuplot script; it reads "profile.dat" (speed_plot_data) and writes output_file.
std::string speed_plot_script(const std::vector<SpeedPlotRow>& rows,
                              const std::vector<StationMark>& stations, const std::string& title,
                              const SpeedPlotLabels& labels, PlotFormat format,
                              const std::filesystem::path& output_file);
std::string speed_plot_data(const std::vector<SpeedPlotRow>& rows);

// Draws straight into file (not atomically: file should be a temporary).
void write_speed_plot_file(const std::filesystem::path& file, const Timeline& timeline,
                           const std::string& title, const SpeedPlotLabels& labels,
                           PlotFormat format);
// Atomic; the format follows the name (.svg, .png); other names and a missing gnuplot are
// clear errors.
void write_speed_plot(const std::filesystem::path& path, const Timeline& timeline,
                      const std::string& title, const SpeedPlotLabels& labels);
// Kept for existing callers: the distance view without station names.
void write_speed_plot_svg(const std::filesystem::path& path, const Timeline& timeline,
                          const std::string& title);

}  // namespace ecorail::output
