#pragma once
// Short-time power spectrum and mel filterbank shared by the MFCC and log-mel encoders.
#include <vector>

#include "audio/audio.h"
#include "core/matrix.h"

namespace glossa::features {

struct StftConfig {
  int n_fft = 512;  // samples (32 ms); the periodic Hann window spans n_fft
  int hop = 320;    // 20 ms
};

// Power spectrum |X|^2, [frames, n_fft/2 + 1]; frame t is centred on sample t * hop (the signal
// is zero-padded by n_fft/2 on both sides), frames = ceil(samples / hop).
MatrixRM power_spectrum(const std::vector<float>& samples, const StftConfig& cfg);

// Slaney-style mel filterbank (the mel scale and area normalisation librosa uses by default),
// [n_mels, n_fft/2 + 1].
MatrixRM mel_filterbank(int sample_rate, int n_fft, int n_mels, double fmin, double fmax);

double hz_to_mel(double hz);
double mel_to_hz(double mel);

}  // namespace glossa::features
