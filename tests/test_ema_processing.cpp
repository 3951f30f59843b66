// Landmark processing (src/ema/processing.h): head stabilisation, gap filling, resampling.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <functional>
#include <limits>
#include <string>
#include <vector>

#include "core/error.h"
#include "ema/processing.h"

namespace glossa::ema {
namespace {

constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();

// Element-wise equality that treats NaN == NaN.
bool same(const MatrixRM& a, const MatrixRM& b) {
  if (a.rows() != b.rows() || a.cols() != b.cols()) return false;
  for (Eigen::Index i = 0; i < a.size(); ++i) {
    const float x = a.data()[i], y = b.data()[i];
    if (std::isnan(x) != std::isnan(y)) return false;
    if (!std::isnan(x) && x != y) return false;
  }
  return true;
}

// ---------------------------------------------------------------------------------------------
// stabilise_head

struct Pose {
  std::vector<std::string> names;
  std::vector<Eigen::Vector3d> head;  // positions in the head frame, mm
};

// A head-frame pose in the frame DESIGN.md defines: origin at the upper incisor (REF-UI),
// y from the right (REF-RM) to the left (REF-LM) mastoid, x from the mastoids' midpoint towards
// the incisor, z = x cross y (up). References are interleaved with the articulators so that
// removing them has to keep the others' order.
Pose head_pose() {
  return {{"TT", "REF-LM", "TB", "REF-UI", "UL", "REF-RM", "LL"},
          {{-8.0, 1.5, -12.0},
           {-95.0, 62.0, 0.0},
           {-35.0, -2.0, -5.0},
           {0.0, 0.0, 0.0},
           {6.0, 0.5, 9.0},
           {-95.0, -62.0, 0.0},
           {5.0, -0.3, -16.0}}};
}

// The rigid motion of frame f: a rotation of up to ~25 degrees about a slowly changing axis
// and a translation of tens of millimetres.
Eigen::Isometry3d motion(int f) {
  const double a = 0.45 * std::sin(0.31 * f + 0.2);
  const Eigen::Vector3d axis =
      Eigen::Vector3d(std::cos(0.05 * f), 0.7 + 0.3 * std::sin(0.11 * f), 0.4).normalized();
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.rotate(Eigen::AngleAxisd(a, axis));
  T.pretranslate(Eigen::Vector3d(30.0 + 5.0 * std::sin(0.2 * f), -12.0 + f * 0.5,
                                 140.0 - 3.0 * std::cos(0.17 * f)));
  return T;
}

LandmarkSeq moving_head(const Pose& pose, int frames) {
  LandmarkSeq seq;
  seq.set.names = pose.names;
  seq.rate = 250.0;
  seq.positions.resize(frames, 3 * static_cast<Eigen::Index>(pose.names.size()));
  for (int f = 0; f < frames; ++f) {
    const Eigen::Isometry3d T = motion(f);
    for (size_t l = 0; l < pose.names.size(); ++l) {
      const Eigen::Vector3d p = T * pose.head[l];
      seq.positions.block(f, 3 * static_cast<Eigen::Index>(l), 1, 3) = p.transpose().cast<float>();
    }
  }
  return seq;
}

TEST(StabiliseHead, RecoversHeadFramePositions) {
  const Pose pose = head_pose();
  const int frames = 40;
  const LandmarkSeq seq = moving_head(pose, frames);
  const LandmarkSeq out = stabilise_head(seq);

  EXPECT_EQ(out.set.names, (std::vector<std::string>{"TT", "TB", "UL", "LL"}));
  EXPECT_EQ(out.rate, seq.rate);
  ASSERT_EQ(out.positions.rows(), frames);
  ASSERT_EQ(out.positions.cols(), 12);
  const std::vector<int> kept = {0, 2, 4, 6};  // indices in pose
  double worst = 0;
  for (int f = 0; f < frames; ++f) {
    for (size_t k = 0; k < kept.size(); ++k) {
      const Eigen::Vector3d got =
          out.positions.block(f, 3 * static_cast<Eigen::Index>(k), 1, 3).transpose().cast<double>();
      worst = std::max(worst, (got - pose.head[kept[k]]).norm());
    }
  }
  EXPECT_LT(worst, 1e-3) << "largest deviation from the head-frame pose, mm";
}

TEST(StabiliseHead, FramesWithMissingReferencesBecomeNaN) {
  const Pose pose = head_pose();
  LandmarkSeq seq = moving_head(pose, 10);
  // Frame 0 lacks REF-UI: the template must come from frame 1, and frame 0 is NaN.
  seq.positions(0, 3 * 3 + 1) = kNaN;
  // Frame 6 lacks REF-RM.
  seq.positions(6, 3 * 5 + 2) = kNaN;
  // A NaN articulator stays NaN without spoiling the others.
  seq.positions(4, 3 * 0) = kNaN;
  const LandmarkSeq out = stabilise_head(seq);
  ASSERT_EQ(out.positions.rows(), 10);
  for (Eigen::Index c = 0; c < out.positions.cols(); ++c) {
    EXPECT_TRUE(std::isnan(out.positions(0, c))) << c;
    EXPECT_TRUE(std::isnan(out.positions(6, c))) << c;
  }
  EXPECT_TRUE(std::isnan(out.positions(4, 0)));
  for (int f : {1, 2, 3, 4, 5, 7, 8, 9}) {
    for (int k = 0; k < 4; ++k) {
      if (f == 4 && k == 0) continue;
      const Eigen::Vector3d got = out.positions.block(f, 3 * k, 1, 3).transpose().cast<double>();
      EXPECT_LT((got - pose.head[2 * k]).norm(), 1e-3) << "frame " << f << " sensor " << k;
    }
  }
}

TEST(StabiliseHead, OtherReferencesUseTheFirstCompleteFrame) {
  // References not named REF-UI/LM/RM: the template is their configuration in the first
  // complete frame, so every frame comes out where frame 0 had it.
  Pose pose = head_pose();
  pose.names = {"TT", "REF-A", "TB", "REF-B", "UL", "REF-C", "LL"};
  const LandmarkSeq seq = moving_head(pose, 25);
  const LandmarkSeq out = stabilise_head(seq);
  ASSERT_EQ(out.set.names, (std::vector<std::string>{"TT", "TB", "UL", "LL"}));
  const Eigen::Isometry3d T0 = motion(0);
  for (int f = 0; f < 25; ++f) {
    for (int k = 0; k < 4; ++k) {
      const Eigen::Vector3d want = T0 * pose.head[2 * k];
      const Eigen::Vector3d got = out.positions.block(f, 3 * k, 1, 3).transpose().cast<double>();
      EXPECT_LT((got - want).norm(), 1e-3) << "frame " << f << " sensor " << k;
    }
  }
}

TEST(StabiliseHead, FewerThanThreeReferencesIsAnError) {
  LandmarkSeq seq;
  seq.set.names = {"TT", "REF-UI", "REF-LM", "TB"};
  seq.positions = MatrixRM::Random(5, 12);
  try {
    stabilise_head(seq);
    FAIL() << "expected glossa::Error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("3 reference"), std::string::npos) << e.what();
  }
  seq.set.names = {"TT", "TB", "UL", "LL"};
  EXPECT_THROW(stabilise_head(seq), Error);
}

TEST(StabiliseHead, NoCompleteReferenceFrameIsAnError) {
  const Pose pose = head_pose();
  LandmarkSeq seq = moving_head(pose, 4);
  seq.positions.col(3 * 1).setConstant(kNaN);  // REF-LM never tracked
  EXPECT_THROW(stabilise_head(seq), Error);
}

// ---------------------------------------------------------------------------------------------
// fill_gaps

// Two sensors at 100 Hz, 20 frames; sensor A's coordinates are c * 100 + 10 f.
LandmarkSeq ramp_seq() {
  LandmarkSeq seq;
  seq.set.names = {"A", "B"};
  seq.rate = 100.0;
  seq.positions.resize(20, 6);
  for (int f = 0; f < 20; ++f)
    for (int c = 0; c < 6; ++c) seq.positions(f, c) = float(c * 100 + 10 * f);
  return seq;
}

void blank(LandmarkSeq& seq, int sensor, int from, int to) {  // frames [from, to)
  for (int f = from; f < to; ++f)
    for (int a = 0; a < 3; ++a) seq.positions(f, 3 * sensor + a) = kNaN;
}

TEST(FillGaps, ShortRunIsInterpolatedLinearly) {
  LandmarkSeq seq = ramp_seq();
  const MatrixRM want = seq.positions;
  blank(seq, 0, 5, 8);    // 3 frames
  blank(seq, 1, 10, 11);  // 1 frame
  // A non-linear neighbourhood: interpolation runs between the two valid neighbours.
  seq.positions(12, 4) = 500.f;
  seq.positions(13, 4) = kNaN;
  seq.positions(14, 4) = kNaN;
  seq.positions(15, 4) = 200.f;
  const GapReport r = fill_gaps(seq, 0.05);
  EXPECT_TRUE(r.ok);
  EXPECT_NEAR(r.longest_gap_s, 0.03, 1e-12);
  EXPECT_EQ(r.worst_sensor, "A");
  EXPECT_EQ(r.filled_runs, 2) << "runs counted once per sensor (x coordinate)";
  for (int f = 5; f < 8; ++f)
    for (int c = 0; c < 3; ++c) EXPECT_FLOAT_EQ(seq.positions(f, c), want(f, c)) << f << "," << c;
  for (int c = 3; c < 6; ++c) EXPECT_FLOAT_EQ(seq.positions(10, c), want(10, c));
  EXPECT_FLOAT_EQ(seq.positions(13, 4), 400.f);
  EXPECT_FLOAT_EQ(seq.positions(14, 4), 300.f);
  EXPECT_TRUE(seq.positions.allFinite());
}

TEST(FillGaps, LeadingAndTrailingRunsTakeTheNearestValue) {
  LandmarkSeq seq = ramp_seq();
  blank(seq, 0, 0, 3);
  blank(seq, 1, 16, 20);
  const GapReport r = fill_gaps(seq, 0.05);
  EXPECT_TRUE(r.ok);
  for (int f = 0; f < 3; ++f)
    for (int c = 0; c < 3; ++c) EXPECT_EQ(seq.positions(f, c), float(c * 100 + 30)) << f;
  for (int f = 16; f < 20; ++f)
    for (int c = 3; c < 6; ++c) EXPECT_EQ(seq.positions(f, c), float(c * 100 + 150)) << f;
  EXPECT_NEAR(r.longest_gap_s, 0.04, 1e-12);
  EXPECT_EQ(r.worst_sensor, "B");
}

TEST(FillGaps, RunOfExactlyTheLimitIsFilled) {
  LandmarkSeq seq = ramp_seq();
  blank(seq, 1, 4, 9);  // 5 frames = 0.05 s
  const GapReport r = fill_gaps(seq, 0.05);
  EXPECT_TRUE(r.ok);
  EXPECT_TRUE(seq.positions.allFinite());
  EXPECT_FLOAT_EQ(seq.positions(6, 4), 460.f);
}

TEST(FillGaps, LongRunLeavesDataUnchanged) {
  LandmarkSeq seq = ramp_seq();
  blank(seq, 0, 2, 4);   // short: would be filled
  blank(seq, 1, 5, 15);  // 10 frames = 0.1 s > 0.05 s
  const MatrixRM before = seq.positions;
  const GapReport r = fill_gaps(seq, 0.05);
  EXPECT_FALSE(r.ok);
  EXPECT_NEAR(r.longest_gap_s, 0.1, 1e-12);
  EXPECT_EQ(r.worst_sensor, "B");
  EXPECT_TRUE(same(seq.positions, before)) << "nothing may change when the limit is exceeded";
}

TEST(FillGaps, SensorWithoutAnyValidSampleIsNotOk) {
  LandmarkSeq seq = ramp_seq();
  blank(seq, 1, 0, 20);
  const MatrixRM before = seq.positions;
  const GapReport r = fill_gaps(seq, 10.0);
  EXPECT_FALSE(r.ok);
  EXPECT_EQ(r.worst_sensor, "B");
  EXPECT_TRUE(same(seq.positions, before));
}

TEST(FillGaps, NothingToDo) {
  LandmarkSeq seq = ramp_seq();
  const MatrixRM before = seq.positions;
  const GapReport r = fill_gaps(seq, 0.05);
  EXPECT_TRUE(r.ok);
  EXPECT_EQ(r.filled_runs, 0);
  EXPECT_EQ(r.longest_gap_s, 0.0);
  EXPECT_TRUE(same(seq.positions, before));
}

// ---------------------------------------------------------------------------------------------
// resample

LandmarkSeq signal_seq(int frames, double rate, const std::function<double(double)>& fn) {
  LandmarkSeq seq;
  seq.set.names = {"S"};
  seq.rate = rate;
  seq.positions.resize(frames, 3);
  for (int f = 0; f < frames; ++f) {
    const double t = f / rate;
    seq.positions(f, 0) = static_cast<float>(fn(t));
    seq.positions(f, 1) = static_cast<float>(100.0 + fn(t));  // offset
    seq.positions(f, 2) = static_cast<float>(-2.0 * fn(t));
  }
  return seq;
}

TEST(ResampleLandmarks, NearestPicksEveryFifthSample) {
  LandmarkSeq seq;
  seq.set.names = {"A", "B"};
  seq.rate = 250.0;
  seq.positions.resize(1003, 6);
  for (Eigen::Index i = 0; i < seq.positions.size(); ++i) seq.positions.data()[i] = float(i) * 0.5f;
  const LandmarkSeq out = resample(seq, 50.0, Resampling::kNearest);
  EXPECT_EQ(out.rate, 50.0);
  EXPECT_EQ(out.set, seq.set);
  ASSERT_EQ(out.positions.rows(), 201);  // floor(1002 / 5) + 1
  for (Eigen::Index k = 0; k < out.positions.rows(); ++k)
    for (Eigen::Index c = 0; c < 6; ++c)
      ASSERT_EQ(out.positions(k, c), seq.positions(5 * k, c)) << k << "," << c;
}

TEST(ResampleLandmarks, FrameCountFormula) {
  for (int n : {1, 2, 4, 5, 6, 10, 11, 249, 250, 251, 1000}) {
    LandmarkSeq seq;
    seq.set.names = {"A"};
    seq.rate = 250.0;
    seq.positions = MatrixRM::Zero(n, 3);
    const Eigen::Index want = (n - 1) / 5 + 1;
    EXPECT_EQ(resample(seq, 50.0, Resampling::kNearest).positions.rows(), want) << n;
    if (n >= 3)  // n = 1, 2: see AntialiasedVeryShortSequence
      EXPECT_EQ(resample(seq, 50.0, Resampling::kAntialiased).positions.rows(), want) << n;
  }
  // A ratio that is not an integer: 200 Hz -> 60 Hz, n = 11 -> floor(10 * 0.3) + 1 = 4.
  LandmarkSeq seq;
  seq.set.names = {"A"};
  seq.rate = 200.0;
  seq.positions = MatrixRM::Zero(11, 3);
  EXPECT_EQ(resample(seq, 60.0, Resampling::kNearest).positions.rows(), 4);
  // Empty stays empty.
  seq.positions.resize(0, 3);
  EXPECT_EQ(resample(seq, 50.0, Resampling::kAntialiased).positions.rows(), 0);
}

TEST(ResampleLandmarks, AntialiasedVeryShortSequence) {
  for (int n : {1, 2}) {
    LandmarkSeq seq;
    seq.set.names = {"A"};
    seq.rate = 250.0;
    seq.positions = MatrixRM::Constant(n, 3, 7.0f);
    const LandmarkSeq out = resample(seq, 50.0, Resampling::kAntialiased);
    ASSERT_EQ(out.positions.rows(), 1) << n;
    EXPECT_NEAR(out.positions(0, 0), 7.0f, 1e-4f);
  }
}

TEST(ResampleLandmarks, AntialiasedKeepsASlowSine) {
  const double amp = 5.0;
  auto fn = [&](double t) { return amp * std::sin(2.0 * M_PI * 2.0 * t + 0.3); };
  const LandmarkSeq seq = signal_seq(2500, 250.0, fn);  // 10 s
  const LandmarkSeq out = resample(seq, 50.0, Resampling::kAntialiased);
  ASSERT_EQ(out.positions.rows(), 500);
  double worst = 0;
  for (Eigen::Index k = 25; k < 475; ++k) {  // skip 0.5 s at each edge
    const double t = k / 50.0;
    worst = std::max(worst, std::abs(out.positions(k, 0) - fn(t)));
    worst = std::max(worst, std::abs(out.positions(k, 1) - (100.0 + fn(t))));
    worst = std::max(worst, std::abs(out.positions(k, 2) + 2.0 * fn(t)) / 2.0);
  }
  EXPECT_LT(worst, 0.01 * amp) << "largest error relative to a 2 Hz sine of amplitude 5";
}

TEST(ResampleLandmarks, AntialiasedRemovesAbove25HzWhileNearestAliases) {
  const double amp = 4.0;
  auto fn = [&](double t) { return amp * std::sin(2.0 * M_PI * 40.0 * t); };
  const LandmarkSeq seq = signal_seq(2500, 250.0, fn);
  auto peak = [](const LandmarkSeq& s, Eigen::Index c, double offset) {
    double m = 0;
    for (Eigen::Index k = 25; k < s.positions.rows() - 25; ++k)
      m = std::max(m, std::abs(s.positions(k, c) - offset));
    return m;
  };
  const LandmarkSeq anti = resample(seq, 50.0, Resampling::kAntialiased);
  EXPECT_LT(peak(anti, 0, 0.0), 0.1 * amp);
  EXPECT_LT(peak(anti, 1, 100.0), 0.1 * amp);
  // Nearest sampling folds 40 Hz onto 10 Hz at (nearly) full amplitude.
  const LandmarkSeq near = resample(seq, 50.0, Resampling::kNearest);
  EXPECT_GT(peak(near, 0, 0.0), 0.9 * amp);
  // ... and it really is a 10 Hz sine: -amp sin(2 pi 10 t).
  for (Eigen::Index k = 0; k < 50; ++k)
    EXPECT_NEAR(near.positions(k, 0), -amp * std::sin(2.0 * M_PI * 10.0 * k / 50.0), 1e-3) << k;
}

TEST(ResampleLandmarks, BadRatesAndNames) {
  LandmarkSeq seq;
  seq.set.names = {"A"};
  seq.rate = 250.0;
  seq.positions = MatrixRM::Zero(10, 3);
  EXPECT_THROW(resample(seq, 0.0, Resampling::kNearest), Error);
  seq.rate = 0;
  EXPECT_THROW(resample(seq, 50.0, Resampling::kAntialiased), Error);
  EXPECT_EQ(parse_resampling("nearest"), Resampling::kNearest);
  EXPECT_EQ(parse_resampling("antialiased"), Resampling::kAntialiased);
  EXPECT_THROW(parse_resampling("cubic"), Error);
}

}  // namespace
}  // namespace glossa::ema
