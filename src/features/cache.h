#pragma once
// A feature cache keyed by the audio's content and the encoder's config, so that features are
// computed once per corpus and configuration. Entries are .npy files written atomically.
#include <filesystem>

#include "features/encoder.h"

namespace glossa::features {

class FeatureCache {
 public:
  // An empty `dir` disables caching.
  explicit FeatureCache(std::filesystem::path dir) : dir_(std::move(dir)) {}

  // The default folder: $GLOSSA_CACHE, else $XDG_CACHE_HOME/glossa, else ~/.cache/glossa.
  static std::filesystem::path default_dir();

  // Returns cached features when present and well-formed, else encodes and stores them.
  MatrixRM get(const Encoder& encoder, const Audio& audio) const;

  std::filesystem::path entry_path(const Encoder& encoder, const Audio& audio) const;

 private:
  std::filesystem::path dir_;
};

}  // namespace glossa::features
