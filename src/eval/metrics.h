#pragma once
// The papers' metrics. For an utterance with S frames and L landmarks:
//   mean sample error (eq. 1): e = 1/S sum_s 1/L sum_l |y_hat_sl - y_sl|_2   (mm)
// reported as the mean over utterances; per-landmark error is eq. 1 restricted to one landmark;
// RMSE is over all coordinates and frames; Pearson r is computed per utterance and coordinate
// (x, y, z of each landmark) and averaged, skipping coordinates that do not move (std < 1e-6).
#include <string>
#include <vector>

#include "core/matrix.h"

namespace glossa::eval {

// eq. 1 for one utterance; pred and truth are [S, 3L].
double mean_sample_error(const MatrixRM& pred, const MatrixRM& truth);

struct Metrics {
  double mean_error_mm = 0;                 // eq. 1, mean over utterances
  std::vector<double> per_landmark_mm;      // eq. 1 per landmark, mean over utterances
  double rmse_mm = 0;                       // over all coordinates and frames
  double pearson = 0;                       // mean over utterances and coordinates
  std::vector<double> pearson_per_coord;    // [3L], mean over utterances
  size_t utterances = 0;
  size_t frames = 0;
};

class MetricAccumulator {
 public:
  explicit MetricAccumulator(size_t landmarks) : L_(landmarks) {}
  void add(const MatrixRM& pred, const MatrixRM& truth);
  Metrics result() const;

 private:
  size_t L_;
  std::vector<double> utt_errors_;
  std::vector<std::vector<double>> utt_landmark_errors_;
  double sq_sum_ = 0;
  size_t sq_count_ = 0;
  std::vector<double> r_sum_;
  std::vector<size_t> r_count_;
  size_t frames_ = 0;
};

// Pearson correlation of two equally long vectors; NaN when either is constant.
double pearson(const Eigen::Ref<const Eigen::VectorXf>& a, const Eigen::Ref<const Eigen::VectorXf>& b);

}  // namespace glossa::eval
