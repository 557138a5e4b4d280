#include "data/line.hpp"

#include <cstdio>

namespace ecorail::data {

namespace {

void append_number(std::string& out, double value) {
  char buf[64];
  // -0.0 and 0.0 are the same content.
  std::snprintf(buf, sizeof buf, "%.6f", value == 0.0 ? 0.0 : value);
  out += buf;
}

void append_table(std::string& out, const char* title, const std::vector<IntervalRow>& rows) {
  out += title;
  out += '\n';
  for (const auto& r : rows) {
    append_number(out, r.start_km_post_m);
    out += ' ';
    append_number(out, r.end_km_post_m);
    out += ' ';
    append_number(out, r.value);
    out += '\n';
  }
}

}  // namespace

const Station* Line::find_station(const std::string& station_name) const {
  for (const auto& s : stations) {
    if (s.name == station_name) return &s;
  }
  return nullptr;
}

std::uint64_t Line::checksum() const {
  // The canonical text covers content only: not the line's name, file names or source rows, so
  // the same line read from CSV files or from TOML has the same checksum.
  std::string text = "stations\n";
  for (const auto& s : stations) {
    text += s.name;
    text += ' ';
    append_number(text, s.km_post_m);
    text += '\n';
  }
  append_table(text, "gradients", gradients);
  append_table(text, "speed_limits", limits);
  append_table(text, "curves", curves);
  // The extensions join the text only when used, so the checksums of lines without them (and
  // the frontier caches keyed by them) are unchanged.
  if (!curvatures.empty()) {
    text += "curvatures\n";
    for (const auto& c : curvatures) {
      for (const double v : {c.start_km_post_m, c.end_km_post_m}) {
        append_number(text, v);
        text += ' ';
      }
      char buf[64];
      std::snprintf(buf, sizeof buf, "%.12g %.12g\n", c.curvature_start_per_m + 0.0,
                    c.curvature_end_per_m + 0.0);
      text += buf;
    }
  }
  if (!tunnels.empty()) {
    text += "tunnels\n";
    for (const auto& t : tunnels) {
      for (const double v : {t.start_km_post_m, t.end_km_post_m, t.cross_section_m2}) {
        append_number(text, v);
        text += ' ';
      }
      text += '\n';
    }
  }
  if (curve_formula == CurveFormula::Roeckl) text += "curve_formula roeckl\n";
  if (cap_limits_at_train_speed) text += "cap_limits_at_train_speed\n";
  return fnv1a64(text);
}

std::string hex64(std::uint64_t value) {
  char buf[20];
  std::snprintf(buf, sizeof buf, "%016llx", static_cast<unsigned long long>(value));
  return buf;
}

std::uint64_t fnv1a64(std::string_view text) {
  std::uint64_t h = 14695981039346656037ULL;
  for (const char c : text) {
    h ^= static_cast<unsigned char>(c);
    h *= 1099511628211ULL;
  }
  return h;
}

}  // namespace ecorail::data
