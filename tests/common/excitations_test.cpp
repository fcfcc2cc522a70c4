// The excitations the solver consumes, against their closed forms.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "records/excitations.h"
#include "solver/common/error.h"

namespace skewbridge::records::excitations_test {
namespace {

TEST(PulseExcitation, CosinePulseIsOneCycleThenRest) {
  const double a_g = 3.0;
  const double w_g = 2.0 * std::numbers::pi;  // period 1 s
  const PulseExcitation pulse(PulseShape::kCosine, a_g, w_g);
  EXPECT_DOUBLE_EQ(pulse.Duration(), 1.0);
  for (double t : {0.0, 0.1, 0.37, 0.5, 0.999}) {
    EXPECT_NEAR(pulse.At(t).x(), a_g * std::cos(w_g * t), 1e-14) << t;
    EXPECT_EQ(pulse.At(t).y(), 0.0);
  }
  EXPECT_EQ(pulse.At(1.0).x(), 0.0);
  EXPECT_EQ(pulse.At(5.0).x(), 0.0);
  EXPECT_DOUBLE_EQ(pulse.PieceAt(0.3).t_end, 1.0);
}

TEST(PulseExcitation, SinePulseAlongAGivenDirection) {
  const Eigen::Vector2d dir(0.6, 0.8);
  const PulseExcitation pulse(PulseShape::kSine, 2.0, 4.0, dir);
  const double t = 0.3;
  EXPECT_NEAR(pulse.At(t).x(), 0.6 * 2.0 * std::sin(4.0 * t), 1e-14);
  EXPECT_NEAR(pulse.At(t).y(), 0.8 * 2.0 * std::sin(4.0 * t), 1e-14);
}

TEST(PulseExcitation, RejectsNonPositiveFrequency) {
  EXPECT_THROW(PulseExcitation(PulseShape::kCosine, 1.0, 0.0), InputError);
  EXPECT_THROW(PulseExcitation(PulseShape::kCosine, 1.0, -2.0), InputError);
  EXPECT_THROW(PulseExcitation(PulseShape::kCosine, NAN, 2.0), InputError);
}

TEST(SampledExcitation, InterpolatesLinearlyAndKinksAtSamples) {
  const SampledExcitation record(0.5, {0.0, 1.0, -1.0, 2.0});
  EXPECT_DOUBLE_EQ(record.Duration(), 1.5);
  EXPECT_DOUBLE_EQ(record.At(0.25).x(), 0.5);
  EXPECT_DOUBLE_EQ(record.At(0.75).x(), 0.0);
  EXPECT_DOUBLE_EQ(record.At(1.0).x(), -1.0);
  EXPECT_DOUBLE_EQ(record.At(1.25).x(), 0.5);
  const ExcitationPiece piece = record.PieceAt(0.5);  // a kink starts the next piece
  EXPECT_DOUBLE_EQ(piece.t_begin, 0.5);
  EXPECT_DOUBLE_EQ(piece.t_end, 1.0);
  EXPECT_DOUBLE_EQ(piece.slope.x(), -4.0);
  EXPECT_EQ(record.At(1.6).x(), 0.0);  // at rest after the record
}

TEST(SampledExcitation, RejectsBadInput) {
  EXPECT_THROW(SampledExcitation(0.0, {1.0}), InputError);
  EXPECT_THROW(SampledExcitation(0.01, {}), InputError);
  EXPECT_THROW(SampledExcitation(0.01, {1.0, NAN}), InputError);
  EXPECT_THROW(SampledExcitation(0.01, {1.0, 2.0}, {1.0}), InputError);
}

}  // namespace
}  // namespace skewbridge::records::excitations_test
