#include "features/spectrum.h"

#include <cmath>
#include <complex>
#include <unsupported/Eigen/FFT>

namespace glossa::features {

MatrixRM power_spectrum(const std::vector<float>& samples, const StftConfig& cfg) {
  const size_t n = samples.size();
  const size_t frames = (n + cfg.hop - 1) / cfg.hop;
  const int bins = cfg.n_fft / 2 + 1;
  MatrixRM out(static_cast<Eigen::Index>(frames), bins);
  std::vector<float> window(cfg.n_fft);
  for (int i = 0; i < cfg.n_fft; ++i)
    window[i] = 0.5f - 0.5f * static_cast<float>(std::cos(2.0 * M_PI * i / cfg.n_fft));
  Eigen::FFT<float> fft;
  std::vector<float> frame(cfg.n_fft);
  std::vector<std::complex<float>> spec;
  const long half = cfg.n_fft / 2;
  for (size_t t = 0; t < frames; ++t) {
    const long start = static_cast<long>(t) * cfg.hop - half;
    for (int i = 0; i < cfg.n_fft; ++i) {
      const long k = start + i;
      frame[i] = (k >= 0 && k < static_cast<long>(n)) ? samples[k] * window[i] : 0.f;
    }
    fft.fwd(spec, frame);
    for (int b = 0; b < bins; ++b) out(static_cast<Eigen::Index>(t), b) = std::norm(spec[b]);
  }
  return out;
}

// Slaney mel scale: linear below 1 kHz, logarithmic above.
double hz_to_mel(double hz) {
  const double f_sp = 200.0 / 3.0;
  const double min_log_hz = 1000.0, min_log_mel = min_log_hz / f_sp;
  const double logstep = std::log(6.4) / 27.0;
  return hz < min_log_hz ? hz / f_sp : min_log_mel + std::log(hz / min_log_hz) / logstep;
}

double mel_to_hz(double mel) {
  const double f_sp = 200.0 / 3.0;
  const double min_log_hz = 1000.0, min_log_mel = min_log_hz / f_sp;
  const double logstep = std::log(6.4) / 27.0;
  return mel < min_log_mel ? mel * f_sp : min_log_hz * std::exp(logstep * (mel - min_log_mel));
}

MatrixRM mel_filterbank(int sample_rate, int n_fft, int n_mels, double fmin, double fmax) {
  const int bins = n_fft / 2 + 1;
  MatrixRM fb = MatrixRM::Zero(n_mels, bins);
  std::vector<double> edges(n_mels + 2);
  const double mmin = hz_to_mel(fmin), mmax = hz_to_mel(fmax);
  for (int i = 0; i < n_mels + 2; ++i) edges[i] = mel_to_hz(mmin + (mmax - mmin) * i / (n_mels + 1));
  for (int m = 0; m < n_mels; ++m) {
    const double lo = edges[m], mid = edges[m + 1], hi = edges[m + 2];
    const double norm = 2.0 / (hi - lo);
    for (int b = 0; b < bins; ++b) {
      const double f = double(b) * sample_rate / n_fft;
      const double up = (f - lo) / (mid - lo), down = (hi - f) / (hi - mid);
      const double w = std::max(0.0, std::min(up, down));
      fb(m, b) = static_cast<float>(w * norm);
    }
  }
  return fb;
}

}  // namespace glossa::features
