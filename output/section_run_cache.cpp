#include "output/section_run_cache.hpp"

#include <unistd.h>
#include <cstdint>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <system_error>

namespace ecorail::output {

namespace {

std::uint64_t fnv1a(const std::string& text) {
  std::uint64_t h = 1469598103934665603ULL;
  for (unsigned char c : text) {
    h ^= c;
    h *= 1099511628211ULL;
  }
  return h;
}

}  // namespace

FileSectionRunStore::FileSectionRunStore(std::filesystem::path directory)
    : directory_(std::move(directory)) {}

std::filesystem::path FileSectionRunStore::path_for(const std::string& key) const {
  char name[40];
  std::snprintf(name, sizeof name, "%016llx.run", static_cast<unsigned long long>(fnv1a(key)));
  return directory_ / name;
}

bool FileSectionRunStore::load(const std::string& key, recovery::SectionPiece* piece) {
  std::ifstream in(path_for(key));
  if (!in) return false;
  std::string stored;
  if (!std::getline(in, stored) || stored != key) return false;
  recovery::SectionPiece p;
  std::size_t count = 0;
  if (!(in >> p.time_s >> p.resimulated_time_s >> p.traction_uJ >> p.regen_uJ >> count) ||
      count > 10000000)
    return false;
  p.offsets.resize(count);
  p.traction.resize(count);
  p.regen.resize(count);
  std::int64_t tr = 0, rg = 0;
  for (std::size_t i = 0; i < count; ++i) {
    if (!(in >> p.offsets[i] >> p.traction[i] >> p.regen[i])) return false;
    tr += p.traction[i];
    rg += p.regen[i];
  }
  std::string end;
  if (!(in >> end) || end != "end" || tr != p.traction_uJ || rg != p.regen_uJ) return false;
  *piece = std::move(p);
  return true;
}

void FileSectionRunStore::save(const std::string& key, const recovery::SectionPiece& piece) {
  std::error_code ec;
  std::filesystem::create_directories(directory_, ec);
  const std::filesystem::path target = path_for(key);
  const std::filesystem::path tmp =
      target.string() + ".tmp" + std::to_string(static_cast<long>(::getpid()));
  {
    std::ofstream out(tmp);
    if (!out) return;  // a cache that cannot be written is no error: the run goes on
    out.precision(17);
    out << key << "\n"
        << piece.time_s << " " << piece.resimulated_time_s << " " << piece.traction_uJ << " "
        << piece.regen_uJ << " " << piece.offsets.size() << "\n";
    for (std::size_t i = 0; i < piece.offsets.size(); ++i)
      out << piece.offsets[i] << " " << piece.traction[i] << " " << piece.regen[i] << "\n";
    out << "end\n";
    if (!out) {
      std::filesystem::remove(tmp, ec);
      return;
    }
  }
  std::filesystem::rename(tmp, target, ec);
  if (ec) std::filesystem::remove(tmp, ec);
}

}  // namespace ecorail::output
