// MFCC and log-mel encoders. The papers' MFCC (SPEC.md B.41, after Alexanderson et al. 2020):
// 27 mel bands, 27 coefficients per 20 ms frame. The window they print ("2080 Hz") is garbled,
// so glossa uses a 32 ms (512-sample) Hann window; power spectrum, Slaney mel filterbank
// 0-8 kHz, 10 log10 (floor 1e-10), orthonormal DCT-II. No deltas and no utterance-level
// top-dB clipping, so a frame depends only on its own 32 ms of audio (streaming-safe).
#include <cmath>

#include "core/error.h"
#include "features/encoder.h"
#include "features/spectrum.h"

namespace glossa::features {
namespace {

using nlohmann::json;

struct MelConfig {
  int n_fft = 512;
  int n_mels = 27;
  double fmin = 0;
  double fmax = 8000;
};

MelConfig read_mel_config(const json& c, int default_mels) {
  MelConfig m;
  m.n_mels = default_mels;
  m.n_fft = c.value("n_fft", m.n_fft);
  m.n_mels = c.value("n_mels", m.n_mels);
  m.fmin = c.value("fmin", m.fmin);
  m.fmax = c.value("fmax", m.fmax);
  if (m.n_fft < 64 || m.n_fft > 8192 || (m.n_fft & (m.n_fft - 1)))
    throw Error("encoder config: n_fft must be a power of two between 64 and 8192");
  if (m.n_mels < 1 || m.n_mels > 256) throw Error("encoder config: n_mels must be in 1..256");
  if (m.fmin < 0 || m.fmax <= m.fmin || m.fmax > kSampleRate / 2)
    throw Error("encoder config: need 0 <= fmin < fmax <= 8000");
  return m;
}

MatrixRM log_mel(const Audio& audio, const MelConfig& m, const MatrixRM& fb) {
  if (audio.sample_rate != kSampleRate)
    throw Error("encoder: audio must be 16 kHz (got " + std::to_string(audio.sample_rate) + ")");
  const MatrixRM power = power_spectrum(audio.samples, {m.n_fft, kHop});
  MatrixRM mel = power * fb.transpose();
  return mel.unaryExpr([](float v) { return 10.f * std::log10(std::max(v, 1e-10f)); });
}

class LogMelEncoder : public Encoder {
 public:
  explicit LogMelEncoder(const json& c)
      : m_(read_mel_config(c, 40)), fb_(mel_filterbank(kSampleRate, m_.n_fft, m_.n_mels, m_.fmin, m_.fmax)) {}
  std::string name() const override { return "logmel"; }
  int dims() const override { return m_.n_mels; }
  json config() const override {
    return {{"type", "logmel"}, {"n_fft", m_.n_fft}, {"n_mels", m_.n_mels},
            {"fmin", m_.fmin},  {"fmax", m_.fmax},   {"hop", kHop}};
  }
  MatrixRM encode(const Audio& audio) const override { return log_mel(audio, m_, fb_); }

 private:
  MelConfig m_;
  MatrixRM fb_;
};

class MfccEncoder : public Encoder {
 public:
  explicit MfccEncoder(const json& c)
      : m_(read_mel_config(c, 27)),
        n_mfcc_(c.value("n_mfcc", m_.n_mels)),
        fb_(mel_filterbank(kSampleRate, m_.n_fft, m_.n_mels, m_.fmin, m_.fmax)) {
    if (n_mfcc_ < 1 || n_mfcc_ > m_.n_mels)
      throw Error("encoder config: n_mfcc must be in 1..n_mels");
    // Orthonormal DCT-II, [n_mfcc, n_mels].
    dct_.resize(n_mfcc_, m_.n_mels);
    for (int k = 0; k < n_mfcc_; ++k) {
      const double scale = std::sqrt((k == 0 ? 1.0 : 2.0) / m_.n_mels);
      for (int n = 0; n < m_.n_mels; ++n)
        dct_(k, n) = static_cast<float>(scale * std::cos(M_PI * k * (2 * n + 1) / (2.0 * m_.n_mels)));
    }
  }
  std::string name() const override { return "mfcc"; }
  int dims() const override { return n_mfcc_; }
  json config() const override {
    return {{"type", "mfcc"}, {"n_fft", m_.n_fft}, {"n_mels", m_.n_mels}, {"n_mfcc", n_mfcc_},
            {"fmin", m_.fmin}, {"fmax", m_.fmax},   {"hop", kHop}};
  }
  MatrixRM encode(const Audio& audio) const override {
    return log_mel(audio, m_, fb_) * dct_.transpose();
  }

 private:
  MelConfig m_;
  int n_mfcc_;
  MatrixRM fb_;
  MatrixRM dct_;
};

}  // namespace

std::unique_ptr<Encoder> make_encoder(const json& config) {
  const std::string type = config.value("type", "");
  if (type == "mfcc") return std::make_unique<MfccEncoder>(config);
  if (type == "logmel") return std::make_unique<LogMelEncoder>(config);
  throw Error("unknown encoder type '" + type + "' (available: mfcc, logmel)");
}

std::unique_ptr<Encoder> make_encoder(const std::string& type) {
  return make_encoder(json{{"type", type}});
}

}  // namespace glossa::features
