#include "data/atomic_file.hpp"

#include <atomic>
#include <cerrno>
#include <cstring>
#include <fstream>
#include <iostream>
#include <mutex>
#include <sstream>
#include <stdexcept>
#include <system_error>

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include "data/input_error.hpp"

namespace ecorail::data {

namespace {

// Unique within the process (the frontier cache writes from several threads) and between
// processes (the pid), so two writers never share a temporary.
std::filesystem::path temp_for(const std::filesystem::path& target) {
  static std::atomic<unsigned> counter{0};
  const std::string suffix = ".tmp" + std::to_string(::getpid()) + "-" + std::to_string(++counter);
  if (is_stdout_path(target)) {
    return std::filesystem::temp_directory_path() / ("ecorail-stdout" + suffix);
  }
  std::filesystem::path tmp = target;
  tmp += suffix;
  return tmp;
}

void remove_quietly(const std::filesystem::path& p) {
  std::error_code ignored;
  std::filesystem::remove(p, ignored);
}

// An anonymous temporary in the target's directory (O_TMPFILE): it has no name until commit
// links it, so a process killed while writing (SIGKILL, the OOM killer) leaves nothing behind.
// Writers open it by the name /proc/PID/fd/N (gnuplot, a child, too). Returns -1 where the file
// system cannot (then the named temporary of temp_for is used).
int anonymous_temp(const std::filesystem::path& target, std::filesystem::path* name) {
  if (::access("/proc/self/fd", X_OK) != 0) return -1;
  std::filesystem::path dir = target.parent_path();
  if (dir.empty()) dir = ".";
  const int fd = ::open(dir.c_str(), O_TMPFILE | O_WRONLY | O_CLOEXEC, 0666);
  if (fd >= 0) {
    *name = "/proc/" + std::to_string(::getpid()) + "/fd/" + std::to_string(fd);
  }
  return fd;
}

// Gives the anonymous temporary a name next to the target (for the instant before the rename).
void link_anonymous(const std::filesystem::path& fd_name, const std::filesystem::path& tmp) {
  if (::linkat(AT_FDCWD, fd_name.c_str(), AT_FDCWD, tmp.c_str(), AT_SYMLINK_FOLLOW) != 0) {
    throw std::runtime_error(std::strerror(errno));
  }
}

// An input of this run: the file's identity when it existed at registration (device and inode,
// so that any spelling or hard link of it matches) and its canonical path.
struct RegisteredInput {
  std::string what;
  std::filesystem::path canonical;
  bool has_identity = false;
  dev_t device = 0;
  ino_t inode = 0;
};

std::mutex inputs_mutex;
std::vector<RegisteredInput> registered_inputs;
std::atomic<bool> register_reads{false};

std::filesystem::path canonical_of(const std::filesystem::path& path) {
  std::error_code ec;
  const auto absolute = std::filesystem::absolute(path, ec);
  if (ec) return path.lexically_normal();
  const auto canonical = std::filesystem::weakly_canonical(absolute, ec);
  return ec ? absolute.lexically_normal() : canonical;
}

// An output that would replace an input of the run is bad input (exit 2), whenever it is found.
void check_not_an_input(const std::filesystem::path& path) {
  const std::string what = input_read_as(path);
  if (!what.empty()) {
    throw InputError(
        path.string(), 0, "",
        "an output other than an input of this run (" + what + "); the input was left as it is");
  }
}

void check_target(const std::filesystem::path& path) {
  const std::string problem = output_target_problem(path);
  if (!problem.empty()) throw std::runtime_error(problem);
}

}  // namespace

void register_input(const std::string& what, const std::filesystem::path& path) {
  if (path.empty() || is_stdout_path(path)) return;
  RegisteredInput input{what, canonical_of(path)};
  struct stat st {};
  if (::stat(path.c_str(), &st) == 0) {
    input.has_identity = true;
    input.device = st.st_dev;
    input.inode = st.st_ino;
  }
  const std::lock_guard<std::mutex> lock(inputs_mutex);
  for (const RegisteredInput& known : registered_inputs) {
    const bool same = input.has_identity && known.has_identity
                          ? known.device == input.device && known.inode == input.inode
                          : known.canonical == input.canonical;
    if (same) return;  // the first name it was given is the one reported
  }
  registered_inputs.push_back(std::move(input));
}

void set_register_files_read(bool on) {
  register_reads = on;
}

bool register_files_read() {
  return register_reads;
}

std::string input_read_as(const std::filesystem::path& path) {
  if (path.empty() || is_stdout_path(path)) return "";
  struct stat st {};
  const bool exists = ::stat(path.c_str(), &st) == 0;
  const std::filesystem::path canonical = canonical_of(path);
  const std::lock_guard<std::mutex> lock(inputs_mutex);
  for (const RegisteredInput& input : registered_inputs) {
    const bool same = exists && input.has_identity
                          ? st.st_dev == input.device && st.st_ino == input.inode
                          : canonical == input.canonical;
    if (same) return input.what;
  }
  return "";
}

void clear_registered_inputs() {
  const std::lock_guard<std::mutex> lock(inputs_mutex);
  registered_inputs.clear();
}

std::string output_target_problem(const std::filesystem::path& path) {
  if (is_stdout_path(path)) return "";
  if (path.empty()) return "an empty path";
  if (const std::string what = input_read_as(path); !what.empty()) {
    return "'" + path.string() + "' is an input of this run (" + what +
           "); an output never replaces an input";
  }
  std::error_code ec;
  const auto st = std::filesystem::symlink_status(path, ec);
  if (!ec && std::filesystem::exists(st)) {
    if (std::filesystem::is_directory(st)) return "'" + path.string() + "' is a directory";
    if (std::filesystem::is_symlink(st)) {
      return "'" + path.string() +
             "' is a symbolic link (only regular files are replaced; '-' writes to standard "
             "output)";
    }
    if (!std::filesystem::is_regular_file(st)) {
      return "'" + path.string() +
             "' is not a regular file (a FIFO, a device or a socket is never replaced; '-' "
             "writes to standard output)";
    }
  }
  std::filesystem::path dir = path.parent_path();
  if (dir.empty()) dir = ".";
  if (!std::filesystem::is_directory(dir, ec)) {
    return "directory '" + dir.string() + "' does not exist";
  }
  if (::access(dir.c_str(), W_OK | X_OK) != 0) {
    return "directory '" + dir.string() + "' is not writable";
  }
  return "";
}

OutputBatch::~OutputBatch() {
  for (const auto& e : entries_) {
    if (e.fd >= 0) {
      ::close(e.fd);  // an anonymous temporary vanishes with its last descriptor
    } else if (!committed_ && !e.tmp.empty()) {
      remove_quietly(e.tmp);
    }
  }
}

void OutputBatch::add(const std::filesystem::path& path,
                      const std::function<void(std::ostream&)>& write) {
  add_produced(path, [&](const std::filesystem::path& tmp) {
    std::ofstream out(tmp, std::ios::binary);
    if (!out) throw std::runtime_error("cannot open for writing");
    write(out);
    out.flush();
    if (!out) throw std::runtime_error(std::string("write failed: ") + std::strerror(errno));
    out.close();
    if (!out) throw std::runtime_error(std::string("write failed: ") + std::strerror(errno));
  });
}

void OutputBatch::add_produced(const std::filesystem::path& path,
                               const std::function<void(const std::filesystem::path&)>& produce) {
  std::filesystem::path tmp = temp_for(path);
  int fd = -1;
  check_not_an_input(path);
  try {
    check_target(path);
    if (!is_stdout_path(path)) fd = anonymous_temp(path, &tmp);
    produce(tmp);
    std::error_code ec;
    const auto st =
        fd >= 0 ? std::filesystem::status(tmp, ec) : std::filesystem::symlink_status(tmp, ec);
    if (!std::filesystem::is_regular_file(st)) {
      throw std::runtime_error("nothing was written");
    }
  } catch (const std::exception& ex) {
    if (fd >= 0) {
      ::close(fd);
    } else {
      remove_quietly(tmp);
    }
    throw std::runtime_error("cannot write " + path.string() + ": " + ex.what());
  }
  if (fd >= 0) {
    entries_.push_back({path, tmp, {}, fd});
    return;
  }
  if (is_stdout_path(path)) {
    // Held in memory until commit: a temporary file outside the target's directory could be
    // left behind when standard output is a closed pipe (SIGPIPE ends the process).
    std::ifstream in(tmp, std::ios::binary);
    std::ostringstream content;
    content << in.rdbuf();
    in.close();
    remove_quietly(tmp);
    entries_.push_back({path, {}, content.str()});
    return;
  }
  entries_.push_back({path, tmp, {}});
}

void OutputBatch::commit() {
  // Everything is written; only the targets may have changed since they were checked.
  for (const auto& e : entries_) check_not_an_input(e.target);
  for (const auto& e : entries_) {
    const std::string problem = output_target_problem(e.target);
    if (!problem.empty())
      throw std::runtime_error("cannot write " + e.target.string() + ": " + problem);
  }
  for (const auto& e : entries_) {
    if (is_stdout_path(e.target)) {
      std::cout.flush();
      std::cout << e.stdout_content;
      std::cout.flush();
      if (!std::cout) throw std::runtime_error("cannot write to standard output");
      continue;
    }
    std::error_code ec;
    if (e.fd >= 0) {
      const auto named = temp_for(e.target);
      try {
        link_anonymous(e.tmp, named);
      } catch (const std::exception& ex) {
        throw std::runtime_error("cannot write " + e.target.string() + ": " + ex.what());
      }
      std::filesystem::rename(named, e.target, ec);
      if (ec) remove_quietly(named);
    } else {
      std::filesystem::rename(e.tmp, e.target, ec);
    }
    if (ec) {
      throw std::runtime_error("cannot write " + e.target.string() + ": " + ec.message());
    }
  }
  committed_ = true;
}

void write_atomically(const std::filesystem::path& path,
                      const std::function<void(std::ostream&)>& write) {
  OutputBatch batch;
  batch.add(path, write);
  batch.commit();
}

void produce_atomically(const std::filesystem::path& path,
                        const std::function<void(const std::filesystem::path&)>& produce) {
  OutputBatch batch;
  batch.add_produced(path, produce);
  batch.commit();
}

}  // namespace ecorail::data
