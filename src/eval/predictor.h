#pragma once
// Anything evaluated in a results table: a trained model or one of the two baselines. A
// predictor maps audio to displacements from the speaker's neutral pose, [frames, 3L].
#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include "audio/audio.h"
#include "core/matrix.h"
#include "features/encoder.h"
#include "features/normalizer.h"
#include "nn/model.h"
#include "train/dataset.h"

namespace glossa::eval {

class Predictor {
 public:
  virtual ~Predictor() = default;
  virtual std::string name() const = 0;
  virtual int64_t parameters() const { return 0; }
  virtual double train_minutes() const { return NAN; }
  virtual MatrixRM predict(const Audio& audio) const = 0;
};

// Predicts no displacement: the speaker's neutral (mean) pose in every frame.
class MeanPosePredictor : public Predictor {
 public:
  explicit MeanPosePredictor(size_t landmarks) : L_(landmarks) {}
  std::string name() const override { return "mean pose"; }
  MatrixRM predict(const Audio& audio) const override;

 private:
  size_t L_;
};

// Ridge regression on standardised features stacked over frames t-context..t+context.
// The regularisation weight is chosen on the validation sequences from a log grid.
class RidgePredictor : public Predictor {
 public:
  static std::unique_ptr<RidgePredictor> fit(const nlohmann::json& encoder_config,
                                             const std::vector<train::Sequence>& train,
                                             const std::vector<train::Sequence>& val,
                                             int context = 5);
  std::string name() const override;
  int64_t parameters() const override { return W_.size(); }
  double train_minutes() const override { return train_minutes_; }
  MatrixRM predict(const Audio& audio) const override;
  MatrixRM predict_features(const MatrixRM& features) const;
  double lambda() const { return lambda_; }

 private:
  std::unique_ptr<features::Encoder> encoder_;
  features::Normalizer norm_;
  int context_ = 5;
  double lambda_ = 0;
  double train_minutes_ = 0;
  Eigen::MatrixXf W_;  // [(2c+1)D + 1, 3L]
};

// Stacks rows t-c..t+c (edge-replicated) of standardised features, plus a bias column.
Eigen::MatrixXf stack_context(const MatrixRM& x, int context);

class ModelPredictor : public Predictor {
 public:
  ModelPredictor(std::shared_ptr<nn::Model> model, std::string name)
      : model_(std::move(model)), name_(std::move(name)) {}
  std::string name() const override { return name_; }
  int64_t parameters() const override { return model_->parameter_count(); }
  double train_minutes() const override;
  MatrixRM predict(const Audio& audio) const override;

 private:
  std::shared_ptr<nn::Model> model_;
  std::string name_;
};

}  // namespace glossa::eval
