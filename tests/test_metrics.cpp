// The papers' metrics (src/eval/metrics.h) on hand-computed cases.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "core/error.h"
#include "eval/metrics.h"

namespace glossa::eval {
namespace {

MatrixRM rows(std::initializer_list<std::initializer_list<float>> r) {
  MatrixRM m(static_cast<Eigen::Index>(r.size()), static_cast<Eigen::Index>(r.begin()->size()));
  Eigen::Index i = 0;
  for (const auto& row : r) {
    Eigen::Index j = 0;
    for (float v : row) m(i, j++) = v;
    ++i;
  }
  return m;
}

// Utterance A: 2 frames, 2 landmarks. Offsets pred - truth:
//   frame 0: L0 (3, 4, 0) -> 5,   L1 (0, 0, 0) -> 0
//   frame 1: L0 (0, 3, 4) -> 5,   L1 (6, 8, 0) -> 10
// eq. 1: (5 + 0 + 5 + 10) / 4 = 5; per landmark: L0 5, L1 5; squared sum 150 over 12 values.
struct Utt {
  MatrixRM truth, pred;
};

Utt utterance_a() {
  Utt u;
  u.truth = rows({{1, 2, 3, 10, 20, 30}, {-1, -2, -3, 0, 0, 0}});
  u.pred = u.truth;
  u.pred.row(0) += rows({{3, 4, 0, 0, 0, 0}});
  u.pred.row(1) += rows({{0, 3, 4, 6, 8, 0}});
  return u;
}

// Utterance B: 4 frames, L0 off by (2, 0, 0) -> 2, L1 exact -> 0. eq. 1: 1; squared sum 16.
Utt utterance_b() {
  Utt u;
  u.truth = MatrixRM(4, 6);
  for (Eigen::Index f = 0; f < 4; ++f)
    for (Eigen::Index c = 0; c < 6; ++c) u.truth(f, c) = float(f * 7 + c * c);
  u.pred = u.truth;
  u.pred.col(0).array() += 2.0f;
  return u;
}

TEST(Metrics, MeanSampleErrorByHand) {
  const Utt a = utterance_a();
  EXPECT_DOUBLE_EQ(mean_sample_error(a.pred, a.truth), 5.0);
  const Utt b = utterance_b();
  EXPECT_DOUBLE_EQ(mean_sample_error(b.pred, b.truth), 1.0);
  EXPECT_DOUBLE_EQ(mean_sample_error(a.truth, a.truth), 0.0);
  // Symmetric in its arguments.
  EXPECT_DOUBLE_EQ(mean_sample_error(a.truth, a.pred), 5.0);
}

TEST(Metrics, EuclideanNotPerCoordinate) {
  // One landmark off by (1, 1, 1): sqrt(3), not 3 and not 1.
  const MatrixRM t = MatrixRM::Zero(1, 3);
  const MatrixRM p = MatrixRM::Ones(1, 3);
  EXPECT_NEAR(mean_sample_error(p, t), std::sqrt(3.0), 1e-12);
}

TEST(Metrics, AccumulatorAveragesOverUtterancesNotFrames) {
  MetricAccumulator acc(2);
  const Utt a = utterance_a(), b = utterance_b();
  acc.add(a.pred, a.truth);
  acc.add(b.pred, b.truth);
  const Metrics m = acc.result();
  EXPECT_EQ(m.utterances, 2u);
  EXPECT_EQ(m.frames, 6u);
  // (5 + 1) / 2 = 3; a frame-weighted mean would be (2 * 5 + 4 * 1) / 6 = 2.33.
  EXPECT_DOUBLE_EQ(m.mean_error_mm, 3.0);
  // Per landmark: L0 (5 + 2) / 2, L1 (5 + 0) / 2.
  ASSERT_EQ(m.per_landmark_mm.size(), 2u);
  EXPECT_DOUBLE_EQ(m.per_landmark_mm[0], 3.5);
  EXPECT_DOUBLE_EQ(m.per_landmark_mm[1], 2.5);
  // RMSE over every coordinate of every frame: sqrt((150 + 16) / (12 + 24)).
  EXPECT_NEAR(m.rmse_mm, std::sqrt(166.0 / 36.0), 1e-12);
}

TEST(Metrics, EmptyAccumulatorAndEmptyUtterance) {
  MetricAccumulator acc(2);
  Metrics m = acc.result();
  EXPECT_EQ(m.utterances, 0u);
  EXPECT_EQ(m.frames, 0u);
  EXPECT_EQ(m.mean_error_mm, 0.0);
  acc.add(MatrixRM(0, 6), MatrixRM(0, 6));  // ignored
  EXPECT_EQ(acc.result().utterances, 0u);
  const Utt a = utterance_a();
  acc.add(a.pred, a.truth);
  m = acc.result();
  EXPECT_EQ(m.utterances, 1u);
  EXPECT_DOUBLE_EQ(m.mean_error_mm, 5.0);
}

TEST(Metrics, PearsonFunction) {
  Eigen::VectorXf t(5), lin(5), anti(5), flat(5);
  t << 0, 1, 2, 3, 4;
  lin = 2.5f * t.array() + 7.0f;
  anti = -0.5f * t.array() + 1.0f;
  flat.setConstant(3.0f);
  EXPECT_NEAR(pearson(lin, t), 1.0, 1e-12);
  EXPECT_NEAR(pearson(anti, t), -1.0, 1e-12);
  EXPECT_TRUE(std::isnan(pearson(flat, t)));
  EXPECT_TRUE(std::isnan(pearson(t, flat)));
  // By hand: a = 1 2 3 4, b = 1 3 2 4: centred dot 4, both sums of squares 5 -> r = 0.8.
  Eigen::VectorXf a(4), b(4);
  a << 1, 2, 3, 4;
  b << 1, 3, 2, 4;
  EXPECT_NEAR(pearson(a, b), 0.8, 1e-12);
  // Large offsets must not destroy the precision (positions in mm far from the origin).
  Eigen::VectorXf a2 = a.array() + 1000.0f, b2 = b.array() - 500.0f;
  EXPECT_NEAR(pearson(a2, b2), 0.8, 1e-6);
}

TEST(Metrics, PearsonInAccumulatorSkipsConstantChannels) {
  // One landmark. Utterance 1: x perfect (r = 1), y anti (r = -1), z constant (skipped).
  // Utterance 2: x and y perfect, z constant. Per coordinate: x 1, y 0, z NaN; overall mean
  // over (utterance, coordinate) pairs that count: (1 - 1 + 1 + 1) / 4 = 0.5.
  MetricAccumulator acc(1);
  for (int u = 0; u < 2; ++u) {
    MatrixRM truth(6, 3), pred(6, 3);
    for (int f = 0; f < 6; ++f) {
      const float s = float(f * f) + float(u);
      truth(f, 0) = s;
      truth(f, 1) = 10.0f - s;
      truth(f, 2) = 42.0f;
      pred(f, 0) = 3.0f * s - 1.0f;
      pred(f, 1) = u == 0 ? -truth(f, 1) : truth(f, 1) + 5.0f;
      pred(f, 2) = 40.0f;
    }
    acc.add(pred, truth);
  }
  const Metrics m = acc.result();
  ASSERT_EQ(m.pearson_per_coord.size(), 3u);
  EXPECT_NEAR(m.pearson_per_coord[0], 1.0, 1e-9);
  EXPECT_NEAR(m.pearson_per_coord[1], 0.0, 1e-9);
  EXPECT_TRUE(std::isnan(m.pearson_per_coord[2]));
  EXPECT_NEAR(m.pearson, 0.5, 1e-9);
}

TEST(Metrics, ShapeMismatchIsAnError) {
  const MatrixRM t = MatrixRM::Zero(3, 6);
  EXPECT_THROW(mean_sample_error(MatrixRM::Zero(2, 6), t), Error);
  EXPECT_THROW(mean_sample_error(MatrixRM::Zero(3, 3), t), Error);
  EXPECT_THROW(mean_sample_error(MatrixRM::Zero(3, 4), MatrixRM::Zero(3, 4)), Error);
  EXPECT_THROW(mean_sample_error(MatrixRM(0, 6), MatrixRM(0, 6)), Error);
  try {
    mean_sample_error(MatrixRM::Zero(2, 6), t);
    FAIL() << "expected glossa::Error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("shape"), std::string::npos) << e.what();
  }
  MetricAccumulator acc(2);
  EXPECT_THROW(acc.add(MatrixRM::Zero(3, 6), MatrixRM::Zero(4, 6)), Error);
  EXPECT_THROW(acc.add(MatrixRM::Zero(3, 9), MatrixRM::Zero(3, 9)), Error);  // 3 landmarks, not 2
  EXPECT_EQ(acc.result().utterances, 0u) << "a refused utterance must not be counted";
}

}  // namespace
}  // namespace glossa::eval
