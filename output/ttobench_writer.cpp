#include "output/ttobench_writer.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <stdexcept>

#include "data/atomic_file.hpp"
#include "data/ttobench_json.hpp"
#include "data/ttobench_units.hpp"
#include "physics/units.hpp"

namespace ecorail::output {

namespace {

using data::ttobench::json_number;

// The value whose forward conversion (the reader's) gives `target` exactly, searched over a few
// ulps around the plain inverse `guess`, so that read -> write -> read keeps every bit.
double exact_inverse(double target, double guess, const std::function<double(double)>& forward) {
  if (forward(guess) == target) return guess;
  double up = guess;
  double down = guess;
  for (int i = 0; i < 64; ++i) {
    up = std::nextafter(up, std::numeric_limits<double>::infinity());
    if (forward(up) == target) return up;
    down = std::nextafter(down, -std::numeric_limits<double>::infinity());
    if (forward(down) == target) return down;
  }
  return guess;
}

std::string quantity(const char* key, const char* unit, double value) {
  return std::string("  \"") + key + "\": {\"unit\": \"" + unit +
         "\", \"value\": " + json_number(value) + "},\n";
}

std::string radius_text(double curvature_per_m) {
  return curvature_per_m == 0.0 ? "\"infinity\"" : json_number(1.0 / curvature_per_m);
}

std::string escape(const std::string& s) {
  std::string out;
  for (const char c : s) {
    if (c == '"' || c == '\\') out += '\\';
    if (static_cast<unsigned char>(c) < 0x20) continue;
    out += c;
  }
  return out;
}

// Rows of a km-post table clipped to [lo, hi], as (position from lo, value), merging neighbours
// of equal value (TTOBench lists only changes).
std::vector<std::pair<double, double>> clipped(const std::vector<data::IntervalRow>& rows,
                                               double lo, double hi) {
  std::vector<data::IntervalRow> sorted = rows;
  std::sort(sorted.begin(), sorted.end(),
            [](const auto& a, const auto& b) { return a.start_km_post_m < b.start_km_post_m; });
  std::vector<std::pair<double, double>> out;
  for (const auto& r : sorted) {
    if (r.end_km_post_m <= lo || r.start_km_post_m >= hi) continue;
    const double x = std::max(r.start_km_post_m, lo) - lo;
    if (!out.empty() && out.back().second == r.value) continue;
    out.emplace_back(out.empty() ? 0.0 : x, r.value);
  }
  return out;
}

std::string pairs_table(const char* key, const char* units,
                        const std::vector<std::pair<double, double>>& rows) {
  std::string out = std::string("  \"") + key + "\": {\"units\": " + units + ", \"values\": [";
  for (std::size_t i = 0; i < rows.size(); ++i) {
    out +=
        (i ? ", [" : "[") + json_number(rows[i].first) + ", " + json_number(rows[i].second) + "]";
  }
  return out + "]}";
}

}  // namespace

std::string line_to_ttobench(const data::Line& line, const std::string& id) {
  if (line.stations.size() < 2) throw std::invalid_argument("a TTOBench track needs two stops");
  std::vector<data::Station> stops = line.stations;
  std::sort(stops.begin(), stops.end(),
            [](const auto& a, const auto& b) { return a.km_post_m < b.km_post_m; });
  for (std::size_t i = 1; i < stops.size(); ++i) {
    if (!(stops[i].km_post_m > stops[i - 1].km_post_m)) {
      throw std::invalid_argument("a TTOBench track needs stops at distinct positions; " +
                                  stops[i].name + " shares its km post");
    }
  }
  const double lo = stops.front().km_post_m;
  const double hi = stops.back().km_post_m;
  bool default_names = true;
  for (std::size_t i = 0; i < stops.size(); ++i) {
    default_names = default_names && stops[i].name == "S" + std::to_string(i);
  }
  std::string out = "{\n  \"metadata\": {\"id\": \"" + escape(id) +
                    "\", \"library version\": \"TTOBench v1.4\", \"created by\": \"ecorail\"},\n";
  out += "  \"stops\": {\"unit\": \"m\", \"values\": [";
  for (std::size_t i = 0; i < stops.size(); ++i) {
    out += (i ? ", " : "") + json_number(stops[i].km_post_m - lo);
  }
  out += "]},\n";
  if (!default_names) {
    out += "  \"stop names\": [";
    for (std::size_t i = 0; i < stops.size(); ++i) {
      out += std::string(i ? ", \"" : "\"") + escape(stops[i].name) + "\"";
    }
    out += "],\n";
  }
  out += pairs_table("speed limits", "{\"position\": \"m\", \"velocity\": \"km/h\"}",
                     clipped(line.limits, lo, hi)) +
         ",\n";
  out += pairs_table("gradients", "{\"position\": \"m\", \"slope\": \"permil\"}",
                     clipped(line.gradients, lo, hi));
  // Curvatures: the line's own (clothoids kept), or its constant curves.
  std::vector<data::CurvatureRow> curv = line.curvatures;
  if (curv.empty()) {
    for (const auto& r : line.curves) {
      const double k = r.value > 0.0 ? 1.0 / r.value : 0.0;
      curv.push_back({r.start_km_post_m, r.end_km_post_m, k, k, r.source_row});
    }
  }
  std::sort(curv.begin(), curv.end(),
            [](const auto& a, const auto& b) { return a.start_km_post_m < b.start_km_post_m; });
  std::string rows;
  for (const auto& c : curv) {
    if (c.end_km_post_m <= lo || c.start_km_post_m >= hi) continue;
    const bool straight = c.curvature_start_per_m == 0.0 && c.curvature_end_per_m == 0.0;
    if (rows.empty() && straight && c.end_km_post_m >= hi) break;  // all straight: omit
    const double x = rows.empty() ? 0.0 : std::max(c.start_km_post_m, lo) - lo;
    if (c.start_km_post_m < lo && c.curvature_start_per_m != c.curvature_end_per_m) {
      throw std::invalid_argument("a clothoid across the first stop cannot be clipped exactly");
    }
    rows += (rows.empty() ? "[" : ", [") + json_number(x) + ", " +
            radius_text(c.curvature_start_per_m) + ", " + radius_text(c.curvature_end_per_m) + "]";
  }
  if (!rows.empty()) {
    out +=
        ",\n  \"curvatures\": {\"units\": {\"position\": \"m\", \"radius at start\": \"m\", "
        "\"radius at end\": \"m\"}, \"values\": [" +
        rows + "]}";
  }
  if (!line.tunnels.empty()) {
    out +=
        ",\n  \"tunnels\": {\"units\": {\"position\": \"m\", \"length\": \"m\", \"cross "
        "section\": \"m^2\"}, \"values\": [";
    for (std::size_t i = 0; i < line.tunnels.size(); ++i) {
      const auto& t = line.tunnels[i];
      out += (i ? ", [" : "[") + json_number(t.start_km_post_m - lo) + ", " +
             json_number(t.end_km_post_m - t.start_km_post_m) + ", " +
             json_number(t.cross_section_m2) + "]";
    }
    out += "]}";
  }
  return out + "\n}\n";
}

std::string train_to_ttobench(const physics::Train& t) {
  const auto constant_capped = [](const physics::ForceEnvelope& e, const char* what) {
    if (!e.is_table() || e.points().size() != 1 || !(e.power_cap_kW() > 0.0)) {
      throw std::invalid_argument(
          std::string("TTOBench states a constant ") + what +
          " force under a power cap; this train's envelope is another curve (refused rather "
          "than approximated)");
    }
    return std::make_pair(e.points().front().force_kN, e.power_cap_kW());
  };
  const auto [traction_kN, traction_kW] = constant_capped(t.traction, "traction");
  const auto [regen_kN, regen_kW] = constant_capped(t.braking, "regenerative braking");
  const auto davis = [&](double specific, double kN_factor) {
    const double guess = data::ttobench::specific_to_force(specific, t) / kN_factor;
    return exact_inverse(specific, guess, [&](double v) {
      return data::ttobench::force_to_specific(v * kN_factor, t);
    });
  };
  if (t.has_efficiency_maps()) {
    throw std::invalid_argument(
        "TTOBench states constant efficiencies; this train's are maps over speed and force "
        "(refused rather than approximated)");
  }
  if (t.gravity_m_s2 != data::ttobench::kGravity_m_s2) {
    throw std::invalid_argument("TTOBench trains are read with g = 9.81 m/s^2; this train uses " +
                                json_number(t.gravity_m_s2));
  }
  std::string out = "{\n  \"metadata\": {\"id\": \"" + escape(t.name) +
                    "\", \"library version\": \"TTOBench v1.4\", \"created by\": \"ecorail\"},\n";
  if (t.length_m > 0.0) out += quantity("length", "m", t.length_m);
  out += quantity("mass", "kg", t.mass_kg);
  out += quantity("rho", "-", t.rotating_mass_factor);
  out += quantity("max traction power", "kW", traction_kW);
  out += quantity("max reg braking power", "kW", regen_kW);
  out += quantity("max traction force", "kN", traction_kN);
  out += quantity("max reg braking force", "kN", regen_kN);
  out += quantity("max pn braking force", "N", t.pneumatic_brake_N);
  if (std::isfinite(t.max_accel_m_s2)) {
    out += quantity("max acceleration", "m/s^2", t.max_accel_m_s2);
  }
  if (std::isfinite(t.max_decel_m_s2)) {
    out += quantity("max deceleration", "m/s^2", t.max_decel_m_s2);
  }
  const double vmax_kmh = exact_inverse(t.max_speed_ms, units::ms_to_kmh(t.max_speed_ms),
                                        [](double v) { return data::ttobench::kmh_to_ms(v); });
  out += quantity("max speed", "km/h", vmax_kmh);
  out += quantity("rolling resistance r0", "N", davis(t.davis.A, 1.0));
  out += quantity("rolling resistance r1", "kN/(km/h)", davis(t.davis.B, 1000.0));
  out += quantity("rolling resistance r2", "kN/(km/h)^2", davis(t.davis.C, 1000.0));
  out += quantity("efficiency traction", "-", t.traction_efficiency);
  out += quantity("efficiency reg brake", "-", t.regen_efficiency);
  if (t.auxiliary_power_W > 0.0) out += quantity("auxiliary power", "W", t.auxiliary_power_W);
  if (!t.tunnel_drag.empty()) {
    out +=
        "  \"tunnel resistance\": {\"units\": {\"cross section\": \"m^2\", \"coefficient\": "
        "\"kN/(km/h)^2\"}, \"values\": [";
    for (std::size_t i = 0; i < t.tunnel_drag.size(); ++i) {
      out += (i ? ", [" : "[") + json_number(t.tunnel_drag[i].cross_section_m2) + ", " +
             json_number(t.tunnel_drag[i].C_kN_per_kmh2) + "]";
    }
    out += "]},\n";
  }
  out.erase(out.size() - 2);  // the last ",\n"
  return out + "\n}\n";
}

void save_line_ttobench(const data::Line& line, const std::string& id,
                        const std::filesystem::path& path) {
  const std::string text = line_to_ttobench(line, id);
  data::write_atomically(path, [&](std::ostream& out) { out << text; });
}

void save_train_ttobench(const physics::Train& train, const std::filesystem::path& path) {
  const std::string text = train_to_ttobench(train);
  data::write_atomically(path, [&](std::ostream& out) { out << text; });
}

}  // namespace ecorail::output
