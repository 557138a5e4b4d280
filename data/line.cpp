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
