#include "data/train_io.hpp"

#include <charconv>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string_view>

#include "data/atomic_file.hpp"
#include "data/csv_reader.hpp"
#include "data/embedded.hpp"
#include "data/input_error.hpp"
#include "data/line.hpp"
#include "data/plausibility.hpp"
#include "data/toml_util.hpp"
#include "data/ttobench_io.hpp"
#include "physics/units.hpp"

namespace ecorail::data {

namespace {

// Envelope pieces must meet exactly, up to rounding of the written speeds.
constexpr double kSpeedTolerance_kmh = 1e-9;

// ---- reading ------------------------------------------------------------------------------

class TrainReader {
 public:
  explicit TrainReader(std::string file) : file_(std::move(file)) {}

  double number(const toml::table& t, const std::string& key, const std::string& prefix) const {
    return toml_util::number(t.get(key), file_, 0, prefix + key);
  }
  double optional_number(const toml::table& t, const std::string& key, double fallback) const {
    return t.contains(key) ? number(t, key, "") : fallback;
  }
  const toml::table& table(const toml::table& t, const std::string& key) const {
    const toml::node* node = t.get(key);
    if (node == nullptr || !node->is_table()) {
      throw InputError(file_, 0, key, "a table [" + key + "]; got " + toml_util::describe(node));
    }
    return *node->as_table();
  }
  [[noreturn]] void fail(const std::string& key, const std::string& expected) const {
    throw InputError(file_, 0, key, expected);
  }
  void require(bool ok, const std::string& key, const std::string& expected, double got) const {
    if (!ok) fail(key, expected + "; got " + format_number(got));
  }

  physics::ForceEnvelope envelope(const toml::table& root, const std::string& name) const {
    const toml::table& t = table(root, name);
    toml_util::check_keys(t, {"segments", "points", "power_cap_kW"}, file_, 0, name + ".");
    const double cap = optional_number(t, "power_cap_kW", 0.0);
    require(cap >= 0.0, name + ".power_cap_kW", "a power cap of at least 0 kW (0 = none)", cap);
    const bool has_segments = t.contains("segments");
    const bool has_points = t.contains("points");
    if (has_segments == has_points) {
      fail(name, has_segments ? "either segments or points; got both"
                              : "segments = [...] or points = [...]; got neither");
    }
    if (has_segments) return physics::ForceEnvelope::piecewise(segments(t, name), cap);
    return physics::ForceEnvelope::table(points(t, name), cap);
  }

 private:
  const toml::array& array(const toml::table& t, const std::string& key) const {
    const toml::node* node = t.get(key);
    if (node == nullptr || !node->is_array() || node->as_array()->empty()) {
      fail(key, "a non-empty array; got " + (node != nullptr && node->is_array()
                                                 ? std::string("an empty array")
                                                 : toml_util::describe(node)));
    }
    return *node->as_array();
  }

  std::vector<physics::PolynomialPiece> segments(const toml::table& t,
                                                 const std::string& name) const {
    const auto& arr = array(t, "segments");
    std::vector<physics::PolynomialPiece> pieces;
    double expected_from = 0.0;
    for (std::size_t i = 0; i < arr.size(); ++i) {
      const std::string key = name + ".segments[" + std::to_string(i + 1) + "]";
      const toml::table* seg = arr.get(i)->as_table();
      if (seg == nullptr) {
        fail(key,
             "a table { from_kmh, to_kmh, coeffs_kN }; got " + toml_util::describe(arr.get(i)));
      }
      toml_util::check_keys(*seg, {"from_kmh", "to_kmh", "coeffs_kN"}, file_, 0, key + ".");
      physics::PolynomialPiece piece;
      piece.from_kmh = number(*seg, "from_kmh", key + ".");
      piece.to_kmh = number(*seg, "to_kmh", key + ".");
      if (std::abs(piece.from_kmh - expected_from) > kSpeedTolerance_kmh) {
        fail(key + ".from_kmh",
             (i == 0 ? std::string("segments contiguous from 0 km/h, the first starting at 0")
                     : "segments contiguous from 0 km/h, this one starting at the previous "
                       "to_kmh " +
                           format_number(expected_from)) +
                 "; got " + format_number(piece.from_kmh));
      }
      require(piece.to_kmh > piece.from_kmh, key + ".to_kmh",
              "a speed above from_kmh " + format_number(piece.from_kmh), piece.to_kmh);
      const std::string ckey = key + ".coeffs_kN";
      const toml::node* coeffs = seg->get("coeffs_kN");
      if (coeffs == nullptr || !coeffs->is_array() || coeffs->as_array()->empty()) {
        fail(ckey, "a non-empty array of numbers; got " + (coeffs != nullptr && coeffs->is_array()
                                                               ? std::string("an empty array")
                                                               : toml_util::describe(coeffs)));
      }
      for (std::size_t k = 0; k < coeffs->as_array()->size(); ++k) {
        piece.coeffs_kN.push_back(toml_util::number(coeffs->as_array()->get(k), file_, 0,
                                                    ckey + "[" + std::to_string(k + 1) + "]"));
      }
      expected_from = piece.to_kmh;
      pieces.push_back(std::move(piece));
    }
    return pieces;
  }

  std::vector<physics::TablePoint> points(const toml::table& t, const std::string& name) const {
    const auto& arr = array(t, "points");
    std::vector<physics::TablePoint> out;
    for (std::size_t i = 0; i < arr.size(); ++i) {
      const std::string key = name + ".points[" + std::to_string(i + 1) + "]";
      const toml::array* pair = arr.get(i)->as_array();
      if (pair == nullptr || pair->size() != 2) {
        fail(key, "a pair [v_kmh, F_kN]; got " +
                      (pair != nullptr ? "an array of " + std::to_string(pair->size())
                                       : toml_util::describe(arr.get(i))));
      }
      physics::TablePoint p;
      p.speed_kmh = toml_util::number(pair->get(0), file_, 0, key + "[1]");
      p.force_kN = toml_util::number(pair->get(1), file_, 0, key + "[2]");
      require(p.speed_kmh >= 0.0, key + "[1]", "a speed of at least 0 km/h", p.speed_kmh);
      if (!out.empty()) {
        require(p.speed_kmh > out.back().speed_kmh, key + "[1]",
                "a speed above the previous point's " + format_number(out.back().speed_kmh),
                p.speed_kmh);
      }
      require(p.force_kN >= 0.0, key + "[2]", "a force of at least 0 kN", p.force_kN);
      out.push_back(p);
    }
    return out;
  }

  std::string file_;
};

// ---- writing ------------------------------------------------------------------------------

// The shortest text that reads back to exactly value, always a TOML float ("80.0", "1e-05").
std::string toml_float(double value) {
  if (!std::isfinite(value)) throw std::invalid_argument("train holds a non-finite number");
  char buf[64];
  const auto res = std::to_chars(buf, buf + sizeof buf, value);
  std::string s(buf, res.ptr);
  if (s.find_first_of(".e") == std::string::npos) s += ".0";
  return s;
}

// The file value whose conversion to_si gives back si exactly, if one lies within a few ulps of
// the plain inverse conversion (the case for every train that was itself read from a file).
double file_value(double si, double guess, double (*to_si)(double)) {
  if (to_si(guess) == si) return guess;
  double up = guess;
  double down = guess;
  for (int i = 0; i < 16; ++i) {
    up = std::nextafter(up, std::numeric_limits<double>::infinity());
    if (to_si(up) == si) return up;
    down = std::nextafter(down, -std::numeric_limits<double>::infinity());
    if (to_si(down) == si) return down;
  }
  return guess;
}

double mass_to_kg(double mass_t) {
  return units::t_to_kg(mass_t);
}
double kN_to_N(double f_kN) {
  return 1000.0 * f_kN;
}
double kW_to_W(double p_kW) {
  return 1000.0 * p_kW;
}
double speed_to_ms(double v_kmh) {
  return units::kmh_to_ms(v_kmh);
}

std::string toml_string(const std::string& s) {
  std::string out = "\"";
  for (const char c : s) {
    switch (c) {
      case '"':
        out += "\\\"";
        break;
      case '\\':
        out += "\\\\";
        break;
      case '\n':
        out += "\\n";
        break;
      case '\t':
        out += "\\t";
        break;
      case '\r':
        out += "\\r";
        break;
      default:
        if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f) {
          char buf[8];
          std::snprintf(buf, sizeof buf, "\\u%04x", static_cast<unsigned char>(c));
          out += buf;
        } else {
          out += c;
        }
    }
  }
  return out + "\"";
}

void write_envelope(std::string& out, const char* name, const physics::ForceEnvelope& e) {
  if (e.empty()) throw std::invalid_argument(std::string("train has no ") + name + " envelope");
  out += std::string("\n[") + name + "]\n";
  if (e.is_table()) {
    out += "# points [v_kmh, F_kN], interpolated linearly\npoints = [\n";
    for (const auto& p : e.points()) {
      out += "  [" + toml_float(p.speed_kmh) + ", " + toml_float(p.force_kN) + "],\n";
    }
  } else {
    out += "# coefficients in ascending powers of v (km/h), giving kN\nsegments = [\n";
    for (const auto& p : e.pieces()) {
      out += "  { from_kmh = " + toml_float(p.from_kmh) + ", to_kmh = " + toml_float(p.to_kmh) +
             ", coeffs_kN = [";
      for (std::size_t k = 0; k < p.coeffs_kN.size(); ++k) {
        out += (k == 0 ? "" : ", ") + toml_float(p.coeffs_kN[k]);
      }
      out += "] },\n";
    }
  }
  out += "]\n";
  if (e.power_cap_kW() > 0.0) out += "power_cap_kW = " + toml_float(e.power_cap_kW()) + "\n";
}

// An efficiency map (docs/formats.md): speeds_kmh and forces_kN ascending (at least two each),
// efficiency one row of values per speed, each value in (0, 1]. Absent: empty (the constant).
physics::EfficiencyMap read_efficiency_map(const toml::table& root, const std::string& name,
                                           const std::string& file) {
  physics::EfficiencyMap map;
  const toml::node* node = root.get(name);
  if (node == nullptr) return map;
  auto fail = [&](const std::string& key, const std::string& expected) {
    throw InputError(file, 0, name + "." + key, expected);
  };
  if (!node->is_table()) {
    throw InputError(file, 0, name, "a table with speeds_kmh, forces_kN and efficiency");
  }
  const toml::table& t = *node->as_table();
  toml_util::check_keys(t, {"speeds_kmh", "forces_kN", "efficiency"}, file, 0, name + ".");
  // The conversions the writer inverts (speed_to_ms, kN_to_N), so a map reads back exactly.
  auto axis = [&](const char* key, double (*to_si)(double)) {
    const toml::array* a = t.get(key) ? t.get(key)->as_array() : nullptr;
    if (a == nullptr || a->size() < 2) fail(key, "an array of at least two ascending numbers");
    std::vector<double> out;
    for (std::size_t i = 0; i < a->size(); ++i) {
      const std::string where = std::string(key) + "[" + std::to_string(i + 1) + "]";
      const double x = toml_util::number(a->get(i), file, 0, name + "." + where);
      if (!(x >= 0.0) || (!out.empty() && !(to_si(x) > out.back()))) {
        fail(where, "ascending numbers from 0 up; got " + format_number(x));
      }
      out.push_back(to_si(x));
    }
    return out;
  };
  map.speeds_ms = axis("speeds_kmh", speed_to_ms);
  map.forces_N = axis("forces_kN", kN_to_N);
  const toml::array* rows = t.get("efficiency") ? t.get("efficiency")->as_array() : nullptr;
  if (rows == nullptr || rows->size() != map.speeds_ms.size()) {
    fail("efficiency", "one row per speed (" + std::to_string(map.speeds_ms.size()) + " rows)");
  }
  for (std::size_t i = 0; i < rows->size(); ++i) {
    const std::string row_key = "efficiency[" + std::to_string(i + 1) + "]";
    const toml::array* row = rows->get(i)->as_array();
    if (row == nullptr || row->size() != map.forces_N.size()) {
      fail(row_key, "one value per force (" + std::to_string(map.forces_N.size()) + " values)");
    }
    for (std::size_t j = 0; j < row->size(); ++j) {
      const std::string where = row_key + "[" + std::to_string(j + 1) + "]";
      const double x = toml_util::number(row->get(j), file, 0, name + "." + where);
      if (!(x > 0.0 && x <= 1.0)) fail(where, "an efficiency in (0, 1]; got " + format_number(x));
      map.values.push_back(x);
    }
  }
  return map;
}

void write_efficiency_map(std::string& out, const char* name, const physics::EfficiencyMap& m) {
  if (m.empty()) return;
  out += std::string("\n[") + name + "]\nspeeds_kmh = [";
  for (std::size_t i = 0; i < m.speeds_ms.size(); ++i) {
    out += (i ? ", " : "") +
           toml_float(file_value(m.speeds_ms[i], units::ms_to_kmh(m.speeds_ms[i]), speed_to_ms));
  }
  out += "]\nforces_kN = [";
  for (std::size_t j = 0; j < m.forces_N.size(); ++j) {
    out += (j ? ", " : "") + toml_float(file_value(m.forces_N[j], m.forces_N[j] / 1000.0, kN_to_N));
  }
  out += "]\nefficiency = [\n";
  for (std::size_t i = 0; i < m.speeds_ms.size(); ++i) {
    out += "  [";
    for (std::size_t j = 0; j < m.forces_N.size(); ++j) {
      out += (j ? ", " : "") + toml_float(m.values[i * m.forces_N.size() + j]);
    }
    out += "],\n";
  }
  out += "]\n";
}

}  // namespace

physics::Train parse_train_toml(const std::string& text, const std::string& file_label) {
  const toml::table root = toml_util::parse(text, file_label);
  const TrainReader r(file_label);
  toml_util::check_keys(
      root,
      {"name", "mass_t", "rotating_mass_factor", "gravity_m_s2", "max_speed_kmh", "max_accel_m_s2",
       "max_decel_m_s2", "traction_efficiency", "regen_efficiency", "davis", "traction", "braking",
       "pneumatic_brake_kN", "length_m", "tunnel_drag", "auxiliary_power_kW",
       "traction_efficiency_map", "regen_efficiency_map"},
      file_label, 0, "");
  physics::Train train;
  const toml::node* name = root.get("name");
  if (name == nullptr || !name->is_string()) {
    r.fail("name", "a string; got " + toml_util::describe(name));
  }
  train.name = std::string(name->as_string()->get());

  const double mass_t = r.number(root, "mass_t", "");
  r.require(mass_t > 0.0, "mass_t", "a mass above 0 t", mass_t);
  train.mass_kg = mass_to_kg(mass_t);
  train.rotating_mass_factor = r.number(root, "rotating_mass_factor", "");
  r.require(train.rotating_mass_factor >= 0.0, "rotating_mass_factor",
            "a rotating-mass factor of at least 0", train.rotating_mass_factor);
  train.gravity_m_s2 = r.optional_number(root, "gravity_m_s2", 9.8);
  r.require(train.gravity_m_s2 > 0.0, "gravity_m_s2", "a gravity above 0 m/s^2",
            train.gravity_m_s2);
  const double vmax_kmh = r.number(root, "max_speed_kmh", "");
  r.require(vmax_kmh > 0.0, "max_speed_kmh", "a maximum speed above 0 km/h", vmax_kmh);
  train.max_speed_ms = speed_to_ms(vmax_kmh);
  // An absent comfort limit is no limit (a TTOBench train without one, written as TOML).
  train.max_accel_m_s2 =
      r.optional_number(root, "max_accel_m_s2", std::numeric_limits<double>::infinity());
  r.require(train.max_accel_m_s2 > 0.0, "max_accel_m_s2", "an acceleration limit above 0 m/s^2",
            train.max_accel_m_s2);
  train.max_decel_m_s2 =
      r.optional_number(root, "max_decel_m_s2", std::numeric_limits<double>::infinity());
  r.require(train.max_decel_m_s2 > 0.0, "max_decel_m_s2", "a deceleration limit above 0 m/s^2",
            train.max_decel_m_s2);
  train.traction_efficiency = r.number(root, "traction_efficiency", "");
  r.require(train.traction_efficiency > 0.0 && train.traction_efficiency <= 1.0,
            "traction_efficiency", "an efficiency in (0, 1]", train.traction_efficiency);
  train.regen_efficiency = r.number(root, "regen_efficiency", "");
  r.require(train.regen_efficiency > 0.0 && train.regen_efficiency <= 1.0, "regen_efficiency",
            "an efficiency in (0, 1]", train.regen_efficiency);

  const toml::table& davis = r.table(root, "davis");
  toml_util::check_keys(davis, {"A", "B", "C"}, file_label, 0, "davis.");
  train.davis.A = r.number(davis, "A", "davis.");
  train.davis.B = r.number(davis, "B", "davis.");
  train.davis.C = r.number(davis, "C", "davis.");

  train.traction = r.envelope(root, "traction");
  train.braking = r.envelope(root, "braking");
  // Optional terms of TTOBench trains (docs/formats.md): pneumatic brake, length, tunnel drag.
  train.pneumatic_brake_N = kN_to_N(r.optional_number(root, "pneumatic_brake_kN", 0.0));
  r.require(train.pneumatic_brake_N >= 0.0, "pneumatic_brake_kN", "a force of at least 0 kN",
            train.pneumatic_brake_N / 1000.0);
  train.length_m = r.optional_number(root, "length_m", 0.0);
  r.require(train.length_m >= 0.0, "length_m", "a length of at least 0 m", train.length_m);
  if (const toml::array* drag =
          root.get("tunnel_drag") ? root.get("tunnel_drag")->as_array() : nullptr) {
    for (std::size_t i = 0; i < drag->size(); ++i) {
      const std::string key = "tunnel_drag[" + std::to_string(i + 1) + "]";
      const toml::array* pair = drag->get(i)->as_array();
      if (pair == nullptr || pair->size() != 2) r.fail(key, "a pair [m^2, kN/(km/h)^2]");
      physics::TunnelDrag d{toml_util::number(pair->get(0), file_label, 0, key + "[1]"),
                            toml_util::number(pair->get(1), file_label, 0, key + "[2]")};
      r.require(d.cross_section_m2 > 0.0 &&
                    (train.tunnel_drag.empty() ||
                     d.cross_section_m2 > train.tunnel_drag.back().cross_section_m2),
                key + "[1]", "increasing cross-sections above 0 m^2", d.cross_section_m2);
      r.require(d.C_kN_per_kmh2 >= 0.0, key + "[2]", "a coefficient of at least 0",
                d.C_kN_per_kmh2);
      train.tunnel_drag.push_back(d);
    }
  } else if (root.contains("tunnel_drag")) {
    r.fail("tunnel_drag", "an array of pairs [m^2, kN/(km/h)^2]");
  }
  train.auxiliary_power_W = kW_to_W(r.optional_number(root, "auxiliary_power_kW", 0.0));
  train.traction_efficiency_map = read_efficiency_map(root, "traction_efficiency_map", file_label);
  train.regen_efficiency_map = read_efficiency_map(root, "regen_efficiency_map", file_label);
  plausible::check_train(train, file_label);
  return train;
}

physics::Train default_train() {
  const std::string_view text = embedded::find("train.toml");
  if (text.empty()) {
    throw InputError("<embedded>/train.toml", 0, "", "a train compiled into the program; got none");
  }
  return parse_train_toml(std::string(text), "<embedded>/train.toml");
}

physics::Train load_train(const std::filesystem::path& path) {
  const std::string text = read_text_file(path);
  // A TTOBench train (JSON), known by its content.
  if (looks_like_json(text)) return train_from_ttobench(text, path.string());
  return parse_train_toml(text, path.string());
}

std::string train_to_toml(const physics::Train& t) {
  std::string out = "# Train for ecorail; format in docs/formats.md.\n";
  out += "name = " + toml_string(t.name) + "\n";
  out += "mass_t = " + toml_float(file_value(t.mass_kg, t.mass_kg / 1000.0, mass_to_kg)) + "\n";
  out += "rotating_mass_factor = " + toml_float(t.rotating_mass_factor) + "\n";
  out += "gravity_m_s2 = " + toml_float(t.gravity_m_s2) + "\n";
  out += "max_speed_kmh = " +
         toml_float(file_value(t.max_speed_ms, units::ms_to_kmh(t.max_speed_ms), speed_to_ms)) +
         "\n";
  if (std::isfinite(t.max_accel_m_s2)) {  // absent = no limit
    out += "max_accel_m_s2 = " + toml_float(t.max_accel_m_s2) + "\n";
  }
  if (std::isfinite(t.max_decel_m_s2)) {
    out += "max_decel_m_s2 = " + toml_float(t.max_decel_m_s2) + "\n";
  }
  out += "traction_efficiency = " + toml_float(t.traction_efficiency) + "\n";
  out += "regen_efficiency = " + toml_float(t.regen_efficiency) + "\n";
  // The TTOBench terms only when used, so existing trains keep their text and checksum.
  if (t.pneumatic_brake_N != 0.0) {
    out += "pneumatic_brake_kN = " +
           toml_float(file_value(t.pneumatic_brake_N, t.pneumatic_brake_N / 1000.0, kN_to_N)) +
           "\n";
  }
  if (t.length_m != 0.0) out += "length_m = " + toml_float(t.length_m) + "\n";
  if (!t.tunnel_drag.empty()) {
    out += "tunnel_drag = [";
    for (const auto& d : t.tunnel_drag) {
      out += "[" + toml_float(d.cross_section_m2) + ", " + toml_float(d.C_kN_per_kmh2) + "],";
    }
    out += "]\n";
  }
  if (t.auxiliary_power_W != 0.0) {
    out += "auxiliary_power_kW = " +
           toml_float(file_value(t.auxiliary_power_W, t.auxiliary_power_W / 1000.0, kW_to_W)) +
           "\n";
  }
  out += "\n[davis]\n";
  out += "A = " + toml_float(t.davis.A) + "\n";
  out += "B = " + toml_float(t.davis.B) + "\n";
  out += "C = " + toml_float(t.davis.C) + "\n";
  write_envelope(out, "traction", t.traction);
  write_envelope(out, "braking", t.braking);
  write_efficiency_map(out, "traction_efficiency_map", t.traction_efficiency_map);
  write_efficiency_map(out, "regen_efficiency_map", t.regen_efficiency_map);
  return out;
}

void save_train(const physics::Train& train, const std::filesystem::path& path) {
  const std::string text = train_to_toml(train);
  write_atomically(path, [&](std::ostream& out) { out << text; });
}

std::uint64_t train_checksum(const physics::Train& train) {
  return fnv1a64(train_to_toml(train));
}

}  // namespace ecorail::data
