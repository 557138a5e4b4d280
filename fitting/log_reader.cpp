#include "fitting/log_reader.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <map>
#include <optional>
#include <ostream>

#include "data/csv_reader.hpp"
#include "data/input_error.hpp"
#include "physics/units.hpp"

namespace ecorail::fitting {

namespace {

std::string lower(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return s;
}

// Columns looked up by lower-case name; the original spelling is kept for messages.
class Columns {
 public:
  explicit Columns(const data::CsvTable& t) : table_(&t) {
    for (std::size_t i = 0; i < t.header().size(); ++i) index_[lower(t.header()[i])] = i;
  }
  std::optional<std::size_t> find(const std::string& name) const {
    auto it = index_.find(lower(name));
    if (it == index_.end()) return std::nullopt;
    return it->second;
  }
  // The first of several alternative columns that is present.
  std::optional<std::size_t> first_of(std::initializer_list<const char*> names) const {
    for (const char* n : names) {
      if (auto c = find(n)) return c;
    }
    return std::nullopt;
  }
  const std::string& name(std::size_t c) const { return table_->header()[c]; }
  std::string listing() const {
    std::string s;
    for (const auto& h : table_->header()) s += (s.empty() ? "" : ", ") + h;
    return s;
  }

 private:
  const data::CsvTable* table_;
  std::map<std::string, std::size_t> index_;
};

std::string number_text(double v) {
  return data::format_number(v);
}

}  // namespace

std::string_view format_name(LogFormat f) {
  return f == LogFormat::Published ? "published per-second table" : "plain CSV";
}

Log parse_log(std::string_view text, const std::string& label) {
  const data::CsvTable table = data::CsvTable::parse(text, label);
  const Columns cols(table);
  Log log;
  log.label = label;

  const auto time_s = cols.find("time_s");
  const auto time_hms = cols.find("time_hms");
  if (!time_s && !time_hms) {
    throw data::InputError(
        label, 1, "time_s",
        "a time column time_s (seconds) or time_hms (HH:MM:SS); got columns " + cols.listing());
  }
  const auto speed_ms = cols.first_of({"speed_ms", "speed_m_s"});
  const auto speed_cm_s = cols.find("speed_cm_s");
  const auto speed_kmh = cols.find("speed_kmh");
  if (!speed_ms && !speed_cm_s && !speed_kmh) {
    throw data::InputError(
        label, 1, "speed_kmh",
        "a speed column speed_kmh, speed_ms or speed_cm_s; got columns " + cols.listing());
  }
  const auto position = cols.first_of({"position_m", "distance_m"});
  const auto km_post = cols.find("km_post_m");
  const auto gradient = cols.find("gradient_permille");
  const auto curve = cols.find("curve_radius_m");
  const auto traction = cols.find("traction_force_kN");
  const auto braking = cols.find("braking_force_kN");
  const auto force = cols.find("force_kN");
  const auto notch = cols.find("notch");
  if (!traction && !braking && !force && !notch) {
    throw data::InputError(label, 1, "traction_force_kN",
                           "a force column: traction_force_kN and/or braking_force_kN, force_kN "
                           "(signed, traction positive) or notch (-1..1); got columns " +
                               cols.listing());
  }
  log.format = (time_hms && speed_cm_s && traction && cols.find("traction_power_kW"))
                   ? LogFormat::Published
                   : LogFormat::Plain;
  log.speed_column = cols.name(speed_ms ? *speed_ms : speed_cm_s ? *speed_cm_s : *speed_kmh);
  log.has_position = position.has_value() || km_post.has_value();
  log.has_gradient = gradient.has_value();
  log.has_curve = curve.has_value();
  log.has_traction = traction.has_value() || force.has_value();
  log.has_braking = braking.has_value() || force.has_value();
  log.has_notch = notch.has_value();

  for (const auto& r : table.rows()) {
    LogRow row;
    row.source_row = r.row;
    auto num = [&](std::size_t c) { return table.number(r, c); };
    row.time_s =
        time_s ? num(*time_s)
               : data::parse_clock_s(table.text(r, *time_hms), data::TwoFieldClock::MinutesSeconds,
                                     label, r.row, cols.name(*time_hms), "a time HH:MM:SS");
    if (speed_ms) {
      row.speed_ms = num(*speed_ms);
    } else if (speed_cm_s) {
      row.speed_ms = num(*speed_cm_s) / 100.0;
    } else {
      row.speed_ms = units::kmh_to_ms(num(*speed_kmh));
    }
    const std::size_t speed_col = speed_ms ? *speed_ms : speed_cm_s ? *speed_cm_s : *speed_kmh;
    if (row.speed_ms < 0.0) {
      throw data::InputError(label, r.row, cols.name(speed_col),
                             "a speed of at least 0; got " + table.text(r, speed_col));
    }
    if (position) {
      row.position_m = num(*position);
    } else if (km_post) {
      row.position_m = num(*km_post);  // converted to travel direction below
    }
    if (gradient) row.gradient_permille = num(*gradient);
    if (curve) {
      row.curve_radius_m = num(*curve);
      if (row.curve_radius_m < 0.0) {
        throw data::InputError(
            label, r.row, cols.name(*curve),
            "a radius of at least 0 m (0 = straight); got " + table.text(r, *curve));
      }
    }
    auto non_negative = [&](std::size_t c) {
      const double v = num(c);
      if (v < 0.0) {
        throw data::InputError(label, r.row, cols.name(c),
                               "a force of at least 0 kN; got " + table.text(r, c));
      }
      return units::kN_to_N(v);
    };
    if (force) {
      const double f = units::kN_to_N(num(*force));
      row.traction_force_N = std::max(f, 0.0);
      row.braking_force_N = std::max(-f, 0.0);
    }
    if (traction) row.traction_force_N = non_negative(*traction);
    if (braking) row.braking_force_N = non_negative(*braking);
    if (notch) {
      row.notch = num(*notch);
      if (row.notch < -1.0 || row.notch > 1.0) {
        throw data::InputError(label, r.row, cols.name(*notch),
                               "a notch between -1 (full braking) and 1 (full traction); got " +
                                   table.text(r, *notch));
      }
    }
    if (!log.rows.empty() && !(row.time_s > log.rows.back().time_s)) {
      throw data::InputError(label, r.row, time_s ? cols.name(*time_s) : cols.name(*time_hms),
                             "time increasing from row to row; got " + number_text(row.time_s) +
                                 " s after " + number_text(log.rows.back().time_s) + " s on row " +
                                 std::to_string(log.rows.back().source_row));
    }
    log.rows.push_back(row);
  }
  if (log.rows.size() < 2) {
    throw data::InputError(label, 0, "",
                           "a log of at least 2 rows; got " + std::to_string(log.rows.size()));
  }
  if (!position && km_post) {
    // Kilometre posts may fall or rise along the run: measure from the first row onwards.
    const double first = log.rows.front().position_m;
    const double dir = log.rows.back().position_m >= first ? 1.0 : -1.0;
    for (auto& row : log.rows) row.position_m = dir * (row.position_m - first);
  }
  return log;
}

Log read_log(const std::filesystem::path& path) {
  return parse_log(data::read_text_file(path), path.string());
}

void write_log_csv(const Log& log, std::ostream& out) {
  out.precision(10);
  out << "time_s,speed_kmh";
  if (log.has_position) out << ",position_m";
  if (log.has_gradient) out << ",gradient_permille";
  if (log.has_curve) out << ",curve_radius_m";
  if (log.has_traction) out << ",traction_force_kN";
  if (log.has_braking) out << ",braking_force_kN";
  if (log.has_notch) out << ",notch";
  out << "\n";
  for (const auto& r : log.rows) {
    out << r.time_s << "," << units::ms_to_kmh(r.speed_ms);
    if (log.has_position) out << "," << r.position_m;
    if (log.has_gradient) out << "," << r.gradient_permille;
    if (log.has_curve) out << "," << r.curve_radius_m;
    if (log.has_traction) out << "," << units::N_to_kN(r.traction_force_N);
    if (log.has_braking) out << "," << units::N_to_kN(r.braking_force_N);
    if (log.has_notch) out << "," << r.notch;
    out << "\n";
  }
}

}  // namespace ecorail::fitting
