#include "output/frontier_cache.hpp"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <fstream>

#include "data/atomic_file.hpp"
#include "data/line.hpp"
#include "output/frontier_io.hpp"

namespace ecorail::output {

namespace {

bool sound(const dp::Frontier& f) {
  if (f.points.size() < 2) return false;
  for (std::size_t k = 0; k < f.points.size(); ++k) {
    const dp::FrontierPoint& p = f.points[k];
    if (!std::isfinite(p.running_time_s) || !std::isfinite(p.cost_J)) return false;
    if (k > 0 && !(p.running_time_s > f.points[k - 1].running_time_s)) return false;
  }
  return true;
}

}  // namespace

FileFrontierStore::FileFrontierStore(std::filesystem::path directory)
    : directory_(std::move(directory)) {}

std::filesystem::path FileFrontierStore::default_directory() {
  if (const char* xdg = std::getenv("XDG_CACHE_HOME"); xdg && *xdg) {
    return std::filesystem::path(xdg) / "ecorail" / "frontiers";
  }
  if (const char* home = std::getenv("HOME"); home && *home) {
    return std::filesystem::path(home) / ".cache" / "ecorail" / "frontiers";
  }
  return std::filesystem::temp_directory_path() / "ecorail-frontiers";
}

std::filesystem::path FileFrontierStore::path_for(const std::string& key) const {
  return directory_ / (data::hex64(data::fnv1a64(key)) + ".json");
}

std::optional<dp::Frontier> FileFrontierStore::load(const std::string& key) {
  const auto file = path_for(key);
  std::error_code ec;
  if (!std::filesystem::is_regular_file(file, ec)) return std::nullopt;
  try {
    std::ifstream in(file);
    const nlohmann::json doc = nlohmann::json::parse(in);
    if (doc.at("key").get<std::string>() != key) return std::nullopt;  // stale or a collision
    const nlohmann::json& body = doc.at("frontier");
    if (doc.at("checksum").get<std::string>() != data::hex64(data::fnv1a64(body.dump()))) {
      return std::nullopt;  // edited or damaged
    }
    dp::Frontier f = frontier_from_json(body).frontier;
    if (!sound(f)) return std::nullopt;
    return f;
  } catch (const std::exception&) {
    return std::nullopt;  // truncated or not JSON: recomputed
  }
}

void FileFrontierStore::save(const std::string& key, const dp::Frontier& frontier) {
  std::error_code ec;
  std::filesystem::create_directories(directory_, ec);
  if (ec) return;
  const nlohmann::json body = frontier_json({"", "", frontier});
  const nlohmann::json doc = {
      {"key", key}, {"checksum", data::hex64(data::fnv1a64(body.dump()))}, {"frontier", body}};
  try {
    data::write_atomically(path_for(key), [&](std::ostream& out) { out << doc.dump() << "\n"; });
  } catch (const std::exception&) {
    // The cache is an optimisation: failing to write it is not an error.
  }
}

}  // namespace ecorail::output
