#pragma once
// The features stage: an Encoder maps 16 kHz audio to one feature vector per 20 ms frame
// (50 fps), frame t centred on sample 320 t, so that frame t lines up with landmark frame t.
// An utterance of n samples gives ceil(n / 320) frames.
#include <memory>
#include <string>

#include <nlohmann/json.hpp>

#include "audio/audio.h"
#include "core/matrix.h"

namespace glossa::features {

inline constexpr int kHop = 320;

inline size_t frame_count(size_t samples) { return (samples + kHop - 1) / kHop; }

class Encoder {
 public:
  virtual ~Encoder() = default;
  virtual std::string name() const = 0;
  virtual int dims() const = 0;
  // Everything that determines the output; stored in model files and used as the cache key.
  virtual nlohmann::json config() const = 0;
  // [frame_count(samples), dims]. Throws glossa::Error on audio that is not 16 kHz.
  virtual MatrixRM encode(const Audio& audio) const = 0;
};

// Builds an encoder from its config ({"type": "mfcc" | "logmel", ...}); missing keys take the
// defaults. Throws glossa::Error on an unknown type or a bad value.
std::unique_ptr<Encoder> make_encoder(const nlohmann::json& config);

// "mfcc" or "logmel" with defaults.
std::unique_ptr<Encoder> make_encoder(const std::string& type);
inline std::unique_ptr<Encoder> make_encoder(const char* type) {
  return make_encoder(std::string(type));
}

}  // namespace glossa::features
