#include "output/provenance.hpp"

#include <cstdio>

#include "data/line.hpp"
#include "data/train_io.hpp"
#include "data/version.hpp"

namespace ecorail::output {

nlohmann::json program_json() {
  return {{"name", "ecorail"},
          {"version", data::version()},
          {"commit", data::commit()},
          {"build_type", data::build_type()}};
}

nlohmann::json provenance_json(const data::Line& line, const physics::Train& train,
                               const nlohmann::json& grid, const nlohmann::json& options) {
  return {{"program", program_json()},
          {"line", {{"name", line.name}, {"checksum", data::hex64(line.checksum())}}},
          {"train", {{"name", train.name}, {"checksum", data::hex64(data::train_checksum(train))}}},
          {"grid", grid},
          {"options", options}};
}

}  // namespace ecorail::output
