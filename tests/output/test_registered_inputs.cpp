// No output replaces an input of the same run: a registered input is refused as an output
// target by file identity (any spelling, a hard link), or for a target not yet there by its
// canonical path, by the check before the work and by OutputBatch (InputError, exit 2).
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>

#include "data/atomic_file.hpp"
#include "data/csv_reader.hpp"
#include "data/input_error.hpp"
#include "temp_dir_test.hpp"

namespace ecorail::data {
namespace {

class RegisteredInputs : public ecorail::testing::TempDirTest {
 protected:
  void SetUp() override {
    TempDirTest::SetUp();
    clear_registered_inputs();
    std::ofstream(dir_ / "in.csv") << "a,b\n1,2\n";
    std::filesystem::create_directory(dir_ / "sub");
  }
  void TearDown() override {
    clear_registered_inputs();
    set_register_files_read(false);
    TempDirTest::TearDown();
  }
  std::string content(const std::filesystem::path& p) {
    std::ifstream in(p);
    return std::string(std::istreambuf_iterator<char>(in), {});
  }
};

TEST_F(RegisteredInputs, AnyNameOfTheFileIsRefused) {
  EXPECT_EQ(output_target_problem(dir_ / "in.csv"), "");
  register_input("--plan", dir_ / "in.csv");
  ASSERT_EQ(::link((dir_ / "in.csv").c_str(), (dir_ / "hard.csv").c_str()), 0);
  for (const auto& name : {dir_ / "in.csv", dir_ / "sub" / ".." / "in.csv", dir_ / "." / "in.csv",
                           dir_ / "hard.csv"}) {
    EXPECT_EQ(input_read_as(name), "--plan") << name;
    const std::string problem = output_target_problem(name);
    EXPECT_NE(problem.find("input of this run (--plan)"), std::string::npos) << problem;
  }
  EXPECT_EQ(input_read_as(dir_ / "other.csv"), "");
  EXPECT_EQ(output_target_problem(dir_ / "other.csv"), "");
  EXPECT_EQ(input_read_as("-"), "");
}

TEST_F(RegisteredInputs, AnInputNotYetThereIsMatchedByItsPath) {
  register_input("--headways", dir_ / "later.csv");
  EXPECT_EQ(input_read_as(dir_ / "sub" / ".." / "later.csv"), "--headways");
}

TEST_F(RegisteredInputs, OutputBatchRefusesAndLeavesTheInput) {
  const std::string before = content(dir_ / "in.csv");
  {
    OutputBatch batch;
    batch.add(dir_ / "out.csv", [](std::ostream& out) { out << "x\n"; });
    register_input("a file this run reads", dir_ / "in.csv");  // found while the run worked
    EXPECT_THROW(batch.add(dir_ / "in.csv", [](std::ostream& out) { out << "x\n"; }), InputError);
  }
  EXPECT_EQ(content(dir_ / "in.csv"), before);
  EXPECT_FALSE(std::filesystem::exists(dir_ / "out.csv"));
  // An input registered between the writing and the commit is caught at commit.
  clear_registered_inputs();
  OutputBatch batch;
  batch.add(dir_ / "in.csv", [](std::ostream& out) { out << "x\n"; });
  register_input("--plan", dir_ / "in.csv");
  EXPECT_THROW(batch.commit(), InputError);
  EXPECT_EQ(content(dir_ / "in.csv"), before);
}

TEST_F(RegisteredInputs, FilesReadAreRegisteredOnlyWhenAskedFor) {
  read_text_file(dir_ / "in.csv");
  EXPECT_EQ(input_read_as(dir_ / "in.csv"), "");  // a library caller may rewrite what it read
  set_register_files_read(true);
  read_text_file(dir_ / "in.csv");
  EXPECT_EQ(input_read_as(dir_ / "in.csv"), "a file this run reads");
}

}  // namespace
}  // namespace ecorail::data
