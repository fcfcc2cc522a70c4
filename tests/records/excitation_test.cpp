// A record as the solver's excitation: the samples are the kinks and the values between them
// are the linear interpolation of the record read from its file.
#include <gtest/gtest.h>

#include <filesystem>

#include "records/excitations.h"
#include "records/ground_motion.h"
#include "solver/common/error.h"

namespace skewbridge::records {
namespace {

TEST(ToExcitation, ReproducesTheRecordAtSamplesAndInterpolatesBetween) {
  const GroundMotion m =
      ReadRecord(std::filesystem::path(SKEWBRIDGE_TEST_DATA_DIR) / "records" / "NIS090.AT2");
  const SampledExcitation ex = ToExcitation(m);
  EXPECT_DOUBLE_EQ(ex.Duration(), (m.npts() - 1) * m.dt_s);
  for (const std::size_t k : {0ul, 1ul, 1000ul, 4094ul}) {
    const double t = static_cast<double>(k) * m.dt_s;
    EXPECT_NEAR(ex.At(t).x(), m.acc_mps2[k], 1e-15);
    EXPECT_NEAR(ex.PieceAt(t).t_end, t + m.dt_s, 1e-12);  // the next sample is a kink
    EXPECT_NEAR(ex.At(t + 0.25 * m.dt_s).x(), 0.75 * m.acc_mps2[k] + 0.25 * m.acc_mps2[k + 1],
                1e-12);  // t itself is rounded
  }
  EXPECT_EQ(ex.At(m.npts() * m.dt_s + 1.0).x(), 0.0);
}

TEST(ToExcitation, SplitsTheRecordAlongADirection) {
  GroundMotion m;
  m.dt_s = 0.1;
  m.acc_mps2 = {1.0, -2.0, 3.0};
  const SampledExcitation ex = ToExcitation(m, Eigen::Vector2d(0.6, 0.8));
  EXPECT_NEAR(ex.At(0.1).x(), -1.2, 1e-15);
  EXPECT_NEAR(ex.At(0.1).y(), -1.6, 1e-15);
  EXPECT_THROW(ToExcitation(m, Eigen::Vector2d(1.0, 1.0)), InputError);
}

}  // namespace
}  // namespace skewbridge::records
