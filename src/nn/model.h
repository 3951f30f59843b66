#pragma once
// A trained speech-to-articulation model: encoder config + normalisation + decoder weights +
// landmark set + neutral poses, loaded from one model file. Inference only; see train/.
#include <filesystem>
#include <memory>
#include <string>

#include <nlohmann/json.hpp>

#include "audio/audio.h"
#include "ema/landmarks.h"
#include "features/encoder.h"

namespace glossa::nn {

// Number of CPU threads libtorch (and Eigen) use for inference and training in this process.
void set_threads(int threads);

class Model {
 public:
  // Throws glossa::Error naming the file when it is missing, damaged or of a newer version.
  static Model load(const std::filesystem::path& path);
  ~Model();
  Model(Model&&) noexcept;
  Model& operator=(Model&&) noexcept;

  const LandmarkSet& landmark_set() const;
  const features::Encoder& encoder() const;
  const nlohmann::json& header() const;  // everything the file says about itself
  std::string label() const;             // decoder label, e.g. "Bi-GRU-2L"
  int64_t parameter_count() const;

  // Raw (unnormalised) encoder features [T, D] -> displacements from the neutral pose [T, 3L].
  MatrixRM predict_displacements(const MatrixRM& features) const;
  // Audio -> absolute landmarks: displacements plus `neutral` (1 x 3L), or plus the model's
  // default neutral (the mean of its training speakers' neutral poses).
  LandmarkSeq predict(const Audio& audio, const RowVec* neutral = nullptr) const;
  RowVec default_neutral() const;

 private:
  Model();
  friend class ModelBuilder;
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace glossa::nn
