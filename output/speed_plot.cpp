#include "output/speed_plot.hpp"

#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include <unistd.h>

#include "data/atomic_file.hpp"
#include "physics/units.hpp"

namespace ecorail::output {

namespace {

std::string quote_for_gnuplot(const std::string& s) {
  std::string out;
  for (char c : s) {
    if (c == '\'')
      out += "''";
    else
      out += c;
  }
  return "'" + out + "'";
}

}  // namespace

void write_speed_plot_svg(const std::filesystem::path& path, const Timeline& timeline,
                          const std::string& title) {
  if (std::system("command -v gnuplot >/dev/null 2>&1") != 0) {
    throw std::runtime_error("cannot write " + path.string() +
                             ": gnuplot is not installed (apt-get install gnuplot-nox)");
  }
  const auto dir =
      std::filesystem::temp_directory_path() / ("ecorail-plot-" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  const auto data_file = dir / "profile.dat";
  const auto script_file = dir / "plot.gp";
  const auto log_file = dir / "gnuplot.log";
  {
    std::ofstream data(data_file);
    double last_s = -1.0;
    for (const auto& p : timeline) {
      if (p.s_m - last_s < 0.5 && &p != &timeline.back()) continue;  // 0.5 m is plenty for a plot
      last_s = p.s_m;
      data << p.s_m << ' ' << units::ms_to_kmh(p.v_ms) << ' ' << units::ms_to_kmh(p.speed_limit_ms)
           << ' ' << p.gradient_permille << '\n';
    }
  }
  try {
    data::produce_atomically(path, [&](const std::filesystem::path& tmp) {
      std::ofstream gp(script_file);
      const std::string d = quote_for_gnuplot(data_file.string());
      gp << "set terminal svg size 1000,700 dynamic font 'Helvetica,12' background rgb 'white'\n"
         << "set output " << quote_for_gnuplot(tmp.string()) << "\n"
         << "set multiplot title " << quote_for_gnuplot(title) << "\n"
         << "set lmargin 10\nset rmargin 4\nset grid\n"
         << "set size 1,0.68\nset origin 0,0.30\nset key top right\n"
         << "set ylabel 'speed (km/h)'\nset yrange [0:*]\nset format x ''\n"
         << "plot " << d << " using 1:3 with steps lw 1.5 dt 2 lc rgb '#d62728' title "
         << "'speed limit', " << d << " using 1:2 with lines lw 2 lc rgb '#1f77b4' title 'speed'\n"
         << "set size 1,0.30\nset origin 0,0.0\nset format x '%g'\nset autoscale y\n"
         << "set xlabel 'distance from departure (m)'\nset ylabel 'gradient (per mille)'\n"
         << "plot " << d << " using 1:4 with steps lw 1.5 lc rgb '#2ca02c' "
         << "title 'gradient (+ = uphill)'\n"
         << "unset multiplot\n";
      gp.close();
      const std::string cmd =
          "gnuplot " + script_file.string() + " > " + log_file.string() + " 2>&1";
      if (std::system(cmd.c_str()) != 0) {
        std::ifstream log(log_file);
        std::stringstream msg;
        msg << log.rdbuf();
        throw std::runtime_error("gnuplot failed: " + msg.str());
      }
    });
  } catch (...) {
    std::filesystem::remove_all(dir);
    throw;
  }
  std::filesystem::remove_all(dir);
}

}  // namespace ecorail::output
