// Output integrity: outputs are committed together or not at all, only
// regular files are ever replaced (a symbolic link such as /dev/stdout, a FIFO, a device or a
// directory is refused and left as it was), "-" is standard output, and no temporary file is
// left behind.
#include <gtest/gtest.h>

#include <sys/stat.h>
#include <unistd.h>

#include <fstream>
#include <sstream>
#include <stdexcept>

#include "data/atomic_file.hpp"
#include "temp_dir_test.hpp"

namespace ecorail::data {
namespace {

class OutputBatchTest : public ecorail::testing::TempDirTest {
 protected:
  std::size_t entries() const {
    return static_cast<std::size_t>(std::distance(std::filesystem::directory_iterator(dir_),
                                                  std::filesystem::directory_iterator()));
  }
};

std::string read_file(const std::filesystem::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

auto writes(const std::string& text) {
  return [text](std::ostream& out) { out << text; };
}

TEST_F(OutputBatchTest, NothingIsWrittenUntilCommitAndAllThen) {
  {
    OutputBatch batch;
    batch.add(dir_ / "a.json", writes("a"));
    batch.add(dir_ / "b.csv", writes("b"));
    EXPECT_FALSE(std::filesystem::exists(dir_ / "a.json"));
    batch.commit();
  }
  EXPECT_EQ(read_file(dir_ / "a.json"), "a");
  EXPECT_EQ(read_file(dir_ / "b.csv"), "b");
  EXPECT_EQ(entries(), 2u);  // no temporary left
}

TEST_F(OutputBatchTest, AFailedOutputLeavesNoneBehind) {
  { std::ofstream(dir_ / "old.json") << "old"; }
  EXPECT_THROW(
      {
        OutputBatch batch;
        batch.add(dir_ / "old.json", writes("new"));
        batch.add(dir_ / "b.csv", writes("b"));
        batch.add_produced(dir_ / "c.svg", [](const std::filesystem::path&) {
          throw std::runtime_error("gnuplot failed");
        });
        batch.commit();
      },
      std::runtime_error);
  EXPECT_EQ(read_file(dir_ / "old.json"), "old");
  EXPECT_FALSE(std::filesystem::exists(dir_ / "b.csv"));
  EXPECT_EQ(entries(), 1u);
}

TEST_F(OutputBatchTest, OnlyRegularFilesAreReplaced) {
  std::ofstream(dir_ / "target.json") << "kept";
  std::filesystem::create_symlink(dir_ / "target.json", dir_ / "link.json");
  ASSERT_EQ(::mkfifo((dir_ / "fifo").c_str(), 0600), 0);
  std::filesystem::create_directory(dir_ / "sub");
  for (const char* name : {"link.json", "fifo", "sub"}) {
    EXPECT_NE(output_target_problem(dir_ / name), "") << name;
    EXPECT_THROW(write_atomically(dir_ / name, writes("x")), std::runtime_error) << name;
  }
  EXPECT_TRUE(std::filesystem::is_symlink(dir_ / "link.json"));
  EXPECT_EQ(read_file(dir_ / "target.json"), "kept");
  EXPECT_TRUE(std::filesystem::is_fifo(dir_ / "fifo"));
  EXPECT_TRUE(std::filesystem::is_directory(dir_ / "sub"));
  // The symbolic link /dev/stdout and the device /dev/null are never replaced.
  EXPECT_NE(output_target_problem("/dev/stdout"), "");
  EXPECT_NE(output_target_problem("/dev/null"), "");
  EXPECT_EQ(entries(), 4u);
}

TEST_F(OutputBatchTest, MissingDirectoryIsNamed) {
  const std::string problem = output_target_problem(dir_ / "no" / "x.json");
  EXPECT_NE(problem.find("does not exist"), std::string::npos) << problem;
  EXPECT_EQ(output_target_problem(dir_ / "x.json"), "");
}

TEST_F(OutputBatchTest, DashIsStandardOutputAndLeavesNoTemporary) {
  const auto tmp_entries = [] {
    std::size_t n = 0;
    for (const auto& e :
         std::filesystem::directory_iterator(std::filesystem::temp_directory_path()))
      n += e.path().filename().string().rfind("ecorail-stdout", 0) == 0;
    return n;
  };
  const std::size_t before = tmp_entries();
  ::testing::internal::CaptureStdout();
  {
    OutputBatch batch;
    batch.add("-", writes("to stdout\n"));
    batch.add_produced(
        "-", [](const std::filesystem::path& tmp) { std::ofstream(tmp) << "produced\n"; });
    batch.commit();
  }
  EXPECT_EQ(::testing::internal::GetCapturedStdout(), "to stdout\nproduced\n");
  EXPECT_FALSE(std::filesystem::exists("-"));
  EXPECT_EQ(tmp_entries(), before);
}

}  // namespace
}  // namespace ecorail::data
