#include "features/normalizer.h"

#include "core/error.h"

namespace glossa::features {

Normalizer Normalizer::fit(const std::vector<const MatrixRM*>& data, float min_std) {
  if (data.empty()) throw Error("normalizer: no data");
  const Eigen::Index d = data.front()->cols();
  Eigen::RowVectorXd sum = Eigen::RowVectorXd::Zero(d), sq = Eigen::RowVectorXd::Zero(d);
  double n = 0;
  for (const MatrixRM* m : data) {
    if (m->cols() != d) throw Error("normalizer: inconsistent dimensions");
    const Eigen::MatrixXd md = m->cast<double>();
    sum += md.colwise().sum();
    sq += md.array().square().matrix().colwise().sum();
    n += static_cast<double>(m->rows());
  }
  if (n < 1) throw Error("normalizer: no frames");
  Normalizer out;
  const Eigen::RowVectorXd mean = sum / n;
  const Eigen::RowVectorXd var = (sq / n - mean.array().square().matrix()).cwiseMax(0.0);
  out.mean = mean.cast<float>();
  out.std = var.cwiseSqrt().cast<float>().cwiseMax(min_std);
  return out;
}

MatrixRM Normalizer::apply(const MatrixRM& x) const {
  return (x.rowwise() - mean).array().rowwise() / std.array();
}

MatrixRM Normalizer::invert(const MatrixRM& z) const {
  return (z.array().rowwise() * std.array()).matrix().rowwise() + mean;
}

nlohmann::json Normalizer::to_json() const {
  return {{"mean", std::vector<float>(mean.data(), mean.data() + mean.size())},
          {"std", std::vector<float>(std.data(), std.data() + std.size())}};
}

Normalizer Normalizer::from_json(const nlohmann::json& j) {
  const auto m = j.at("mean").get<std::vector<float>>();
  const auto s = j.at("std").get<std::vector<float>>();
  if (m.size() != s.size()) throw Error("normalizer: mean and std differ in size");
  Normalizer out;
  out.mean = Eigen::Map<const RowVec>(m.data(), 1, m.size());
  out.std = Eigen::Map<const RowVec>(s.data(), 1, s.size());
  return out;
}

}  // namespace glossa::features
