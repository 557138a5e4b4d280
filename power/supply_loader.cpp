#include "power/supply_loader.hpp"

#include <fstream>
#include <sstream>

#include "data/csv_reader.hpp"
#include "data/input_error.hpp"
#include "data/toml_util.hpp"

namespace ecorail::power {

namespace {

namespace tu = data::toml_util;

int line_of(const toml::node& node) {
  return static_cast<int>(node.source().begin.line);
}

class SupplyReader {
 public:
  explicit SupplyReader(std::string file) : file_(std::move(file)) {}

  PowerSupply read(const toml::table& root) const {
    tu::check_keys(root, {"name", "trains", "substations", "conductors"}, file_, 0, "");
    PowerSupply s;
    if (const toml::node* name = root.get("name")) {
      if (!name->is_string()) fail(line_of(*name), "name", "a string; got " + tu::describe(name));
      s.name = name->as_string()->get();
    }
    const toml::table& trains = table(root, "trains");
    const int tr = line_of(trains);
    tu::check_keys(trains, {"max_voltage_V", "min_voltage_V", "auxiliary_power_kW"}, file_, tr,
                   "trains.");
    s.min_train_voltage_V = number(trains, "min_voltage_V", tr, "trains.");
    require(s.min_train_voltage_V > 0.0, tr, "trains.min_voltage_V", "a voltage > 0 V",
            s.min_train_voltage_V);
    s.max_train_voltage_V = number(trains, "max_voltage_V", tr, "trains.");
    require(s.max_train_voltage_V > s.min_train_voltage_V, tr, "trains.max_voltage_V",
            "a voltage above trains.min_voltage_V " + data::format_number(s.min_train_voltage_V),
            s.max_train_voltage_V);
    const double aux_kW = number(trains, "auxiliary_power_kW", tr, "trains.");
    require(aux_kW >= 0.0, tr, "trains.auxiliary_power_kW", "a power >= 0 kW", aux_kW);
    s.auxiliary_power_W = aux_kW * 1e3;

    const toml::array& subs = array(root, "substations");
    for (std::size_t i = 0; i < subs.size(); ++i) {
      const std::string key = "substations[" + std::to_string(i + 1) + "]";
      const toml::table* t = subs.get(i)->as_table();
      if (t == nullptr)
        fail(line_of(*subs.get(i)), key, "a table; got " + tu::describe(subs.get(i)));
      const int row = line_of(*t);
      tu::check_keys(
          *t, {"name", "position_m", "no_load_voltage_V", "internal_resistance_ohm", "reversible"},
          file_, row, key + ".");
      Substation sub;
      const toml::node* name = t->get("name");
      if (name == nullptr || !name->is_string() || name->as_string()->get().empty())
        fail(row, key + ".name", "a non-empty string; got " + tu::describe(name));
      sub.name = name->as_string()->get();
      for (const Substation& other : s.substations)
        if (other.name == sub.name)
          fail(row, key + ".name",
               "a name no other substation has; got \"" + sub.name + "\" twice");
      sub.position_m = number(*t, "position_m", row, key + ".");
      require(sub.position_m >= 0.0, row, key + ".position_m",
              "a position >= 0 m from the run's first station", sub.position_m);
      if (!s.substations.empty())
        require(sub.position_m > s.substations.back().position_m, row, key + ".position_m",
                "a position beyond the previous substation's " +
                    data::format_number(s.substations.back().position_m) + " m",
                sub.position_m);
      sub.no_load_voltage_V = number(*t, "no_load_voltage_V", row, key + ".");
      require(sub.no_load_voltage_V > s.min_train_voltage_V &&
                  sub.no_load_voltage_V < s.max_train_voltage_V,
              row, key + ".no_load_voltage_V",
              "a voltage between trains.min_voltage_V and trains.max_voltage_V",
              sub.no_load_voltage_V);
      sub.internal_resistance_ohm = number(*t, "internal_resistance_ohm", row, key + ".");
      require(sub.internal_resistance_ohm > 0.0, row, key + ".internal_resistance_ohm",
              "a resistance > 0 ohm", sub.internal_resistance_ohm);
      if (const toml::node* rev = t->get("reversible")) {
        if (!rev->is_boolean())
          fail(row, key + ".reversible", "true or false; got " + tu::describe(rev));
        sub.reversible = rev->as_boolean()->get();
      }
      s.substations.push_back(sub);
    }

    const toml::array& cond = array(root, "conductors");
    for (std::size_t i = 0; i < cond.size(); ++i) {
      const std::string key = "conductors[" + std::to_string(i + 1) + "]";
      const toml::table* t = cond.get(i)->as_table();
      if (t == nullptr)
        fail(line_of(*cond.get(i)), key, "a table; got " + tu::describe(cond.get(i)));
      const int row = line_of(*t);
      tu::check_keys(*t, {"from_m", "conductor_ohm_per_km", "return_ohm_per_km"}, file_, row,
                     key + ".");
      ConductorSegment c;
      c.from_m = number(*t, "from_m", row, key + ".");
      if (i == 0)
        require(c.from_m == 0.0, row, key + ".from_m", "the first segment from 0 m", c.from_m);
      else
        require(c.from_m > s.conductors.back().from_m, row, key + ".from_m",
                "a position beyond the previous segment's " +
                    data::format_number(s.conductors.back().from_m) + " m",
                c.from_m);
      c.conductor_ohm_per_km = number(*t, "conductor_ohm_per_km", row, key + ".");
      require(c.conductor_ohm_per_km >= 0.0, row, key + ".conductor_ohm_per_km",
              "a resistance >= 0 ohm/km", c.conductor_ohm_per_km);
      c.return_ohm_per_km = number(*t, "return_ohm_per_km", row, key + ".");
      require(c.return_ohm_per_km >= 0.0, row, key + ".return_ohm_per_km",
              "a resistance >= 0 ohm/km", c.return_ohm_per_km);
      s.conductors.push_back(c);
    }
    std::string why;
    if (!s.IsValid(&why)) fail(0, "", why);  // every rule is checked above; a safety net
    return s;
  }

 private:
  [[noreturn]] void fail(int row, const std::string& key, const std::string& expected) const {
    throw data::InputError(file_, row, key, expected);
  }
  void require(bool ok, int row, const std::string& key, const std::string& expected,
               double got) const {
    if (!ok) fail(row, key, expected + "; got " + data::format_number(got));
  }
  double number(const toml::table& t, const std::string& key, int row,
                const std::string& prefix) const {
    const toml::node* node = t.get(key);
    return tu::number(node, file_, node ? line_of(*node) : row, prefix + key);
  }
  const toml::table& table(const toml::table& t, const std::string& key) const {
    const toml::node* node = t.get(key);
    if (node == nullptr || !node->is_table())
      fail(node ? line_of(*node) : 0, key, "a table [" + key + "]; got " + tu::describe(node));
    return *node->as_table();
  }
  const toml::array& array(const toml::table& t, const std::string& key) const {
    const toml::node* node = t.get(key);
    if (node == nullptr || !node->is_array() || node->as_array()->empty())
      fail(node ? line_of(*node) : 0, key,
           "at least one [[" + key + "]] table; got " +
               (node != nullptr && node->is_array() ? std::string("an empty array")
                                                    : tu::describe(node)));
    return *node->as_array();
  }

  std::string file_;
};

}  // namespace

PowerSupply parse_power_supply(std::string_view text, const std::string& file) {
  const toml::table root = tu::parse(text, file);
  return SupplyReader(file).read(root);
}

PowerSupply load_power_supply(const std::string& file) {
  std::ifstream in(file, std::ios::binary);
  if (!in) throw data::InputError(file, 0, "", "a readable power-supply file (TOML)");
  std::ostringstream text;
  text << in.rdbuf();
  return parse_power_supply(text.str(), file);
}

}  // namespace ecorail::power
