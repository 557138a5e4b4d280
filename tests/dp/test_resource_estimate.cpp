// Resource limits: the memory estimate made before a grid is built is an upper bound
// of the grid's real node count and within 1.5 times it; a grid beyond the memory this process can
// have is refused at once (ResourceLimitError naming ds and dv and the estimate), not after minutes
// of allocation; thread counts are bounded; a frontier of millions of points is refused by its
// options before any solve.
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>

#include "../output/temp_dir_test.hpp"
#include "data/line_loader.hpp"
#include "data/route_builder.hpp"
#include "data/train_io.hpp"
#include "dp/frontier.hpp"
#include "dp/resource_estimate.hpp"
#include "dp/section_engine.hpp"
#include "dp/threads.hpp"

namespace ecorail {
namespace {

struct ReferenceSection {
  physics::Train train = data::default_train();
  physics::Route route = data::build_route(data::default_line(), "A6", "A7", train);
};

TEST(ResourceEstimate, BoundsTheRealNodeCountWithinHalfAgain) {
  const ReferenceSection s;
  for (const dp::GridSpec grid : {dp::GridSpec{20.0, 1.0, 10.0}, dp::GridSpec{5.0, 0.2, 2.5}}) {
    dp::EngineOptions o;
    o.grid = grid;
    const dp::SectionEngine engine(s.train, s.route, o);
    const dp::EngineFootprint f =
        dp::estimate_engine(s.train, s.route, grid, o.envelope_resolution_m);
    const double real = engine.grid().total_nodes();
    EXPECT_GE(f.nodes, real) << grid.ds_m;
    EXPECT_LE(f.nodes, 1.5 * real) << grid.ds_m;
    EXPECT_EQ(f.stages, engine.grid().stage_count());
  }
}

TEST(ResourceEstimate, AGridBeyondMemoryIsRefusedAtOnceNamingTheSteps) {
  const ReferenceSection s;
  dp::EngineOptions o;
  o.grid = {0.001, 0.001, 0.001};  // about 6e10 nodes: no machine holds that
  const auto t0 = std::chrono::steady_clock::now();
  try {
    const dp::SectionEngine engine(s.train, s.route, o);
    ADD_FAILURE() << "a grid of " << engine.grid().total_nodes() << " nodes was built";
  } catch (const dp::ResourceLimitError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("ds 0.001 m"), std::string::npos) << what;
    EXPECT_NE(what.find("dv 0.001 km/h"), std::string::npos) << what;
    EXPECT_NE(what.find("GB"), std::string::npos) << what;
  }
  EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count(), 5.0);
}

TEST(ResourceEstimate, ThreadCountsAreBounded) {
  dp::EngineOptions o;
  o.threads = dp::kMaxThreads;
  EXPECT_TRUE(o.IsValid(nullptr));
  o.threads = 1000000000;
  std::string why;
  EXPECT_FALSE(o.IsValid(&why));
  EXPECT_NE(why.find("1024"), std::string::npos) << why;
  const int before = omp_get_max_threads();
  {
    const dp::ThreadScope scope(1000000000);
    EXPECT_EQ(omp_get_max_threads(), dp::kMaxThreads);
  }
  EXPECT_EQ(omp_get_max_threads(), before);
}

TEST(ResourceEstimate, AFrontierOfTooManyPointsIsRefusedByItsOptions) {
  dp::FrontierOptions o;
  o.step_s = 1e-9;
  EXPECT_FALSE(o.IsValid(nullptr));
  o.step_s = 1.0;
  o.t_max_s = 1e9;
  EXPECT_FALSE(o.IsValid(nullptr));
  o.t_max_s = 200.0;
  o.step_s = 0.1;
  EXPECT_TRUE(o.IsValid(nullptr));
}

}  // namespace
}  // namespace ecorail

namespace ecorail::dp {
namespace {

// A fake root with /proc/self/cgroup and the limit files of a container.
class CgroupLimit : public testing::TempDirTest {
 protected:
  void write(const std::string& path, const std::string& text) {
    std::filesystem::create_directories((dir_ / path).parent_path());
    std::ofstream(dir_ / path) << text;
  }
};

TEST_F(CgroupLimit, V2GroupLimitIsRead) {
  write("proc/self/cgroup", "0::/job/42\n");
  write("sys/fs/cgroup/memory.max", "max\n");
  write("sys/fs/cgroup/job/42/memory.max", "1073741824\n");
  EXPECT_EQ(cgroup_memory_limit_bytes(dir_.string()), 1073741824.0);
}

TEST_F(CgroupLimit, V1LimitAtTheMountRootWhenTheGroupIsNotVisible) {
  // As in a container: the group's path is not under the namespaced mount; its root has it.
  write("proc/self/cgroup", "5:cpu:/\n4:memory:/process_api/abc\n0::/\n");
  write("sys/fs/cgroup/memory/memory.limit_in_bytes", "2147483648\n");
  EXPECT_EQ(cgroup_memory_limit_bytes(dir_.string()), 2147483648.0);
}

TEST_F(CgroupLimit, NoLimitIsInfinite) {
  write("proc/self/cgroup", "4:memory:/\n0::/\n");
  write("sys/fs/cgroup/memory/memory.limit_in_bytes", "9223372036854771712\n");
  write("sys/fs/cgroup/memory.max", "max\n");
  EXPECT_TRUE(std::isinf(cgroup_memory_limit_bytes(dir_.string())));
  EXPECT_TRUE(std::isinf(cgroup_memory_limit_bytes((dir_ / "nothing-here").string())));
  // The process's own limit is never above what the machine has.
  EXPECT_LE(memory_limit_bytes(), cgroup_memory_limit_bytes());
}

}  // namespace
}  // namespace ecorail::dp
