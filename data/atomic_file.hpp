// Writes output files so that they are either complete or absent, and never destroys anything
// but a regular file. Content goes to a temporary file beside the target, which is renamed over
// the target only when writing succeeded. An OutputBatch holds several such temporaries and
// renames them all only at commit(), so a run that fails after writing some outputs leaves none
// of them behind. A target that exists and is not a regular file (a directory, a symbolic link,
// a FIFO, a device) is refused, never replaced; the path "-" means standard output. Nor is an
// input of the same run ever replaced: the inputs are registered (register_input) and an output
// that is one of them, compared by file identity (device and inode; for an output not yet there
// its canonical path), is refused by every check here, before and at commit.
#pragma once

#include <filesystem>
#include <functional>
#include <ostream>
#include <string>
#include <vector>

namespace ecorail::data {

// The path that means standard output.
inline bool is_stdout_path(const std::filesystem::path& path) {
  return path == "-";
}

// Why path cannot take an output file, or "" when it can: it is a registered input of this run,
// its directory does not exist or is not writable, or the target exists and is not a regular
// file. "-" is always acceptable.
std::string output_target_problem(const std::filesystem::path& path);

// Registers path as an input of this run (process-wide), read through what (a flag such as
// "--plan", or a file name): no output may replace it. "-" and "" are ignored. Thread-safe.
void register_input(const std::string& what, const std::filesystem::path& path);
// read_text_file registers every file it reads when this is on (the program turns it on; a
// library caller that reads and rewrites one file in a process leaves it off).
void set_register_files_read(bool on);
bool register_files_read();
// What the registered input that path is reads it through ("--plan"), or "" when path is no
// registered input.
std::string input_read_as(const std::filesystem::path& path);
// Forgets every registered input (tests).
void clear_registered_inputs();

// Temporaries of several outputs, committed together. Not committed (an exception, an early
// return): the destructor removes every temporary and no target is touched.
class OutputBatch {
 public:
  OutputBatch() = default;
  OutputBatch(const OutputBatch&) = delete;
  OutputBatch& operator=(const OutputBatch&) = delete;
  ~OutputBatch();

  // Calls write(stream) on a temporary for path; throws (naming path) on any I/O failure.
  void add(const std::filesystem::path& path, const std::function<void(std::ostream&)>& write);
  // For writers that need a file name (libxlsxwriter, gnuplot): produce(tmp_path) must create
  // tmp_path.
  void add_produced(const std::filesystem::path& path,
                    const std::function<void(const std::filesystem::path&)>& produce);
  // Checks every target again, then renames every temporary onto its target (copies it to
  // standard output for "-"). Throws if a target became unsuitable; nothing is renamed then.
  void commit();

 private:
  struct Entry {
    std::filesystem::path target, tmp;  // tmp: empty for standard output
    std::string stdout_content;         // what goes to standard output at commit
    int fd = -1;  // an anonymous temporary (O_TMPFILE) behind tmp = /proc/PID/fd/N, or -1
  };
  std::vector<Entry> entries_;
  bool committed_ = false;
};

// One file: write(stream) on a temporary renamed to path; throws on any I/O failure or an
// unsuitable target and leaves no file behind.
void write_atomically(const std::filesystem::path& path,
                      const std::function<void(std::ostream&)>& write);
// One file produced by a writer that needs a file name (see OutputBatch::add_produced).
void produce_atomically(const std::filesystem::path& path,
                        const std::function<void(const std::filesystem::path&)>& produce);

}  // namespace ecorail::data
