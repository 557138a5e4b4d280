// Line: a metro line as its data files describe it, in kilometre posts. Stations, and three
// tables of rows over kilometre-post intervals: gradients (per mille, positive = rising towards
// increasing km post), speed limits (km/h) and curves (radius m, 0 = straight). A Line knows
// nothing of travel direction; data/route_builder turns a pair of stations into a
// physics::Route seen in the direction of travel.
#pragma once

#include <cstdint>
#include <limits>
#include <string>
#include <string_view>
#include <vector>

namespace ecorail::data {

struct Station {
  std::string name;
  double km_post_m = 0.0;
  int source_row = 0;  // row in the file it came from, for error messages
  // WGS 84 position (optional columns lat, lon of the stations table; NaN when not given). Only
  // exports that locate stops on a map use it (GTFS stops.txt); it changes no run.
  double lat_deg = std::numeric_limits<double>::quiet_NaN();
  double lon_deg = std::numeric_limits<double>::quiet_NaN();
  bool has_coordinates() const { return lat_deg == lat_deg && lon_deg == lon_deg; }
};

struct IntervalRow {
  double start_km_post_m = 0.0;
  double end_km_post_m = 0.0;
  double value = 0.0;  // gradient per mille, limit km/h or radius m
  int source_row = 0;  // row in the file it came from, for error messages
};

// A tunnel over a km-post interval with its cross-section (TTOBench 'tunnels'); its drag comes
// from the train's tunnel_drag table.
struct TunnelRow {
  double start_km_post_m = 0.0;
  double end_km_post_m = 0.0;
  double cross_section_m2 = 0.0;
  int source_row = 0;  // entry number in the file (1-based), for error messages
};

// A curve over a km-post interval whose signed curvature (1/m: + right, - left, 0 straight)
// runs linearly from start to end: constant, or a clothoid when the two differ (TTOBench
// 'curvatures'). Stated in the direction of increasing km post.
struct CurvatureRow {
  double start_km_post_m = 0.0;
  double end_km_post_m = 0.0;
  double curvature_start_per_m = 0.0;
  double curvature_end_per_m = 0.0;
  int source_row = 0;
};

// How curve resistance (N/kN) follows from the radius R (m): 600 / R (the reference line's
// rule), or Roeckl's 500 / (R - 30) for R >= 300 m and 650 / (R - 55) below.
enum class CurveFormula { Inverse600, Roeckl };

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
  // Extensions a TTOBench track needs (empty/default for the CSV and TOML forms): when
  // curvatures is non-empty it replaces curves (then one straight row); tunnels add drag;
  // a limit above the train's maximum speed means the train's maximum when
  // cap_limits_at_train_speed (TTOBench limits are the track's, not the train's).
  std::string tunnels_file;
  std::vector<CurvatureRow> curvatures;
  std::vector<TunnelRow> tunnels;
  CurveFormula curve_formula = CurveFormula::Inverse600;
  bool cap_limits_at_train_speed = false;

  const Station* find_station(const std::string& name) const;
  // A stable 64-bit checksum of the content (FNV-1a over a canonical text form).
  std::uint64_t checksum() const;
};

// FNV-1a, 64 bits: the hash behind Line::checksum and train_checksum.
std::uint64_t fnv1a64(std::string_view text);
// A checksum as 16 lower-case hex digits ("1c217a07a6df55fb"), as reports and files write it.
std::string hex64(std::uint64_t value);

}  // namespace ecorail::data
