// Helpers shared by the TOML readers of lines and trains (internal to data/): typed access to
// keys with InputErrors that name file, row and key and say what was found.
#pragma once

#include <initializer_list>
#include <string>
#include <string_view>

#include <toml++/toml.h>

namespace ecorail::data::toml_util {

// "a string", "an integer", "a table", ... for messages.
std::string describe(const toml::node* node);
// Parses TOML text; a syntax error is an InputError at the line of the error.
toml::table parse(std::string_view text, const std::string& file);
// A finite number (integer or float) or InputError(file, row, field, "a number; got ...").
double number(const toml::node* node, const std::string& file, int row, const std::string& field);
// Every key of table must be one of allowed; otherwise InputError(file, row, prefix + key, ...).
void check_keys(const toml::table& table, std::initializer_list<std::string_view> allowed,
                const std::string& file, int row, const std::string& prefix);

}  // namespace ecorail::data::toml_util
