// Reading and writing trains as TOML (format in docs/formats.md and data/contest/train.toml):
// mass, rotating-mass factor, limits, efficiencies, Davis coefficients (N/kN, v in km/h) and the
// traction and braking envelopes as polynomial segments or point tables, with an optional
// power cap. The reference train is compiled in. Bad content is an InputError naming the key.
#pragma once

#include <cstdint>
#include <filesystem>

#include "physics/train.hpp"

namespace ecorail::data {

physics::Train default_train();
physics::Train load_train(const std::filesystem::path& path);
physics::Train parse_train_toml(const std::string& text, const std::string& file_label);
// Writes atomically (temporary file, then rename); the result loads back to the same train.
void save_train(const physics::Train& train, const std::filesystem::path& path);
std::string train_to_toml(const physics::Train& train);
// A stable 64-bit checksum of the train's content.
std::uint64_t train_checksum(const physics::Train& train);

}  // namespace ecorail::data
