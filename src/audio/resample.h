#pragma once
// Band-limited resampling with libsoxr (its "high quality" recipe).
#include <vector>

#include "audio/audio.h"

namespace glossa::audio {

// Resamples interleaved float data with `channels` channels from `in_rate` to `out_rate`.
// Output length is round(frames * out_rate / in_rate).
std::vector<float> resample(const std::vector<float>& interleaved, int channels, double in_rate,
                            double out_rate);

Audio resample(const Audio& audio, int out_rate);

}  // namespace glossa::audio
