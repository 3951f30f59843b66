#pragma once
// The value type the audio stage hands on: mono float samples in [-1, 1] at a known rate.
// Inside glossa the rate is always 16 kHz after `load_audio`.
#include <vector>

namespace glossa {

inline constexpr int kSampleRate = 16000;

struct Audio {
  std::vector<float> samples;
  int sample_rate = kSampleRate;

  double seconds() const {
    return sample_rate > 0 ? static_cast<double>(samples.size()) / sample_rate : 0.0;
  }
};

}  // namespace glossa
