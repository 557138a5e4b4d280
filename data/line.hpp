// Line: a metro line as its data files describe it, in kilometre posts. Stations, and three
// tables of rows over kilometre-post intervals: gradients (per mille, positive = rising towards
// increasing km post), speed limits (km/h) and curves (radius m, 0 = straight). A Line knows
// nothing of travel direction; data/route_builder turns a pair of stations into a
// physics::Route seen in the direction of travel.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace ecorail::data {

struct Station {
  std::string name;
  double km_post_m = 0.0;
  int source_row = 0;  // row in the file it came from, for error messages
};

struct IntervalRow {
  double start_km_post_m = 0.0;
  double end_km_post_m = 0.0;
  double value = 0.0;  // gradient per mille, limit km/h or radius m
  int source_row = 0;  // row in the file it came from, for error messages
};

struct Line {
  std::string name;           // e.g. "contest" or the file/directory it came from
  std::string stations_file;  // file names, for error messages
  std::string gradients_file;
  std::string limits_file;
  std::string curves_file;
  std::vector<Station> stations;       // in file order
  std::vector<IntervalRow> gradients;  // sorted by start
  std::vector<IntervalRow> limits;
  std::vector<IntervalRow> curves;

  const Station* find_station(const std::string& name) const;
  // A stable 64-bit checksum of the content (FNV-1a over a canonical text form).
  std::uint64_t checksum() const;
};

// FNV-1a, 64 bits: the hash behind Line::checksum and train_checksum.
std::uint64_t fnv1a64(std::string_view text);
// A checksum as 16 lower-case hex digits ("1c217a07a6df55fb"), as reports and files write it.
std::string hex64(std::uint64_t value);

}  // namespace ecorail::data
