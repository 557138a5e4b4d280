#include "data/ttobench_json.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <limits>

#include "data/csv_reader.hpp"
#include "data/input_error.hpp"

namespace ecorail::data::ttobench {

const UnitTable kLength{{"m", 1.0}, {"km", 1000.0}};
const UnitTable kSpeed{{"km/h", 1.0 / 3.6}, {"m/s", 1.0}};
const UnitTable kSpeedKmh{{"km/h", 1.0}, {"m/s", 3.6}};
const UnitTable kSlope{{"permil", 1.0}, {"%", 10.0}};
const UnitTable kMass{{"kg", 1.0}, {"t", 1000.0}};
const UnitTable kRatio{{"-", 1.0}, {"%", 0.01}};
const UnitTable kPower{{"W", 1.0}, {"kW", 1000.0}, {"MW", 1e6}};
const UnitTable kForce{{"N", 1.0}, {"kN", 1000.0}};
const UnitTable kForceKN{{"N", 0.001}, {"kN", 1.0}};
const UnitTable kPowerKW{{"W", 0.001}, {"kW", 1.0}, {"MW", 1000.0}};
const UnitTable kAcceleration{{"m/s^2", 1.0}};
const UnitTable kArea{{"m^2", 1.0}};
const UnitTable kTime{{"s", 1.0}};
// N/(m/s) = N per 3.6 km/h: a coefficient per m/s is 1/3.6 of itself per km/h.
const UnitTable kLinearDrag{
    {"kN/(km/h)", 1000.0}, {"N/(m/s)", 1.0 / 3.6}, {"kN/(m/s)", 1000.0 / 3.6}};
const UnitTable kQuadraticDrag{{"kN/(km/h)^2", 1000.0},
                               {"N/(m/s)^2", 1.0 / (3.6 * 3.6)},
                               {"kN/(m/s)^2", 1000.0 / (3.6 * 3.6)},
                               {"kg/m", 1.0 / (3.6 * 3.6)}};
const UnitTable kQuadraticDragKN{{"kN/(km/h)^2", 1.0},
                                 {"N/(m/s)^2", 0.001 / (3.6 * 3.6)},
                                 {"kN/(m/s)^2", 1.0 / (3.6 * 3.6)},
                                 {"kg/m", 0.001 / (3.6 * 3.6)}};

Kind detect(std::string_view text) {
  const auto first = text.find_first_not_of(" \t\r\n");
  if (first == std::string_view::npos || (text[first] != '{' && text[first] != '[')) {
    return Kind::NotJson;
  }
  const nlohmann::json j = nlohmann::json::parse(text, nullptr, false);
  if (j.is_discarded() || !j.is_object()) return Kind::OtherJson;
  if (j.contains("timing points")) return Kind::Journey;
  if (j.contains("stops")) return Kind::Track;
  if (j.contains("mass") || j.contains("max traction force")) return Kind::Train;
  // A syntactically broken file that opens with '{' is still meant as JSON.
  return Kind::OtherJson;
}

const char* kind_name(Kind kind) {
  switch (kind) {
    case Kind::NotJson:
      return "not JSON";
    case Kind::OtherJson:
      return "JSON that is not a TTOBench track, train or journey";
    case Kind::Track:
      return "a TTOBench track";
    case Kind::Train:
      return "a TTOBench train";
    case Kind::Journey:
      return "a TTOBench journey";
  }
  return "";
}

std::string join(const std::string& parent, const std::string& key) {
  return parent.empty() ? key : parent + "." + key;
}

std::string index(const std::string& parent, std::size_t i) {
  return parent + "[" + std::to_string(i) + "]";
}

std::string json_number(double value) {
  char buf[64];
  const auto res = std::to_chars(buf, buf + sizeof buf, value);
  return std::string(buf, res.ptr);
}

namespace {
std::string describe(const nlohmann::json& node) {
  if (node.is_null()) return "null";
  if (node.is_boolean()) return "a boolean";
  if (node.is_number()) return "the number " + format_number(node.get<double>());
  if (node.is_string()) return "the string \"" + node.get<std::string>() + "\"";
  if (node.is_array()) return "an array of " + std::to_string(node.size());
  return "an object";
}
}  // namespace

nlohmann::json JsonReader::parse(const std::string& text) const {
  try {
    return nlohmann::json::parse(text);
  } catch (const nlohmann::json::parse_error& e) {
    throw InputError(file_, 0, "",
                     "well-formed JSON; got a syntax error at byte " + std::to_string(e.byte));
  } catch (const nlohmann::json::out_of_range&) {
    // A number literal beyond double's range (1E1191) is out_of_range, not a parse_error.
    throw InputError(file_, 0, "", "well-formed JSON with numbers within double's range");
  }
}

nlohmann::json JsonReader::parse_root(const std::string& text, Kind expected,
                                      const std::string& described) const {
  nlohmann::json root = parse(text);
  const Kind kind = detect(text);
  if (!root.is_object() || kind != expected)
    fail("", described + "; got " + (root.is_object() ? kind_name(kind) : "another JSON value"));
  return root;
}

void JsonReader::fail(const std::string& path, const std::string& expected) const {
  throw InputError(file_, 0, path, expected);
}

const nlohmann::json& JsonReader::object(const nlohmann::json& parent, const std::string& key,
                                         const std::string& path) const {
  const std::string at = join(path, key);
  if (!parent.contains(key)) fail(at, "an object; got nothing (the key is missing)");
  const nlohmann::json& node = parent.at(key);
  if (!node.is_object()) fail(at, "an object; got " + describe(node));
  return node;
}

const nlohmann::json& JsonReader::array(const nlohmann::json& node, const std::string& path) const {
  if (!node.is_array()) fail(path, "an array; got " + describe(node));
  return node;
}

double JsonReader::number(const nlohmann::json& node, const std::string& path) const {
  if (!node.is_number()) fail(path, "a number; got " + describe(node));
  const double v = node.get<double>();
  if (!std::isfinite(v)) fail(path, "a finite number; got " + describe(node));
  return v;
}

double JsonReader::number_or_infinity(const nlohmann::json& node, const std::string& path) const {
  if (node.is_string()) {
    const std::string s = node.get<std::string>();
    if (s == "infinity" || s == "inf" || s == "Infinity") {
      return std::numeric_limits<double>::infinity();
    }
    if (s == "-infinity" || s == "-inf" || s == "-Infinity") {
      return -std::numeric_limits<double>::infinity();
    }
  }
  if (!node.is_number()) fail(path, "a number or \"infinity\"; got " + describe(node));
  return node.get<double>();
}

std::string JsonReader::string(const nlohmann::json& parent, const std::string& key,
                               const std::string& path) const {
  const std::string at = join(path, key);
  if (!parent.contains(key)) fail(at, "a string; got nothing (the key is missing)");
  const nlohmann::json& node = parent.at(key);
  if (!node.is_string()) fail(at, "a string; got " + describe(node));
  return node.get<std::string>();
}

void JsonReader::check_keys(const nlohmann::json& obj, const std::vector<std::string>& allowed,
                            const std::string& path) const {
  for (const auto& [key, value] : obj.items()) {
    bool known = false;
    for (const auto& a : allowed) known = known || a == key;
    if (!known) {
      std::string list;
      for (const auto& a : allowed) list += (list.empty() ? "'" : ", '") + a + "'";
      fail(join(path, key), "one of the keys ecorail models (" + list +
                                "); got an unknown key, refused rather than ignored");
    }
  }
}

const std::vector<std::string> kTrackMetadataKeys{
    "id",      "library version",  "description",     "created by",
    "license", "associated track", "associated train"};
const std::vector<std::string> kTrainMetadataKeys{"id", "library version", "description",
                                                  "created by", "license"};
const std::vector<std::string> kJourneyMetadataKeys{
    "id", "library version", "description", "created by", "license", "associated track"};

std::vector<std::pair<std::string, std::string>> JsonReader::metadata(
    const nlohmann::json& root, const std::vector<std::string>& known) const {
  const nlohmann::json& meta = object(root, "metadata", "");
  std::vector<std::pair<std::string, std::string>> other;
  for (const auto& [key, value] : meta.items()) {
    if (std::find(known.begin(), known.end(), key) == known.end()) {
      other.emplace_back(key, value.dump());
    }
  }
  return other;
}

std::vector<std::string> metadata_warnings(
    const std::vector<std::pair<std::string, std::string>>& other_metadata) {
  std::vector<std::string> out;
  for (const auto& [key, text] : other_metadata) {
    out.push_back("'metadata." + key +
                  "' is not a TTOBench metadata key: kept as free text, no solve reads it");
  }
  return out;
}

double JsonReader::unit_factor(const nlohmann::json& node, const std::string& path,
                               const UnitTable& units) const {
  std::string list;
  for (const auto& [name, factor] : units) list += (list.empty() ? "\"" : ", \"") + name + "\"";
  if (!node.is_string()) fail(path, "a unit, one of " + list + "; got " + describe(node));
  const std::string u = node.get<std::string>();
  for (const auto& [name, factor] : units) {
    if (name == u) return factor;
  }
  fail(path, "a unit, one of " + list + "; got \"" + u + "\"");
}

double JsonReader::quantity(const nlohmann::json& parent, const std::string& key,
                            const UnitTable& units) const {
  const nlohmann::json& q = object(parent, key, "");
  check_keys(q, {"unit", "value"}, key);
  if (!q.contains("unit")) fail(join(key, "unit"), "a unit; got nothing (the key is missing)");
  if (!q.contains("value")) fail(join(key, "value"), "a number; got nothing (the key is missing)");
  const double factor = unit_factor(q.at("unit"), join(key, "unit"), units);
  return number(q.at("value"), join(key, "value")) * factor;
}

}  // namespace ecorail::data::ttobench
