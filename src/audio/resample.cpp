#include "audio/resample.h"

#include <soxr.h>

#include <cmath>

#include "core/error.h"

namespace glossa::audio {

std::vector<float> resample(const std::vector<float>& interleaved, int channels, double in_rate,
                            double out_rate) {
  if (channels <= 0 || in_rate <= 0 || out_rate <= 0)
    throw Error("resample: channels and rates must be positive");
  const size_t in_frames = interleaved.size() / static_cast<size_t>(channels);
  if (in_rate == out_rate) return interleaved;
  const size_t out_frames =
      static_cast<size_t>(std::llround(static_cast<double>(in_frames) * out_rate / in_rate));
  std::vector<float> out(out_frames * static_cast<size_t>(channels));
  if (in_frames == 0 || out_frames == 0) return {};
  const soxr_io_spec_t io = soxr_io_spec(SOXR_FLOAT32_I, SOXR_FLOAT32_I);
  const soxr_quality_spec_t q = soxr_quality_spec(SOXR_HQ, 0);
  size_t done = 0;
  const soxr_error_t err =
      soxr_oneshot(in_rate, out_rate, static_cast<unsigned>(channels), interleaved.data(),
                   in_frames, nullptr, out.data(), out_frames, &done, &io, &q, nullptr);
  if (err) throw Error(std::string("resample: soxr failed: ") + err);
  out.resize(done * static_cast<size_t>(channels));
  // soxr may return a frame fewer than the rounded length; pad by repeating the last frame.
  while (out.size() < out_frames * static_cast<size_t>(channels)) {
    for (int c = 0; c < channels; ++c) out.push_back(out[out.size() - channels]);
  }
  return out;
}

Audio resample(const Audio& audio, int out_rate) {
  Audio out;
  out.sample_rate = out_rate;
  out.samples = resample(audio.samples, 1, audio.sample_rate, out_rate);
  return out;
}

}  // namespace glossa::audio
