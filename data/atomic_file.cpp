#include "data/atomic_file.hpp"

#include <fstream>
#include <stdexcept>
#include <system_error>

#include <unistd.h>

namespace ecorail::data {

namespace {
std::filesystem::path temp_beside(const std::filesystem::path& path) {
  std::filesystem::path tmp = path;
  tmp += ".tmp" + std::to_string(::getpid());
  return tmp;
}
}  // namespace

void produce_atomically(const std::filesystem::path& path,
                        const std::function<void(const std::filesystem::path&)>& produce) {
  const auto tmp = temp_beside(path);
  try {
    produce(tmp);
    if (!std::filesystem::exists(tmp)) throw std::runtime_error("nothing was written");
    std::filesystem::rename(tmp, path);
  } catch (const std::exception& ex) {
    std::error_code ignored;
    std::filesystem::remove(tmp, ignored);
    throw std::runtime_error("cannot write " + path.string() + ": " + ex.what());
  }
}

void write_atomically(const std::filesystem::path& path,
                      const std::function<void(std::ostream&)>& write) {
  produce_atomically(path, [&](const std::filesystem::path& tmp) {
    std::ofstream out(tmp, std::ios::binary);
    if (!out) throw std::runtime_error("cannot open for writing");
    write(out);
    out.flush();
    if (!out) throw std::runtime_error("write failed");
  });
}

}  // namespace ecorail::data
