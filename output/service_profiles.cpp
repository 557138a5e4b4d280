#include "output/service_profiles.hpp"

#include <cmath>
#include <cstdio>
#include <sstream>

namespace ecorail::output {

void write_profiles_csv(std::ostream& out,
                        const std::vector<std::vector<service::ProfilePoint>>& profiles) {
  out << "train,clock_s,position_m,speed_kmh,separation_cap_kmh,line_limit_kmh\n";
  char buf[200];
  for (std::size_t k = 0; k < profiles.size(); ++k)
    for (const service::ProfilePoint& p : profiles[k]) {
      if (std::isfinite(p.cap_ms))
        std::snprintf(buf, sizeof buf, "%zu,%.3f,%.3f,%.4f,%.4f,%.4f\n", k + 1, p.clock_s,
                      p.position_m, 3.6 * p.speed_ms, 3.6 * p.cap_ms, 3.6 * p.limit_ms);
      else
        std::snprintf(buf, sizeof buf, "%zu,%.3f,%.3f,%.4f,,%.4f\n", k + 1, p.clock_s, p.position_m,
                      3.6 * p.speed_ms, 3.6 * p.limit_ms);
      out << buf;
    }
}

void write_profile_plot(const std::filesystem::path& file, PlotFormat format,
                        const std::vector<service::ProfilePoint>& profile,
                        const std::string& title) {
  // Caps far above the line limit are clipped to the plot's top: they never bind there.
  double top = 0.0;
  for (const auto& p : profile) top = std::max(top, 3.6 * p.limit_ms);
  top *= 1.15;
  std::ostringstream data;
  for (const auto& p : profile) {
    const double cap = std::isfinite(p.cap_ms) ? std::min(3.6 * p.cap_ms, top) : top;
    data << p.position_m / 1000.0 << ' ' << 3.6 * p.speed_ms << ' ' << cap << ' '
         << 3.6 * p.limit_ms << '\n';
  }
  std::ostringstream gp;
  gp << gnuplot_terminal(format, 1400, 600) << "set output "
     << gnuplot_quote(std::filesystem::absolute(file).string()) << "\n"
     << "set title " << gnuplot_quote(title) << "\n"
     << "set xlabel " << gnuplot_quote("distance from the first station (km)") << "\n"
     << "set ylabel " << gnuplot_quote("speed (km/h)") << "\n"
     << "set yrange [0:" << top << "]\nset key outside right\nset grid\n"
     << "plot 'profile.dat' using 1:4 with steps lw 1 lc rgb '#7f7f7f' title "
     << gnuplot_quote("line limit") << ", '' using 1:3 with lines lw 1 dt 2 lc rgb '#d62728' title "
     << gnuplot_quote("separation cap sqrt(2 L b)")
     << ", '' using 1:2 with lines lw 2 lc rgb '#1f77b4' title " << gnuplot_quote("speed") << "\n";
  run_gnuplot(gp.str(), {{"profile.dat", data.str()}});
  check_plot_complete(file, format);
}

}  // namespace ecorail::output
