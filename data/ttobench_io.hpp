// TTOBench tracks and trains (https://github.com/dkouzoup/TTOBench, BSD-2) read into ecorail's
// own models (writing them back: output/ttobench_writer.hpp). The mapping, field by
// field, is in docs/formats.md ("TTOBench JSON"). Everything a file carries is either honoured
// or refused with an InputError naming the file and JSON path: unknown keys, units the
// TTOBench validators do not allow, efficiency maps (not modelled yet), a track whose stops do
// not start at 0, ... Metadata is free text: keys TTOBench does not define there are kept and
// reported (ttobench_metadata_warnings). The one exception is 'ETCS braking data' (signalling
// supervision data outside the trajectory model): accepted, and listed by unmodelled_fields so that
// the program says so. Stops are named S0, S1, ... unless the file's optional "stop names" names
// them.
#pragma once

#include <string>
#include <vector>

#include "data/line.hpp"
#include "physics/train.hpp"

namespace ecorail::data {

// True if the text opens like JSON (after white space): the loaders then read it as TTOBench.
bool looks_like_json(const std::string& text);

Line line_from_ttobench(const std::string& text, const std::string& file);
physics::Train train_from_ttobench(const std::string& text, const std::string& file);
// Fields present in a TTOBench file that ecorail accepts but does not model, as
// "'ETCS braking data' (...)" phrases; empty for files that are not TTOBench JSON.
std::vector<std::string> ttobench_unmodelled_fields(const std::string& text);
// Metadata keys TTOBench does not define in a track, train or journey file (kept as free text,
// never refused: metadata is read by no solve), one warning each; empty for other files.
std::vector<std::string> ttobench_metadata_warnings(const std::string& text);

}  // namespace ecorail::data
