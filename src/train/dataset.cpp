#include "train/dataset.h"

#include "core/error.h"

namespace glossa::train {

std::vector<Sequence> load_sequences(const ema::Corpus& corpus,
                                     const std::vector<std::string>& ids,
                                     const features::Encoder& encoder,
                                     const features::FeatureCache& cache,
                                     const std::function<void(size_t, size_t)>& progress) {
  std::vector<Sequence> out;
  out.reserve(ids.size());
  for (size_t i = 0; i < ids.size(); ++i) {
    if (progress) progress(i, ids.size());
    const ema::Utterance& u = corpus.utterance(ids[i]);
    const Audio audio = corpus.load_audio(u);
    LandmarkSeq lm = corpus.load_landmarks(u);
    Sequence s;
    s.id = u.id;
    s.speaker = u.speaker;
    s.seconds = audio.seconds();
    s.features = cache.get(encoder, audio);
    const Eigen::Index n = std::min(s.features.rows(), lm.positions.rows());
    if (n == 0) throw file_error(corpus.landmarks_path(u), "utterance has no frames");
    s.features.conservativeResize(n, Eigen::NoChange);
    s.targets = lm.positions.topRows(n).rowwise() - corpus.speaker(u.speaker).neutral;
    out.push_back(std::move(s));
  }
  if (progress) progress(ids.size(), ids.size());
  return out;
}

}  // namespace glossa::train
