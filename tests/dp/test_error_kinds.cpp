// Every error a user can cause is an ecorail::Error (base/error.hpp) with its kind and context,
// beside the standard exception it always was: the program maps kinds to exit codes in one place
// (cli/errors.cpp), and callers that catch std::invalid_argument or std::runtime_error still
// catch the same errors.
#include <gtest/gtest.h>

#include <stdexcept>
#include <string>

#include "base/error.hpp"
#include "data/input_error.hpp"
#include "dp/journey_plan.hpp"
#include "dp/resource_estimate.hpp"
#include "dp/time_target.hpp"

namespace ecorail {
namespace {

template <typename Thrown, typename Caught>
const Error* caught_as_error(const Thrown& error) {
  try {
    throw error;
  } catch (const Caught& standard) {
    return dynamic_cast<const Error*>(&standard);
  }
  return nullptr;
}

TEST(ErrorKinds, InputErrorCarriesItsFileRowAndFieldAsContext) {
  const data::InputError e("stations.csv", 4, "position_m", "a number");
  const Error* error = caught_as_error<data::InputError, std::runtime_error>(e);
  ASSERT_NE(error, nullptr);
  EXPECT_EQ(error->kind(), ErrorKind::kBadInput);
  EXPECT_EQ(error->context().file, "stations.csv");
  EXPECT_EQ(error->context().row, 4);
  EXPECT_EQ(error->context().field, "position_m");
  EXPECT_STREQ(e.what(), "stations.csv: row 4, field 'position_m': expected a number");
}

TEST(ErrorKinds, RunningTimeDwellAndResourceErrorsKeepTheirStandardBases) {
  const Error* infeasible = caught_as_error<dp::InfeasibleTimeError, std::invalid_argument>(
      dp::InfeasibleTimeError(80.0, 85.5, "A6 -> A7 (flat-out run)"));
  ASSERT_NE(infeasible, nullptr);
  EXPECT_EQ(infeasible->kind(), ErrorKind::kRunningTime);
  const Error* longer =
      caught_as_error<dp::LongTimeError, std::invalid_argument>(dp::LongTimeError(900.0, 600.0));
  ASSERT_NE(longer, nullptr);
  EXPECT_EQ(longer->kind(), ErrorKind::kRunningTime);
  const Error* dwell =
      caught_as_error<dp::DwellError, std::invalid_argument>(dp::DwellError("a dwell for A7"));
  ASSERT_NE(dwell, nullptr);
  EXPECT_EQ(dwell->kind(), ErrorKind::kDwell);
  const Error* resource = caught_as_error<dp::ResourceLimitError, std::runtime_error>(
      dp::ResourceLimitError("grid too fine"));
  ASSERT_NE(resource, nullptr);
  EXPECT_EQ(resource->kind(), ErrorKind::kResourceLimit);
  EXPECT_TRUE(resource->context().file.empty());
}

TEST(ErrorKinds, EveryKindHasItsOwnName) {
  const ErrorKind kinds[] = {ErrorKind::kBadInput,       ErrorKind::kInvalidOptions,
                             ErrorKind::kRunningTime,    ErrorKind::kDwell,
                             ErrorKind::kResourceLimit,  ErrorKind::kPolicyFormat,
                             ErrorKind::kPolicyMismatch, ErrorKind::kNotConverged};
  for (const ErrorKind a : kinds) {
    for (const ErrorKind b : kinds) {
      if (a != b) {
        EXPECT_NE(error_kind_name(a), error_kind_name(b));
      }
    }
  }
}

}  // namespace
}  // namespace ecorail
