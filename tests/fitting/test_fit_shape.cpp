// The fits report as every solver does: a Ceres termination becomes a dp::Termination (only
// Ceres' CONVERGENCE and USER_SUCCESS converge), and the options are checked up front by IsValid
// with one sentence naming the field.
#include <gtest/gtest.h>

#include <string>

#include "fitting/calibration.hpp"
#include "fitting/envelope_fit.hpp"
#include "fitting/formulation.hpp"

namespace ecorail::fitting {
namespace {

TEST(FitShape, CeresTerminationsMapToTheLibrarys) {
  EXPECT_EQ(termination_of_ceres(ceres::CONVERGENCE), dp::Termination::CONVERGENCE);
  EXPECT_EQ(termination_of_ceres(ceres::USER_SUCCESS), dp::Termination::CONVERGENCE);
  EXPECT_EQ(termination_of_ceres(ceres::NO_CONVERGENCE), dp::Termination::NO_CONVERGENCE);
  EXPECT_EQ(termination_of_ceres(ceres::FAILURE), dp::Termination::FAILURE);
  EXPECT_EQ(termination_of_ceres(ceres::USER_FAILURE), dp::Termination::FAILURE);
  FitResult fit;
  EXPECT_FALSE(fit.converged());
  fit.termination = dp::Termination::NO_CONVERGENCE;
  EXPECT_FALSE(fit.converged());
  fit.termination = dp::Termination::CONVERGENCE;
  EXPECT_TRUE(fit.converged());
}

TEST(FitShape, CalibrationOptionsNameTheFirstBadField) {
  std::string why;
  EXPECT_TRUE(CalibrationOptions{}.IsValid(&why)) << why;
  auto refused = [](CalibrationOptions o, const std::string& field) {
    std::string error;
    EXPECT_FALSE(o.IsValid(&error)) << field;
    EXPECT_NE(error.find(field), std::string::npos) << error;
  };
  CalibrationOptions o;
  o.loss_scale = 0.0;
  refused(o, "loss_scale");
  o = {};
  o.discount_weight = 1.5;
  refused(o, "discount_weight");
  o = {};
  o.robust_passes = 0;
  refused(o, "robust_passes");
  o = {};
  o.max_iterations = 0;
  refused(o, "max_iterations");
  o = {};
  o.num_threads = 0;
  refused(o, "num_threads");
  o = {};
  o.output_error.segment_rows = 0;
  refused(o, "segment_rows");
}

TEST(FitShape, EnvelopeDegreeOutsideOneToSixIsRefused) {
  std::string why;
  EnvelopeFitOptions o;
  EXPECT_TRUE(o.IsValid(&why)) << why;
  for (int degree : {0, 7}) {
    o.degree = degree;
    EXPECT_FALSE(o.IsValid(&why));
    EXPECT_EQ(why, "a polynomial degree from 1 to 6; got " + std::to_string(degree));
  }
}

}  // namespace
}  // namespace ecorail::fitting
