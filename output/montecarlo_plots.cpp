#include "output/montecarlo_plots.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>

#include "output/gnuplot.hpp"

namespace ecorail::output {

namespace {

void draw(const std::filesystem::path& file, const std::string& body, const std::string& data) {
  if (const std::string problem = gnuplot_problem(PlotFormat::Svg); !problem.empty())
    throw std::runtime_error(problem);
  std::ostringstream gp;
  gp << gnuplot_terminal(PlotFormat::Svg, 1000, 600) << "set output "
     << gnuplot_quote(std::filesystem::absolute(file).string()) << "\n"
     << "set grid ytics\nset style fill solid 0.8 border -1\n"
     << body;
  run_gnuplot(gp.str(), {{"plot.dat", data}});
  check_plot_complete(file, PlotFormat::Svg);
}

}  // namespace

void write_lateness_histogram(const std::filesystem::path& file,
                              const std::vector<std::int64_t>& counts, const std::string& title) {
  std::ostringstream data;
  std::size_t last = 0;
  for (std::size_t i = 0; i < counts.size(); ++i)
    if (counts[i] > 0) last = i;
  for (std::size_t i = 0; i <= last && i < counts.size(); ++i)
    data << i + 0.5 << " " << counts[i] << "\n";
  std::ostringstream gp;
  gp << "set title " << gnuplot_quote(title) << "\nset xlabel "
     << gnuplot_quote("arrival lateness (s, 1 s bins; early arrivals count as 0)")
     << "\nset ylabel " << gnuplot_quote("arrivals") << "\nset logscale y\nset boxwidth 1\n"
     << "plot 'plot.dat' using 1:2 with boxes lc rgb '#4477aa' notitle\n";
  draw(file, gp.str(), data.str());
}

void write_energy_histogram(const std::filesystem::path& file, const std::vector<double>& day_kJ,
                            const std::string& title) {
  if (day_kJ.empty()) throw std::invalid_argument("an energy histogram needs days");
  const auto [lo_it, hi_it] = std::minmax_element(day_kJ.begin(), day_kJ.end());
  const double lo = *lo_it / 1e6, hi = *hi_it / 1e6;  // GJ
  const int bins = 30;
  const double width = hi > lo ? (hi - lo) / bins : 1e-3;
  std::vector<long> count(bins, 0);
  for (double v : day_kJ) ++count[std::min(bins - 1, static_cast<int>((v / 1e6 - lo) / width))];
  std::ostringstream data;
  data.precision(10);
  for (int i = 0; i < bins; ++i) data << lo + (i + 0.5) * width << " " << count[i] << "\n";
  std::ostringstream gp;
  gp.precision(10);
  gp << "set title " << gnuplot_quote(title) << "\nset xlabel "
     << gnuplot_quote("substation energy of a day (GJ)") << "\nset ylabel " << gnuplot_quote("days")
     << "\nset boxwidth " << width << "\n"
     << "plot 'plot.dat' using 1:2 with boxes lc rgb '#cc6677' notitle\n";
  draw(file, gp.str(), data.str());
}

void write_punctuality_plot(const std::filesystem::path& file,
                            const std::vector<std::string>& stations,
                            const std::vector<double>& punctuality, const std::string& title) {
  std::ostringstream data, tics;
  data.precision(10);
  for (std::size_t i = 0; i < punctuality.size(); ++i) {
    data << i << " " << 100.0 * punctuality[i] << "\n";
    tics << (i ? ", " : "") << gnuplot_quote_tic_label(i < stations.size() ? stations[i] : "")
         << " " << i;
  }
  double lowest = 100.0;
  for (double p : punctuality) lowest = std::min(lowest, 100.0 * p);
  std::ostringstream gp;
  gp << "set title " << gnuplot_quote(title) << "\nset xlabel " << gnuplot_quote("arrival station")
     << "\nset ylabel " << gnuplot_quote("arrivals within the punctuality threshold (%)")
     << "\nset yrange [" << std::floor(std::max(0.0, lowest - 1.0))
     << ":100]\nset boxwidth 0.7\nset xtics (" << tics.str() << ")\n"
     << "plot 'plot.dat' using 1:2 with boxes lc rgb '#117733' notitle\n";
  draw(file, gp.str(), data.str());
}

}  // namespace ecorail::output
