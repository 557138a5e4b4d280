#include "output/frontier_io.hpp"

#include <cmath>
#include <cstdio>
#include <sstream>
#include <stdexcept>

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
  return {{"from", lf.from},
          {"to", lf.to},
          {"min_running_time_s", f.min_time_s},
          {"monotone", f.monotone},
          {"convex", f.convex},
          {"wobbles", wobbles},
          {"points", points},
          {"from_cache", lf.from_cache}};
}

LabelledFrontier frontier_from_json(const nlohmann::json& j) {
  LabelledFrontier lf;
  lf.from = j.at("from").get<std::string>();
  lf.to = j.at("to").get<std::string>();
  lf.from_cache = true;
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

void write_frontiers_csv(std::ostream& out, const std::vector<LabelledFrontier>& frontiers) {
  out << "from,to,target_time_s,running_time_s,traction_energy_kJ,regen_energy_kJ,"
         "net_energy_kJ,lambda_kJ_per_s,converged,wobble\n";
  char buf[400];
  for (const auto& lf : frontiers) {
    for (const auto& p : lf.frontier.points) {
      std::string wobble;
      for (const auto& w : lf.frontier.wobbles) {
        if (w.time_s == p.target_time_s) wobble += (wobble.empty() ? "" : ";") + w.kind;
      }
      std::snprintf(buf, sizeof buf, "%s,%s,%.3f,%.4f,%.3f,%.3f,%.3f,%.3f,%d,%s\n", lf.from.c_str(),
                    lf.to.c_str(), p.target_time_s, p.running_time_s,
                    units::J_to_kJ(p.traction_work_J), units::J_to_kJ(p.regen_J),
                    units::J_to_kJ(p.net_J), p.lambda_J_per_s / 1000.0, p.converged ? 1 : 0,
                    wobble.c_str());
      out << buf;
    }
  }
}

void write_frontiers_csv(const std::filesystem::path& path,
                         const std::vector<LabelledFrontier>& frontiers) {
  data::write_atomically(path, [&](std::ostream& out) { write_frontiers_csv(out, frontiers); });
}

CurveStyle frontier_curve_style(std::size_t i) {
  // Ten colours (matplotlib's tab10), then the same colours dashed, then dotted...: 13 sections
  // of a line never share a style. Point types cycle with a period (6) prime to 10.
  static const char* const colours[] = {"#1f77b4", "#ff7f0e", "#2ca02c", "#d62728", "#9467bd",
                                        "#8c564b", "#e377c2", "#7f7f7f", "#bcbd22", "#17becf"};
  static const int points[] = {7, 5, 9, 11, 13, 15};
  const std::size_t n = std::size(colours);
  return {colours[i % n], static_cast<int>(1 + (i / n) % 6), points[i % std::size(points)]};
}

std::string frontiers_plot_script(const std::vector<LabelledFrontier>& frontiers,
                                  const std::string& title, const std::string& objective,
                                  PlotFormat format, const std::filesystem::path& output_file) {
  std::ostringstream gp;
  gp << gnuplot_terminal(format, 1000, 650) << "set output " << gnuplot_quote(output_file.string())
     << "\nset title " << gnuplot_quote(title) << "\n"
     << "set xlabel " << gnuplot_quote("running time (s)") << "\nset ylabel "
     << gnuplot_quote((objective.empty() ? std::string("energy") : objective) + " (kJ)") << "\n"
     << "set grid\nset key outside right top\nplot ";
  for (std::size_t i = 0; i < frontiers.size(); ++i) {
    const CurveStyle st = frontier_curve_style(i);
    gp << (i ? ", " : "") << "'frontier.dat' index " << i
       << " using 1:2 with linespoints lw 1.5 pt " << st.point_type << " ps 0.5 dt " << st.dash_type
       << " lc rgb '" << st.colour << "' title "
       << gnuplot_quote(frontiers[i].from + " - " + frontiers[i].to);
  }
  gp << "\n";
  return gp.str();
}

void write_frontiers_plot_file(const std::filesystem::path& file,
                               const std::vector<LabelledFrontier>& frontiers,
                               const std::string& title, const std::string& objective,
                               PlotFormat format) {
  if (const std::string problem = gnuplot_problem(format); !problem.empty()) {
    throw std::runtime_error(problem);
  }
  std::ostringstream data;
  data.precision(10);
  for (const auto& lf : frontiers) {
    for (const auto& p : lf.frontier.points) {
      data << p.running_time_s << ' ' << units::J_to_kJ(p.cost_J) << '\n';
    }
    data << "\n\n";  // a gnuplot data block per section
  }
  run_gnuplot(
      frontiers_plot_script(frontiers, title, objective, format, std::filesystem::absolute(file)),
      {{"frontier.dat", data.str()}});
  check_plot_complete(file, format);
}

void write_frontiers_plot(const std::filesystem::path& path,
                          const std::vector<LabelledFrontier>& frontiers, const std::string& title,
                          const std::string& objective) {
  const auto format = plot_format_for(path);
  if (!format) {
    throw std::runtime_error("cannot write " + path.string() +
                             ": a plot file name ends in .svg or .png");
  }
  data::produce_atomically(path, [&](const std::filesystem::path& tmp) {
    write_frontiers_plot_file(tmp, frontiers, title, objective, *format);
  });
}

void write_frontiers_plot_svg(const std::filesystem::path& path,
                              const std::vector<LabelledFrontier>& frontiers,
                              const std::string& title) {
  write_frontiers_plot(path, frontiers, title);
}

}  // namespace ecorail::output
