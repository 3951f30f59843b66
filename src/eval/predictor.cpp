#include "eval/predictor.h"

#include <Eigen/Dense>
#include <chrono>

#include "core/error.h"
#include "eval/metrics.h"

namespace glossa::eval {

MatrixRM MeanPosePredictor::predict(const Audio& audio) const {
  return MatrixRM::Zero(static_cast<Eigen::Index>(features::frame_count(audio.samples.size())),
                        static_cast<Eigen::Index>(3 * L_));
}

Eigen::MatrixXf stack_context(const MatrixRM& x, int c) {
  const Eigen::Index T = x.rows(), D = x.cols();
  Eigen::MatrixXf out(T, (2 * c + 1) * D + 1);
  for (Eigen::Index t = 0; t < T; ++t) {
    for (int k = -c; k <= c; ++k) {
      const Eigen::Index src = std::clamp<Eigen::Index>(t + k, 0, T - 1);
      out.block(t, (k + c) * D, 1, D) = x.row(src);
    }
    out(t, (2 * c + 1) * D) = 1.f;
  }
  return out;
}

std::unique_ptr<RidgePredictor> RidgePredictor::fit(const nlohmann::json& encoder_config,
                                                    const std::vector<train::Sequence>& train,
                                                    const std::vector<train::Sequence>& val,
                                                    int context) {
  const auto start = std::chrono::steady_clock::now();
  if (train.empty()) throw Error("ridge baseline: no training data");
  auto r = std::unique_ptr<RidgePredictor>(new RidgePredictor);
  r->encoder_ = features::make_encoder(encoder_config);
  r->context_ = context;
  std::vector<const MatrixRM*> fx;
  for (const auto& s : train) fx.push_back(&s.features);
  r->norm_ = features::Normalizer::fit(fx);
  const Eigen::Index P = (2 * context + 1) * train.front().features.cols() + 1;
  const Eigen::Index O = train.front().targets.cols();
  Eigen::MatrixXd XtX = Eigen::MatrixXd::Zero(P, P), XtY = Eigen::MatrixXd::Zero(P, O);
  for (const auto& s : train) {
    const Eigen::MatrixXd X = stack_context(r->norm_.apply(s.features), context).cast<double>();
    XtX.noalias() += X.transpose() * X;
    XtY.noalias() += X.transpose() * s.targets.cast<double>();
  }
  const double scale = XtX.diagonal().mean();
  double best = std::numeric_limits<double>::infinity();
  for (double rel : {1e-5, 1e-4, 1e-3, 1e-2, 1e-1, 1.0}) {
    Eigen::MatrixXd A = XtX;
    A.diagonal().array() += rel * scale;
    const Eigen::MatrixXf W = A.ldlt().solve(XtY).cast<float>();
    double err = 0;
    const auto& held = val.empty() ? train : val;
    for (const auto& s : held) {
      const MatrixRM pred = stack_context(r->norm_.apply(s.features), context) * W;
      err += mean_sample_error(pred, s.targets);
    }
    err /= double(held.size());
    if (err < best) {
      best = err;
      r->W_ = W;
      r->lambda_ = rel * scale;
    }
  }
  r->train_minutes_ =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() / 60.0;
  return r;
}

std::string RidgePredictor::name() const {
  return fmt::format("ridge ({} ±{})", encoder_->name(), context_);
}

MatrixRM RidgePredictor::predict_features(const MatrixRM& f) const {
  return stack_context(norm_.apply(f), context_) * W_;
}

MatrixRM RidgePredictor::predict(const Audio& audio) const {
  return predict_features(encoder_->encode(audio));
}

double ModelPredictor::train_minutes() const {
  const auto& t = model_->header().value("training", nlohmann::json::object());
  return t.contains("training_seconds") ? t["training_seconds"].get<double>() / 60.0 : NAN;
}

MatrixRM ModelPredictor::predict(const Audio& audio) const {
  return model_->predict_displacements(model_->encoder().encode(audio));
}

}  // namespace glossa::eval
