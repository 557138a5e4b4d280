// Shared helpers of the data-layer tests: temporary directories, copies of the contest line
// with edits, and a check that an InputError names the expected file, row and field.
#pragma once

#include <gtest/gtest.h>
#include <unistd.h>

#include <atomic>
#include <filesystem>
#include <fstream>
#include <functional>
#include <sstream>
#include <string>

#include "data/input_error.hpp"

namespace ecorail::data::test {

inline std::filesystem::path contest_dir() {
  return std::filesystem::path(ECORAIL_SOURCE_DIR) / "data" / "contest";
}

inline std::string read_file(const std::filesystem::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream out;
  out << in.rdbuf();
  return out.str();
}

inline void write_file(const std::filesystem::path& p, const std::string& text) {
  std::ofstream out(p, std::ios::binary);
  out << text;
}

// A fresh directory under the system temp directory, removed with everything in it.
class TempDir {
 public:
  TempDir() {
    static std::atomic<int> counter{0};
    path_ = std::filesystem::temp_directory_path() /
            ("ecorail_data_test_" + std::to_string(::getpid()) + "_" + std::to_string(counter++));
    std::filesystem::remove_all(path_);
    std::filesystem::create_directories(path_);
  }
  ~TempDir() {
    std::error_code ec;
    std::filesystem::remove_all(path_, ec);
  }
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;
  const std::filesystem::path& path() const { return path_; }
  std::filesystem::path operator/(const std::string& name) const { return path_ / name; }

 private:
  std::filesystem::path path_;
};

// Copies the four contest CSV tables into dir.
inline void copy_contest_line(const std::filesystem::path& dir) {
  for (const char* name : {"stations.csv", "gradients.csv", "speed_limits.csv", "curves.csv"}) {
    std::filesystem::copy_file(contest_dir() / name, dir / name,
                               std::filesystem::copy_options::overwrite_existing);
  }
}

// Replaces the first occurrence of from by to in a file; fails the test if from is absent.
inline void edit_file(const std::filesystem::path& p, const std::string& from,
                      const std::string& to) {
  std::string text = read_file(p);
  const auto pos = text.find(from);
  ASSERT_NE(pos, std::string::npos) << "'" << from << "' not in " << p;
  text.replace(pos, from.size(), to);
  write_file(p, text);
}

// Runs f, which must throw an InputError for file (compared by full string), row and field; the
// message must name all three and contain every fragment of what.
inline void expect_input_error(const std::function<void()>& f, const std::string& file, int row,
                               const std::string& field,
                               std::initializer_list<std::string> what = {}) {
  try {
    f();
    ADD_FAILURE() << "no InputError thrown (expected one for " << file << ")";
  } catch (const InputError& e) {
    const std::string msg = e.what();
    EXPECT_EQ(e.file(), file) << msg;
    EXPECT_EQ(e.row(), row) << msg;
    EXPECT_EQ(e.field(), field) << msg;
    EXPECT_EQ(msg.rfind(file + ": ", 0), 0u) << msg;
    if (row > 0) {
      EXPECT_NE(msg.find("row " + std::to_string(row)), std::string::npos) << msg;
    } else {
      EXPECT_EQ(msg.find(": row "), std::string::npos) << msg;
    }
    if (!field.empty()) {
      EXPECT_NE(msg.find("field '" + field + "'"), std::string::npos) << msg;
    }
    EXPECT_NE(msg.find("expected "), std::string::npos) << msg;
    for (const auto& w : what) EXPECT_NE(msg.find(w), std::string::npos) << msg;
  }
}

}  // namespace ecorail::data::test
