// FileFrontierStore: the on-disk frontier cache behind SectionLibrary (dp keeps no files). One
// JSON file per frontier, named by a hash of its key; the file repeats the full key and a
// checksum of its content, so an entry is used only under exactly its key (line, train, grid,
// range, engine version) and only if it reads back whole and sound (running times rising,
// energies finite). Anything else (absent, truncated, edited, stale, from another key with a
// colliding hash) reads as absent and is recomputed and rewritten. Writing is atomic, and a
// failure to write is not an error: the cache is only an optimisation.
#pragma once

#include <filesystem>
#include <optional>
#include <string>

#include "dp/section_library.hpp"

namespace ecorail::output {

class FileFrontierStore : public dp::FrontierStore {
 public:
  explicit FileFrontierStore(std::filesystem::path directory);
  std::optional<dp::Frontier> load(const std::string& key) override;
  void save(const std::string& key, const dp::Frontier& frontier) override;

  std::filesystem::path path_for(const std::string& key) const;
  // $XDG_CACHE_HOME/ecorail/frontiers, else $HOME/.cache/ecorail/frontiers, else a temp dir.
  static std::filesystem::path default_directory();

 private:
  std::filesystem::path directory_;
};

}  // namespace ecorail::output
