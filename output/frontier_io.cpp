#include "output/frontier_io.hpp"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <stdexcept>

#include <unistd.h>

#include "data/atomic_file.hpp"
#include "physics/units.hpp"

namespace ecorail::output {

namespace {
// JSON has no infinity: the flat-out point's lambda is written as null.
nlohmann::json number_or_null(double v) {
  return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr);
}
}  // namespace

nlohmann::json frontier_json(const LabelledFrontier& lf) {
  const dp::Frontier& f = lf.frontier;
  nlohmann::json points = nlohmann::json::array();
  for (const auto& p : f.points) {
    points.push_back({{"target_time_s", p.target_time_s},
                      {"running_time_s", p.running_time_s},
                      {"traction_energy_kJ", units::J_to_kJ(p.traction_work_J)},
                      {"regen_energy_kJ", units::J_to_kJ(p.regen_J)},
                      {"net_energy_kJ", units::J_to_kJ(p.net_J)},
                      {"cost_kJ", units::J_to_kJ(p.cost_J)},
                      {"lambda", number_or_null(p.lambda_J_per_s / 1000.0)},
                      {"converged", p.converged},
                      {"evaluations", p.evaluations}});
  }
  nlohmann::json wobbles = nlohmann::json::array();
  for (const auto& w : f.wobbles) {
    wobbles.push_back({{"time_s", w.time_s}, {"kind", w.kind}, {"size_kJ", w.size_J / 1000.0}});
  }
  return {{"from", lf.from},        {"to", lf.to},        {"min_running_time_s", f.min_time_s},
          {"monotone", f.monotone}, {"convex", f.convex}, {"wobbles", wobbles},
          {"points", points}};
}

LabelledFrontier frontier_from_json(const nlohmann::json& j) {
  LabelledFrontier lf;
  lf.from = j.at("from").get<std::string>();
  lf.to = j.at("to").get<std::string>();
  dp::Frontier& f = lf.frontier;
  f.min_time_s = j.at("min_running_time_s").get<double>();
  f.monotone = j.at("monotone").get<bool>();
  f.convex = j.at("convex").get<bool>();
  for (const auto& p : j.at("points")) {
    const auto& lam = p.at("lambda");
    f.points.push_back({p.at("target_time_s").get<double>(), p.at("running_time_s").get<double>(),
                        units::kJ_to_J(p.at("traction_energy_kJ").get<double>()),
                        units::kJ_to_J(p.at("regen_energy_kJ").get<double>()),
                        units::kJ_to_J(p.at("net_energy_kJ").get<double>()),
                        units::kJ_to_J(p.at("cost_kJ").get<double>()),
                        lam.is_null() ? INFINITY : lam.get<double>() * 1000.0,
                        p.at("converged").get<bool>(), p.value("evaluations", 0)});
  }
  for (const auto& w : j.at("wobbles")) {
    f.wobbles.push_back({w.at("time_s").get<double>(), w.at("kind").get<std::string>(),
                         w.at("size_kJ").get<double>() * 1000.0});
  }
  return lf;
}

void write_frontiers_csv(const std::filesystem::path& path,
                         const std::vector<LabelledFrontier>& frontiers) {
  data::write_atomically(path, [&](std::ostream& out) {
    out << "from,to,target_time_s,running_time_s,traction_energy_kJ,regen_energy_kJ,"
           "net_energy_kJ,lambda_kJ_per_s,converged,wobble\n";
    char buf[400];
    for (const auto& lf : frontiers) {
      for (const auto& p : lf.frontier.points) {
        std::string wobble;
        for (const auto& w : lf.frontier.wobbles) {
          if (w.time_s == p.target_time_s) wobble += (wobble.empty() ? "" : ";") + w.kind;
        }
        std::snprintf(buf, sizeof buf, "%s,%s,%.3f,%.4f,%.3f,%.3f,%.3f,%.3f,%d,%s\n",
                      lf.from.c_str(), lf.to.c_str(), p.target_time_s, p.running_time_s,
                      units::J_to_kJ(p.traction_work_J), units::J_to_kJ(p.regen_J),
                      units::J_to_kJ(p.net_J), p.lambda_J_per_s / 1000.0, p.converged ? 1 : 0,
                      wobble.c_str());
        out << buf;
      }
    }
  });
}

void write_frontiers_plot_svg(const std::filesystem::path& path,
                              const std::vector<LabelledFrontier>& frontiers,
                              const std::string& title) {
  if (std::system("command -v gnuplot >/dev/null 2>&1") != 0) {
    throw std::runtime_error("cannot write " + path.string() +
                             ": gnuplot is not installed (apt-get install gnuplot-nox)");
  }
  const auto dir =
      std::filesystem::temp_directory_path() / ("ecorail-frontier-" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  try {
    const auto data_file = dir / "frontier.dat";
    {
      std::ofstream data(data_file);
      for (const auto& lf : frontiers) {
        for (const auto& p : lf.frontier.points) {
          data << p.running_time_s << ' ' << units::J_to_kJ(p.cost_J) << '\n';
        }
        data << "\n\n";  // a gnuplot data block per section
      }
    }
    data::produce_atomically(path, [&](const std::filesystem::path& tmp) {
      const auto script = dir / "plot.gp";
      std::ofstream gp(script);
      gp << "set terminal svg size 900,600 dynamic font 'Helvetica,12' background rgb 'white'\n"
         << "set output '" << tmp.string() << "'\nset title '" << title << "'\n"
         << "set xlabel 'running time (s)'\nset ylabel 'energy (kJ)'\nset grid\n"
         << "set key outside right\nplot ";
      for (std::size_t i = 0; i < frontiers.size(); ++i) {
        gp << (i ? ", " : "") << "'" << data_file.string() << "' index " << i
           << " using 1:2 with linespoints pt 7 ps 0.4 title '" << frontiers[i].from << "-"
           << frontiers[i].to << "'";
      }
      gp << "\n";
      gp.close();
      const std::string cmd =
          "gnuplot " + script.string() + " > " + (dir / "log").string() + " 2>&1";
      if (std::system(cmd.c_str()) != 0) throw std::runtime_error("gnuplot failed");
    });
  } catch (...) {
    std::filesystem::remove_all(dir);
    throw;
  }
  std::filesystem::remove_all(dir);
}

}  // namespace ecorail::output
