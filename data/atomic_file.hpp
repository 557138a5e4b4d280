// Writes an output file so that it is either complete or absent: content goes to a temporary
// file beside the target, which is renamed over the target only when writing succeeded.
#pragma once

#include <filesystem>
#include <functional>
#include <ostream>
#include <string>

namespace ecorail::data {

// Calls write(stream) on a temporary file and renames it to path; throws on any I/O failure
// and leaves no file behind.
void write_atomically(const std::filesystem::path& path,
                      const std::function<void(std::ostream&)>& write);
// For writers that need a file name (libxlsxwriter, gnuplot): produce(tmp_path) must create
// tmp_path; it is renamed to path on success and removed on failure.
void produce_atomically(const std::filesystem::path& path,
                        const std::function<void(const std::filesystem::path&)>& produce);

}  // namespace ecorail::data
