// Reading TTOBench JSON (tracks, trains, journeys) with errors that name the file and the JSON
// path of the offending value ("speed limits.values[3][1]", indices 0-based as in the file).
// A TTOBench quantity is an object {"unit": ..., "value": ...} or, for tables,
// {"units": {column: unit}, "values": [[...], ...]}; every unit the TTOBench validators allow is
// converted here to SI, and any other unit is refused. Shared by the track, train and journey
// readers (data/ttobench_io.hpp) so that all three report problems the same way.
#pragma once

#include <nlohmann/json.hpp>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace ecorail::data::ttobench {

// What a JSON text holds, judged by its top-level keys (content, never the file name).
enum class Kind { NotJson, OtherJson, Track, Train, Journey };
Kind detect(std::string_view text);
const char* kind_name(Kind kind);

// A unit name and the factor that turns a value in it into the SI unit of its quantity.
using UnitTable = std::vector<std::pair<std::string, double>>;

class JsonReader {
 public:
  JsonReader(std::string file) : file_(std::move(file)) {}

  // Parses text; a syntax error names the byte offset.
  nlohmann::json parse(const std::string& text) const;
  // Parses text that must be a TTOBench file of the given kind (described for the error, e.g.
  // "a TTOBench track (an object with \"stops\")"): its root object.
  nlohmann::json parse_root(const std::string& text, Kind expected,
                            const std::string& described) const;
  [[noreturn]] void fail(const std::string& path, const std::string& expected) const;

  const nlohmann::json& object(const nlohmann::json& parent, const std::string& key,
                               const std::string& path) const;
  const nlohmann::json& array(const nlohmann::json& node, const std::string& path) const;
  double number(const nlohmann::json& node, const std::string& path) const;
  // A number, or infinity for the strings "infinity"/"inf" (TTOBench's straight track).
  double number_or_infinity(const nlohmann::json& node, const std::string& path) const;
  std::string string(const nlohmann::json& parent, const std::string& key,
                     const std::string& path) const;
  // Refuses any key outside `allowed` (named with its path), so nothing is silently dropped.
  void check_keys(const nlohmann::json& obj, const std::vector<std::string>& allowed,
                  const std::string& path) const;
  // The `metadata` object of root (required): free text that no solve reads. Its keys outside
  // `known` are kept (key and JSON text, in file order) and reported by metadata_warnings, not
  // refused, so files written by other tools are read; its "id" must be a string.
  std::vector<std::pair<std::string, std::string>> metadata(
      const nlohmann::json& root, const std::vector<std::string>& known) const;
  // {"unit": u, "value": x}: x converted to SI with the factor of u in units.
  double quantity(const nlohmann::json& parent, const std::string& key,
                  const UnitTable& units) const;
  // The factor of the unit string at node (path names it) in units.
  double unit_factor(const nlohmann::json& node, const std::string& path,
                     const UnitTable& units) const;
  const std::string& file() const { return file_; }

 private:
  std::string file_;
};

// The metadata keys TTOBench defines for each kind of file (others are kept and reported).
extern const std::vector<std::string> kTrackMetadataKeys;
extern const std::vector<std::string> kTrainMetadataKeys;
extern const std::vector<std::string> kJourneyMetadataKeys;

// One warning per metadata key outside `known` ("metadata.note: not a TTOBench metadata key;
// kept as free text, no solve reads it"); empty when there are none.
std::vector<std::string> metadata_warnings(
    const std::vector<std::pair<std::string, std::string>>& other_metadata);

// A JSON path: parent + "." + key (or key alone at the top), and parent + "[i]".
std::string join(const std::string& parent, const std::string& key);
std::string index(const std::string& parent, std::size_t i);
// The shortest text that reads back to exactly value ("12.5", "1e-05").
std::string json_number(double value);

// Unit tables (factor to SI).
extern const UnitTable kLength;        // m, km
extern const UnitTable kSpeed;         // km/h, m/s -> m/s
extern const UnitTable kSpeedKmh;      // km/h, m/s -> km/h (ecorail's unit for limits)
extern const UnitTable kSlope;         // permil, % -> per mille (factor to per mille)
extern const UnitTable kMass;          // kg, t
extern const UnitTable kRatio;         // -, % -> fraction
extern const UnitTable kPower;         // W, kW, MW
extern const UnitTable kForce;         // N, kN
extern const UnitTable kForceKN;       // N, kN -> kN (ecorail's envelope unit)
extern const UnitTable kPowerKW;       // W, kW, MW -> kW (ecorail's power-cap unit)
extern const UnitTable kAcceleration;  // m/s^2
extern const UnitTable kArea;          // m^2
extern const UnitTable kTime;          // s
// Resistance coefficients, factor to N/(km/h) and N/(km/h)^2 (ecorail's Davis convention).
extern const UnitTable kLinearDrag;
extern const UnitTable kQuadraticDrag;
extern const UnitTable kQuadraticDragKN;  // the same, factor to kN/(km/h)^2

}  // namespace ecorail::data::ttobench
