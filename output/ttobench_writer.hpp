// Writes ecorail lines and trains as TTOBench JSON, the inverse of data/ttobench_io.hpp: reading
// the text back gives the same Line::checksum and train_checksum (tests/data/
// test_ttobench_roundtrip.cpp). A line becomes a track whose position 0 is its lowest-km-post
// station (every station a stop; a line whose stations are not S0, S1, ... carries "stop names";
// the tables are clipped to the stations' span, which is all TTOBench can hold), with
// curvatures or constant curves and tunnels. A train must be what TTOBench can state: a constant
// traction and regenerative braking force under a power cap (a single-point table); any other
// envelope (the reference train's polynomials) is refused with std::invalid_argument rather than
// approximated.
#pragma once

#include <filesystem>
#include <string>

#include "data/line.hpp"
#include "physics/train.hpp"

namespace ecorail::output {

std::string line_to_ttobench(const data::Line& line, const std::string& id);
std::string train_to_ttobench(const physics::Train& train);
// Atomic writes (all or nothing) of the two texts.
void save_line_ttobench(const data::Line& line, const std::string& id,
                        const std::filesystem::path& path);
void save_train_ttobench(const physics::Train& train, const std::filesystem::path& path);

}  // namespace ecorail::output
