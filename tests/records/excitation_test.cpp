// A record as the solver's excitation: the samples are the kinks and the values between them
// are the linear interpolation of the record read from its file. Its acceleration scale (Peak,
// read from the samples) has the bits of the walk over PieceAt that every excitation has, and
// with an unbounded ramp it is the largest sample's magnitude. The piece after a piece, found by
// its number, has the bits of PieceAt at that piece's end.
#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <limits>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include "records/excitations.h"
#include "records/ground_motion.h"
#include "solver/common/error.h"

namespace skewbridge::records::excitation_test {
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

// NIS090 along x and along (0.6, -0.8), then random signals (standard deviation 3 m/s^2, seed
// `seed`) at steps whose multiples round (1/3, 0.1 pi, 0.0123), short and long, with one and two
// components.
std::vector<SampledExcitation> SampledCases(std::uint64_t seed) {
  const GroundMotion record =
      ReadRecord(std::filesystem::path(SKEWBRIDGE_TEST_DATA_DIR) / "records" / "NIS090.AT2");
  std::vector<SampledExcitation> cases;
  cases.push_back(ToExcitation(record));
  cases.push_back(ToExcitation(record, Eigen::Vector2d(0.6, -0.8)));
  std::mt19937_64 random(seed);
  std::normal_distribution<double> normal(0.0, 3.0);
  for (const double dt : {0.005, 0.01, 0.02, 0.0123, 1.0 / 3.0, 0.1 * std::acos(-1.0)}) {
    for (const std::size_t n : {2ul, 3ul, 7ul, 5000ul}) {
      std::vector<double> ax(n), ay(n);
      for (std::size_t k = 0; k < n; ++k) {
        ax[k] = normal(random);
        ay[k] = normal(random);
      }
      cases.emplace_back(dt, ax);
      cases.emplace_back(dt, ax, ay);
    }
  }
  return cases;
}

TEST(SampledExcitationPeak, IsTheBitsOfTheWalkOverPieceAt) {
  const std::vector<SampledExcitation> cases = SampledCases(2011);
  const double inf = std::numeric_limits<double>::infinity();
  for (const SampledExcitation& ex : cases) {
    const double dt = ex.dt_s();
    for (const double horizon : {0.0, 0.3 * dt, dt, 2.5 * dt, inf}) {
      const double walk = ex.Excitation::Peak(horizon);
      EXPECT_EQ(std::bit_cast<std::uint64_t>(ex.Peak(horizon)), std::bit_cast<std::uint64_t>(walk))
          << "dt " << dt << ", " << ex.ax_mps2().size() << " samples, horizon " << horizon;
    }
    // A ramp followed to its end reaches the next sample: the largest sample's magnitude, up to
    // the rounding of the piece's length (k + 1) dt - k dt, a few ulps of k dt (k < 5000).
    double largest = 0.0;
    for (std::size_t k = 0; k < ex.ax_mps2().size(); ++k) {
      const double y = ex.ay_mps2().empty() ? 0.0 : ex.ay_mps2()[k];
      largest = std::max(largest, std::hypot(ex.ax_mps2()[k], y));
    }
    EXPECT_NEAR(ex.Peak(inf), largest, 1e-11 * largest);
  }
}

// Every field of two pieces, bit for bit.
void ExpectSameBits(const ExcitationPiece& a, const ExcitationPiece& b, const std::string& where) {
  const auto bits = [](double x) { return std::bit_cast<std::uint64_t>(x); };
  EXPECT_EQ(bits(a.t_begin), bits(b.t_begin)) << where;
  EXPECT_EQ(bits(a.t_end), bits(b.t_end)) << where;
  for (int i = 0; i < 2; ++i) {
    EXPECT_EQ(bits(a.a_begin[i]), bits(b.a_begin[i])) << where;
    EXPECT_EQ(bits(a.slope[i]), bits(b.slope[i])) << where;
    EXPECT_EQ(bits(a.cos_amplitude[i]), bits(b.cos_amplitude[i])) << where;
    EXPECT_EQ(bits(a.sin_amplitude[i]), bits(b.sin_amplitude[i])) << where;
  }
  EXPECT_EQ(bits(a.omega), bits(b.omega)) << where;
  EXPECT_EQ(a.index, b.index) << where;
}

TEST(SampledExcitationNextPiece, IsTheBitsOfPieceAtThePiecesEnd) {
  const std::vector<SampledExcitation> cases = SampledCases(2027);
  for (const SampledExcitation& ex : cases) {
    // From the first piece to the rest after the last sample: n - 1 ramps, then the rest.
    ExcitationPiece piece = ex.PieceAt(0.0);
    std::size_t steps = 0;
    while (std::isfinite(piece.t_end)) {
      const ExcitationPiece expected = ex.PieceAt(piece.t_end);
      ex.NextPiece(piece);
      ExpectSameBits(piece, expected,
                     "dt " + std::to_string(ex.dt_s()) + ", piece " + std::to_string(steps + 1));
      ++steps;
    }
    EXPECT_EQ(steps, ex.ax_mps2().size() - 1);
    EXPECT_EQ(piece.t_begin, ex.Duration());
    EXPECT_EQ(piece.index, -1);
  }
}

TEST(PieceHolds, APromisedPieceIsPieceAtsBitsAtEveryTimeInsideIt) {
  // A pulse's two pieces and a record's rest are promised: PieceAt at drawn times inside them,
  // their ends' neighbours and huge times gives the piece's bits; a record's ramps are not.
  std::mt19937_64 random(2029);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const auto check = [&](const Excitation& ex, const ExcitationPiece& piece,
                         const std::string& what) {
    ASSERT_TRUE(ex.PieceHolds(piece)) << what;
    std::vector<double> times = {
        piece.t_begin, std::nextafter(piece.t_begin, std::numeric_limits<double>::infinity())};
    if (std::isfinite(piece.t_end)) {
      times.push_back(std::nextafter(piece.t_end, 0.0));
      for (int i = 0; i < 200; ++i) {
        times.push_back(piece.t_begin + unit(random) * (piece.t_end - piece.t_begin));
      }
    } else {
      for (const double far : {1.0, 1e3, 1e300, std::numeric_limits<double>::max()}) {
        times.push_back(piece.t_begin + far);
      }
      for (int i = 0; i < 200; ++i) times.push_back(piece.t_begin + 100.0 * unit(random));
    }
    for (const double t : times) {
      if (!(t >= piece.t_begin && t < piece.t_end)) continue;
      ExpectSameBits(ex.PieceAt(t), piece, what + " at t " + std::to_string(t));
    }
  };
  for (const PulseShape shape : {PulseShape::kCosine, PulseShape::kSine}) {
    for (const double omega : {0.3, 6.283185307179586, 40.0}) {
      const PulseExcitation pulse(shape, -2.5, omega, Eigen::Vector2d(0.6, 0.8));
      check(pulse, pulse.PieceAt(0.0), "pulse");
      check(pulse, pulse.PieceAt(pulse.Duration()), "pulse rest");
    }
  }
  for (const SampledExcitation& ex : SampledCases(2030)) {
    ExcitationPiece piece = ex.PieceAt(0.0);
    while (std::isfinite(piece.t_end)) {
      EXPECT_FALSE(ex.PieceHolds(piece)) << "ramp from " << piece.t_begin;
      ex.NextPiece(piece);
    }
    check(ex, piece, "record rest");
  }
}

TEST(SampledExcitationSamples, ReadInlineAreTheBitsOfPieceAtThePiecesEnd) {
  for (const SampledExcitation& ex : SampledCases(2028)) {
    const SampleView view = ex.Samples();
    ASSERT_EQ(view.count, ex.ax_mps2().size());
    EXPECT_EQ(view.ay_mps2 == nullptr, ex.ay_mps2().empty());
    ExcitationPiece piece = ex.PieceAt(0.0);
    std::size_t ramps = 1;
    // Every ramp after the first from the samples; the last one's end is the rest (false).
    while (NextSampledPiece(view, piece)) {
      ExpectSameBits(piece, ex.PieceAt(piece.t_begin), "piece " + std::to_string(ramps));
      ++ramps;
    }
    EXPECT_EQ(ramps, ex.ax_mps2().size() - 1);
    EXPECT_EQ(piece.t_end, ex.Duration());
  }
  // A pulse has no samples.
  EXPECT_EQ(PulseExcitation(PulseShape::kSine, 1.0, 3.0).Samples().count, 0u);
}

// Records whose peak pieces are hard to tell apart: NIS090, random signals (one of them with
// every sample of one magnitude and alternating sign, so every piece ties), two peaks an ulp
// and 1e-12 apart, and a record whose largest term is a ramp's end between smaller samples.
std::vector<GroundMotion> PeakRecords(std::uint64_t seed) {
  std::vector<GroundMotion> records;
  records.push_back(
      ReadRecord(std::filesystem::path(SKEWBRIDGE_TEST_DATA_DIR) / "records" / "NIS090.AT2"));
  std::mt19937_64 random(seed);
  std::normal_distribution<double> normal(0.0, 3.0);
  for (const double dt : {0.01, 0.0123, 1.0 / 3.0}) {
    GroundMotion m;
    m.dt_s = dt;
    m.acc_mps2.resize(3001);
    for (double& a : m.acc_mps2) a = normal(random);
    records.push_back(m);
    for (std::size_t k = 0; k < m.acc_mps2.size(); ++k) m.acc_mps2[k] = k % 2 ? -2.5 : 2.5;
    records.push_back(m);
    m.acc_mps2.assign(3001, 0.0);
    for (double& a : m.acc_mps2) a = 0.1 * normal(random);
    m.acc_mps2[700] = 4.0;
    m.acc_mps2[2100] = -std::nextafter(4.0, 5.0);
    m.acc_mps2[2900] = 4.0 * (1.0 + 1e-12);
    records.push_back(m);
  }
  return records;
}

TEST(ScaledExcitation, IsTheBitsOfAScaledCopyThroughToExcitation) {
  for (const GroundMotion& m : PeakRecords(7)) {
    for (const double factor : {1.0, 0.37, 27.9}) {
      for (const double angle_deg : {0.0, 30.0, 90.0, 200.0}) {
        const Eigen::Vector2d d(std::cos(angle_deg * std::acos(-1.0) / 180.0),
                                std::sin(angle_deg * std::acos(-1.0) / 180.0));
        GroundMotion copy = m;
        for (double& a : copy.acc_mps2) a *= factor;
        const SampledExcitation expected = ToExcitation(copy, d);
        const SampledExcitation ex = ScaledExcitation(m, factor, d);
        ASSERT_EQ(ex.ax_mps2().size(), expected.ax_mps2().size());
        ASSERT_EQ(ex.ay_mps2().size(), expected.ay_mps2().size());
        for (std::size_t k = 0; k < ex.ax_mps2().size(); ++k) {
          ASSERT_EQ(std::bit_cast<std::uint64_t>(ex.ax_mps2()[k]),
                    std::bit_cast<std::uint64_t>(expected.ax_mps2()[k]));
          if (!ex.ay_mps2().empty()) {
            ASSERT_EQ(std::bit_cast<std::uint64_t>(ex.ay_mps2()[k]),
                      std::bit_cast<std::uint64_t>(expected.ay_mps2()[k]));
          }
        }
      }
    }
  }
  GroundMotion m;
  m.dt_s = 0.1;
  m.acc_mps2 = {1.0, -2.0};
  EXPECT_THROW(ScaledExcitation(m, 2.0, Eigen::Vector2d(1.0, 1.0)), InputError);
}

// The peak read from the pieces FindPeakPieces keeps has the bits of the walk over PieceAt
// (Excitation::Peak), for factors from 2^-40 to 30 and directions all round; at another
// horizon the excitation walks every piece.
TEST(ScaledExcitation, PeakFromItsPeakPiecesIsTheBitsOfTheWalk) {
  std::mt19937_64 random(2029);
  std::uniform_real_distribution<double> log_factor(-3.0, 3.5);
  std::uniform_real_distribution<double> angle(0.0, 360.0);
  for (const GroundMotion& m : PeakRecords(11)) {
    const double horizon = 1e3;
    const auto pieces =
        std::make_shared<const PeakPieces>(FindPeakPieces(m.acc_mps2, m.dt_s, horizon));
    ASSERT_FALSE(pieces->pieces.empty());
    std::vector<double> factors = {1.0, std::ldexp(1.0, -40), 0.5, 3.0, 27.91};
    for (int i = 0; i < 20; ++i) factors.push_back(std::exp(log_factor(random)));
    for (const double factor : factors) {
      std::vector<double> angles = {0.0, 15.0, 45.0, 60.0, 90.0, 180.0, 270.0};
      for (int i = 0; i < 5; ++i) angles.push_back(angle(random));
      for (const double angle_deg : angles) {
        const Eigen::Vector2d d(std::cos(angle_deg * std::acos(-1.0) / 180.0),
                                std::sin(angle_deg * std::acos(-1.0) / 180.0));
        const SampledExcitation ex = ScaledExcitation(m, factor, d, pieces);
        for (const double h : {horizon, 0.3 * m.dt_s}) {
          const double walk = ex.Excitation::Peak(h);
          ASSERT_EQ(std::bit_cast<std::uint64_t>(ex.Peak(h)), std::bit_cast<std::uint64_t>(walk))
              << m.acc_mps2.size() << " samples at dt " << m.dt_s << ", factor " << factor
              << ", angle " << angle_deg << " deg, horizon " << h;
        }
      }
    }
  }
}

// The pieces kept: every piece of a record whose samples all tie, both of two peaks an ulp
// apart, and of a random record only those within 1e-9 of its largest sample of the largest
// term (a few), each of them checked against the terms computed here.
TEST(FindPeakPieces, KeepsThePiecesNearTheLargestTerm) {
  const std::vector<GroundMotion> records = PeakRecords(13);
  const GroundMotion& random = records[1];
  const GroundMotion& ties = records[2];
  const GroundMotion& close = records[3];
  EXPECT_EQ(FindPeakPieces(ties.acc_mps2, ties.dt_s, 1e3).pieces.size(), 3000u);
  const std::vector<std::size_t> near = FindPeakPieces(close.acc_mps2, close.dt_s, 1e3).pieces;
  // The ramps into and out of samples 700, 2100 and 2900 reach them: pieces 699, 700, 2099,
  // 2100, 2899 and 2900.
  EXPECT_EQ(near, (std::vector<std::size_t>{699, 700, 2099, 2100, 2899, 2900}));
  const PeakPieces found = FindPeakPieces(random.acc_mps2, random.dt_s, 1e3);
  double largest = 0.0;
  for (const double a : random.acc_mps2) largest = std::max(largest, std::abs(a));
  EXPECT_EQ(found.largest_mps2, largest);
  EXPECT_GE(found.pieces.size(), 1u);
  EXPECT_LE(found.pieces.size(), 2u);  // the ramps into and out of the largest sample
  for (const std::size_t k : found.pieces) {
    const double top = std::max(std::abs(random.acc_mps2[k]), std::abs(random.acc_mps2[k + 1]));
    EXPECT_NEAR(top, largest, 1e-9 * largest);
  }
}

}  // namespace
}  // namespace skewbridge::records::excitation_test
