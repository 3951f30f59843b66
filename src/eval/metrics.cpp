#include "eval/metrics.h"

#include <cmath>
#include <limits>

#include "core/error.h"

namespace glossa::eval {

namespace {

void check_shapes(const MatrixRM& pred, const MatrixRM& truth) {
  if (pred.rows() != truth.rows() || pred.cols() != truth.cols() || truth.cols() % 3 != 0)
    throw Error("metrics: prediction and truth differ in shape");
}

}  // namespace

double mean_sample_error(const MatrixRM& pred, const MatrixRM& truth) {
  check_shapes(pred, truth);
  if (truth.rows() == 0) throw Error("metrics: empty utterance");
  const Eigen::Index L = truth.cols() / 3;
  double sum = 0;
  for (Eigen::Index s = 0; s < truth.rows(); ++s)
    for (Eigen::Index l = 0; l < L; ++l)
      sum += (pred.block(s, 3 * l, 1, 3) - truth.block(s, 3 * l, 1, 3)).cast<double>().norm();
  return sum / double(truth.rows() * L);
}

double pearson(const Eigen::Ref<const Eigen::VectorXf>& a,
               const Eigen::Ref<const Eigen::VectorXf>& b) {
  const Eigen::VectorXd x = a.cast<double>(), y = b.cast<double>();
  const Eigen::VectorXd xc = x.array() - x.mean(), yc = y.array() - y.mean();
  const double sx = xc.norm(), sy = yc.norm();
  const double n = std::sqrt(double(std::max<Eigen::Index>(x.size(), 1)));
  if (sx / n < 1e-6 || sy / n < 1e-6) return std::numeric_limits<double>::quiet_NaN();
  return xc.dot(yc) / (sx * sy);
}

void MetricAccumulator::add(const MatrixRM& pred, const MatrixRM& truth) {
  check_shapes(pred, truth);
  if (static_cast<size_t>(truth.cols()) != 3 * L_)
    throw Error("metrics: wrong number of landmarks");
  if (truth.rows() == 0) return;
  const Eigen::Index S = truth.rows();
  std::vector<double> per(L_, 0.0);
  for (Eigen::Index s = 0; s < S; ++s)
    for (size_t l = 0; l < L_; ++l)
      per[l] += (pred.block(s, 3 * l, 1, 3) - truth.block(s, 3 * l, 1, 3)).cast<double>().norm();
  double total = 0;
  for (double& p : per) {
    p /= double(S);
    total += p;
  }
  utt_errors_.push_back(total / double(L_));
  utt_landmark_errors_.push_back(per);
  sq_sum_ += (pred - truth).cast<double>().squaredNorm();
  sq_count_ += static_cast<size_t>(truth.size());
  if (r_sum_.empty()) {
    r_sum_.assign(3 * L_, 0.0);
    r_count_.assign(3 * L_, 0);
  }
  for (size_t c = 0; c < 3 * L_; ++c) {
    const double r = pearson(pred.col(static_cast<Eigen::Index>(c)),
                             truth.col(static_cast<Eigen::Index>(c)));
    if (std::isfinite(r)) {
      r_sum_[c] += r;
      ++r_count_[c];
    }
  }
  frames_ += static_cast<size_t>(S);
}

Metrics MetricAccumulator::result() const {
  Metrics m;
  m.utterances = utt_errors_.size();
  m.frames = frames_;
  if (m.utterances == 0) return m;
  for (double e : utt_errors_) m.mean_error_mm += e;
  m.mean_error_mm /= double(m.utterances);
  m.per_landmark_mm.assign(L_, 0.0);
  for (const auto& per : utt_landmark_errors_)
    for (size_t l = 0; l < L_; ++l) m.per_landmark_mm[l] += per[l] / double(m.utterances);
  m.rmse_mm = std::sqrt(sq_sum_ / double(std::max<size_t>(sq_count_, 1)));
  m.pearson_per_coord.assign(3 * L_, std::numeric_limits<double>::quiet_NaN());
  double rs = 0;
  size_t rn = 0;
  for (size_t c = 0; c < 3 * L_; ++c) {
    if (r_count_.empty() || r_count_[c] == 0) continue;
    m.pearson_per_coord[c] = r_sum_[c] / double(r_count_[c]);
    rs += r_sum_[c];
    rn += r_count_[c];
  }
  m.pearson = rn ? rs / double(rn) : std::numeric_limits<double>::quiet_NaN();
  return m;
}

}  // namespace glossa::eval
