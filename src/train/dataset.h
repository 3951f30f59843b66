#pragma once
// Utterances as the learner sees them: encoder features and displacement targets (absolute
// landmarks minus the speaker's neutral pose), both [frames, dims], of equal length.
#include <functional>
#include <string>
#include <vector>

#include "ema/corpus.h"
#include "features/cache.h"

namespace glossa::train {

struct Sequence {
  std::string id;
  std::string speaker;
  MatrixRM features;  // raw encoder output
  MatrixRM targets;   // displacements, mm
  double seconds = 0;
};

std::vector<Sequence> load_sequences(
    const ema::Corpus& corpus, const std::vector<std::string>& ids,
    const features::Encoder& encoder, const features::FeatureCache& cache,
    const std::function<void(size_t, size_t)>& progress = {});

}  // namespace glossa::train
