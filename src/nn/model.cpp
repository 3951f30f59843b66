#include "nn/model.h"

#include <ATen/Parallel.h>

#include <algorithm>

#include "core/error.h"
#include "features/normalizer.h"
#include "nn/cpu_decoder.h"
#include "nn/model_file.h"

namespace glossa::nn {

void set_threads(int threads) {
  if (threads < 1) throw Error("threads must be at least 1");
  at::set_num_threads(threads);
  Eigen::setNbThreads(threads);
}

struct Model::Impl {
  nlohmann::json header;
  LandmarkSet set;
  std::unique_ptr<features::Encoder> encoder;
  features::Normalizer feature_norm, target_norm;
  CpuDecoder decoder;
  RowVec neutral;
};

Model::Model() : impl_(std::make_unique<Impl>()) {}
Model::~Model() = default;
Model::Model(Model&&) noexcept = default;
Model& Model::operator=(Model&&) noexcept = default;

Model Model::load(const std::filesystem::path& path) {
  ModelFile mf = ModelFile::read(path);
  Model m;
  Impl& I = *m.impl_;
  const std::string name = path.string();
  try {
    const auto& h = mf.header;
    if (h.value("kind", "") != "glossa-landmark-model")
      throw file_error(path, "not a glossa landmark model");
    I.header = h;
    I.set.names = h.at("landmark_set").get<std::vector<std::string>>();
    I.encoder = features::make_encoder(h.at("encoder"));
    I.feature_norm = features::Normalizer::from_json(h.at("feature_norm"));
    I.target_norm = features::Normalizer::from_json(h.at("target_norm"));
    if (I.feature_norm.mean.size() != I.encoder->dims())
      throw file_error(path, "feature normalisation does not match the encoder's dimensions");
    const auto out_dims = static_cast<int>(3 * I.set.size());
    if (I.target_norm.mean.size() != out_dims)
      throw file_error(path, "target normalisation does not match the landmark set");
    const auto neutral = h.at("neutral").at("default").get<std::vector<float>>();
    if (static_cast<int>(neutral.size()) != out_dims)
      throw file_error(path, "default neutral pose does not match the landmark set");
    I.neutral = Eigen::Map<const RowVec>(neutral.data(), 1, out_dims);
    DecoderConfig dc = DecoderConfig::from_json(h.at("decoder"));
    dc.resolve_inference(0);  // files from before the option ran whole utterances
    I.decoder = CpuDecoder(dc, I.encoder->dims(), out_dims, mf.tensors, name);
  } catch (const nlohmann::json::exception& e) {
    throw file_error(path, std::string("model header is incomplete: ") + e.what());
  } catch (const Error& e) {
    const std::string what = e.what();
    if (what.rfind(name, 0) == 0) throw;
    throw file_error(path, what);
  }
  return m;
}

const LandmarkSet& Model::landmark_set() const { return impl_->set; }
const features::Encoder& Model::encoder() const { return *impl_->encoder; }
const nlohmann::json& Model::header() const { return impl_->header; }
std::string Model::label() const { return impl_->decoder.config().label(); }
int64_t Model::parameter_count() const { return impl_->decoder.parameter_count(); }
RowVec Model::default_neutral() const { return impl_->neutral; }

MatrixRM Model::predict_displacements(const MatrixRM& features) const {
  const Impl& I = *impl_;
  if (features.cols() != I.encoder->dims())
    throw Error("model: features have " + std::to_string(features.cols()) +
                " dimensions, the model expects " + std::to_string(I.encoder->dims()));
  if (features.rows() == 0) return MatrixRM(0, 3 * I.set.size());
  MatrixRM x = I.feature_norm.apply(features);
  const MatrixRM z = I.decoder.forward(x);
  return I.target_norm.invert(z);
}

LandmarkSeq Model::predict(const Audio& audio, const RowVec* neutral) const {
  const Impl& I = *impl_;
  const RowVec& base = neutral ? *neutral : I.neutral;
  if (base.size() != static_cast<Eigen::Index>(3 * I.set.size()))
    throw Error("model: the neutral pose does not match the model's landmark set");
  LandmarkSeq seq;
  seq.set = I.set;
  seq.rate = 50.0;
  seq.positions = predict_displacements(I.encoder->encode(audio));
  seq.positions.rowwise() += base;
  return seq;
}

}  // namespace glossa::nn
