// The file cache of the Monte Carlo simulator's section runs (recovery::SectionRunStore): one
// small text file per piece (its key, knot and re-simulated times, then its sparse power bins
// in micro-joules), named by a hash of the key, written to a temporary and renamed, read back
// only when the key in the file is the exact key asked for (line, train, grid, engine version,
// running time and bin step), so a stale or corrupt file is simply solved again.
#pragma once

#include <filesystem>
#include <string>

#include "recovery/section_runs.hpp"

namespace ecorail::output {

class FileSectionRunStore : public recovery::SectionRunStore {
 public:
  explicit FileSectionRunStore(std::filesystem::path directory);
  bool load(const std::string& key, recovery::SectionPiece* piece) override;
  void save(const std::string& key, const recovery::SectionPiece& piece) override;
  std::filesystem::path path_for(const std::string& key) const;

 private:
  std::filesystem::path directory_;
};

}  // namespace ecorail::output
