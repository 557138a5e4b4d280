#include "data/toml_util.hpp"

#include <cmath>
#include <sstream>

#include "data/csv_reader.hpp"
#include "data/input_error.hpp"

namespace ecorail::data::toml_util {

std::string describe(const toml::node* node) {
  if (node == nullptr) return "nothing (the key is missing)";
  switch (node->type()) {
    case toml::node_type::table:
      return "a table";
    case toml::node_type::array:
      return "an array";
    case toml::node_type::string:
      return "the string \"" + std::string(node->as_string()->get()) + "\"";
    case toml::node_type::integer:
      return "the integer " + std::to_string(node->as_integer()->get());
    case toml::node_type::floating_point:
      return "the float " + format_number(node->as_floating_point()->get());
    case toml::node_type::boolean:
      return node->as_boolean()->get() ? "the boolean true" : "the boolean false";
    case toml::node_type::date:
    case toml::node_type::time:
    case toml::node_type::date_time:
      return "a date or time";
    default:
      return "nothing";
  }
}

toml::table parse(std::string_view text, const std::string& file) {
  try {
    return toml::parse(text, std::string_view(file));
  } catch (const toml::parse_error& e) {
    std::ostringstream what;
    what << "valid TOML; got a syntax error at line " << e.source().begin.line << ", column "
         << e.source().begin.column << ": " << e.description();
    throw InputError(file, 0, "", what.str());
  }
}

double number(const toml::node* node, const std::string& file, int row, const std::string& field) {
  if (node != nullptr) {
    if (const auto* i = node->as_integer()) return static_cast<double>(i->get());
    if (const auto* f = node->as_floating_point()) {
      if (std::isfinite(f->get())) return f->get();
      throw InputError(file, row, field, "a finite number; got " + describe(node));
    }
  }
  throw InputError(file, row, field, "a number; got " + describe(node));
}

void check_keys(const toml::table& table, std::initializer_list<std::string_view> allowed,
                const std::string& file, int row, const std::string& prefix) {
  for (const auto& [key, value] : table) {
    bool known = false;
    for (const auto a : allowed) known = known || key.str() == a;
    if (!known) {
      std::string list;
      for (const auto a : allowed) list += (list.empty() ? "" : ", ") + std::string(a);
      throw InputError(file, row, prefix + std::string(key.str()),
                       "one of the keys " + list + "; got an unknown key");
    }
  }
}

}  // namespace ecorail::data::toml_util
