// MFCC and log-mel encoders (src/features/encoder.h, spectrum.h), checked against an independent
// NumPy reference (tests/oracles/mfcc_reference.py) and on hand-made signals.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "core/error.h"
#include "features/encoder.h"
#include "features/spectrum.h"
#include "io/npy.h"
#include "support/fixtures.h"

namespace glossa::features {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;
using testing::TempDir;

constexpr const char* kPython = "/usr/bin/python3";

fs::path oracle_script() {
  return fs::path(GLOSSA_SOURCE_DIR) / "tests" / "oracles" / "mfcc_reference.py";
}

// Deterministic test signal: a linear chirp 100 Hz -> 7 kHz with a slow amplitude envelope,
// plus uniform noise from a fixed LCG, so every mel band has energy.
Audio chirp_plus_noise(double seconds) {
  Audio a;
  a.sample_rate = kSampleRate;
  const auto n = static_cast<size_t>(seconds * kSampleRate);
  const double f0 = 100.0, f1 = 7000.0;
  uint32_t s = 2024;
  for (size_t i = 0; i < n; ++i) {
    const double t = double(i) / kSampleRate;
    const double phase = 2.0 * M_PI * (f0 * t + 0.5 * (f1 - f0) / seconds * t * t);
    const double env = 0.3 + 0.2 * std::sin(2.0 * M_PI * 1.7 * t);
    s = s * 1664525u + 1013904223u;
    const double noise = (double(s >> 8) / double(1u << 24) - 0.5) * 0.02;
    a.samples.push_back(static_cast<float>(env * std::sin(phase) + noise));
  }
  return a;
}

io::NpyArray load(const fs::path& p) { return io::read_npy(p); }

double max_abs_diff(const MatrixRM& got, const io::NpyArray& want) {
  double m = 0;
  for (Eigen::Index i = 0; i < got.size(); ++i)
    m = std::max(m, std::abs(double(got.data()[i]) - double(want.data[static_cast<size_t>(i)])));
  return m;
}

// Runs the NumPy oracle once for the suite; fails when /usr/bin/python3 lacks NumPy.
class MfccOracle : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = new TempDir();
    audio_ = new Audio(chirp_plus_noise(1.3));
    std::string out;
    if (testing::run_command(fmt::format("{} -c 'import numpy'", kPython), &out) != 0) {
      error_ = fmt::format(
          "{} cannot import numpy (install python3-numpy, as scripts/install-deps.sh does); "
          "the MFCC reference needs it:\n{}",
          kPython, out);
      return;
    }
    const fs::path in = *dir_ / "audio.npy";
    io::write_npy(in, audio_->samples.data(), {audio_->samples.size()});
    if (testing::run_command(fmt::format("{} '{}' '{}' '{}'", kPython, oracle_script().string(),
                                         in.string(), dir_->path().string()),
                             &out) != 0)
      error_ = "oracle " + oracle_script().string() + " failed:\n" + out;
  }
  static void TearDownTestSuite() {
    delete audio_;
    delete dir_;
  }
  void SetUp() override { ASSERT_TRUE(error_.empty()) << error_; }

  static inline TempDir* dir_ = nullptr;
  static inline Audio* audio_ = nullptr;
  static inline std::string error_;
};

TEST_F(MfccOracle, MelFilterbankMatchesReference) {
  const io::NpyArray want = load(*dir_ / "melfb27.npy");
  ASSERT_EQ(want.shape, (std::vector<size_t>{27, 257}));
  const MatrixRM fb = mel_filterbank(kSampleRate, 512, 27, 0.0, 8000.0);
  ASSERT_EQ(fb.rows(), 27);
  ASSERT_EQ(fb.cols(), 257);
  // Weights are of order 1e-3 (area-normalised over hundreds of Hz); float32 storage.
  EXPECT_LT(max_abs_diff(fb, want), 1e-8);
}

TEST_F(MfccOracle, PowerSpectrumMatchesReference) {
  const io::NpyArray want = load(*dir_ / "power.npy");
  const MatrixRM p = power_spectrum(audio_->samples, {});
  ASSERT_EQ(want.shape,
            (std::vector<size_t>{static_cast<size_t>(p.rows()), static_cast<size_t>(p.cols())}));
  // Relative to each frame's peak: float32 FFT round-off is relative to the frame's energy.
  double worst = 0;
  for (Eigen::Index t = 0; t < p.rows(); ++t) {
    double peak = 0;
    for (Eigen::Index b = 0; b < p.cols(); ++b)
      peak = std::max(peak, double(want.data[size_t(t * p.cols() + b)]));
    for (Eigen::Index b = 0; b < p.cols(); ++b)
      worst =
          std::max(worst, std::abs(p(t, b) - double(want.data[size_t(t * p.cols() + b)])) / peak);
  }
  EXPECT_LT(worst, 1e-5);
}

// Tolerance: glossa computes in float32 (window, FFT, power, mel product, log10), the oracle in
// float64. float32 FFT round-off is ~1e-7 of the frame's energy, so a mel band 40 dB below the
// frame's strongest band carries a relative error of ~1e-5, i.e. ~5e-5 dB (10 log10 turns a
// relative error e into 4.34 e dB); the mel product and log10 add ~1e-7 relative, and float32
// spacing at |100| dB is ~8e-6. The orthonormal DCT mixes 27 bands with weights <= 0.27, so an
// MFCC carries at most ~7x a band's error. Measured here: ~1e-4 dB on log-mel and ~5e-5 on
// MFCCs of magnitude up to ~200. kDbTolerance = 2e-3 leaves a ~20x margin for other compilers,
// FMA and FFT back-ends, and is still far below what a real difference causes: on this signal a
// symmetric instead of periodic Hann window moves MFCCs by 0.11, frames centred one sample off
// by 0.16, and another mel scale or normalisation by whole dB.
constexpr double kDbTolerance = 2e-3;

TEST_F(MfccOracle, MfccMatchesReference) {
  const io::NpyArray want = load(*dir_ / "mfcc.npy");
  const auto enc = make_encoder("mfcc");
  const MatrixRM got = enc->encode(*audio_);
  ASSERT_EQ(got.rows(), 65);  // 1.3 s = 20800 samples, ceil(20800 / 320)
  ASSERT_EQ(want.shape, (std::vector<size_t>{static_cast<size_t>(got.rows()),
                                             static_cast<size_t>(got.cols())}));
  double scale = 0;
  for (float v : want.data) scale = std::max(scale, double(std::abs(v)));
  EXPECT_GT(scale, 10.0) << "the fixture should produce MFCCs of order 10-100";
  const double diff = max_abs_diff(got, want);
  EXPECT_LT(diff, kDbTolerance) << "max |MFCC - reference|, values up to " << scale;
}

TEST_F(MfccOracle, LogMelMatchesReference) {
  const io::NpyArray want = load(*dir_ / "logmel.npy");
  const auto enc = make_encoder("logmel");
  const MatrixRM got = enc->encode(*audio_);
  ASSERT_EQ(enc->dims(), 40);
  ASSERT_EQ(want.shape, (std::vector<size_t>{static_cast<size_t>(got.rows()),
                                             static_cast<size_t>(got.cols())}));
  EXPECT_LT(max_abs_diff(got, want), kDbTolerance) << "max |log-mel - reference|, dB";
}

// ---------------------------------------------------------------------------------------------
// Frames

TEST(Mfcc, FrameCountIsCeilSamplesOverHop) {
  const auto mfcc = make_encoder("mfcc");
  const auto logmel = make_encoder("logmel");
  for (size_t n : {1u, 100u, 319u, 320u, 321u, 640u, 959u, 16000u, 16001u, 20800u}) {
    Audio a;
    a.samples.assign(n, 0.01f);
    const size_t want = (n + 319) / 320;
    EXPECT_EQ(frame_count(n), want) << n;
    EXPECT_EQ(static_cast<size_t>(mfcc->encode(a).rows()), want) << n;
    EXPECT_EQ(static_cast<size_t>(logmel->encode(a).rows()), want) << n;
    EXPECT_EQ(static_cast<size_t>(power_spectrum(a.samples, {}).rows()), want) << n;
  }
  Audio empty;
  const MatrixRM e = mfcc->encode(empty);
  EXPECT_EQ(e.rows(), 0);
  EXPECT_EQ(e.cols(), 27);
}

TEST(Mfcc, ImpulseShowsUpInItsFrame) {
  const auto logmel = make_encoder("logmel");
  const size_t n = 320 * 30;
  for (size_t k : {0u, 1u, 7u, 15u, 29u}) {
    for (int offset : {0, 100, -100}) {
      const long at = long(320 * k) + offset;
      if (at < 0 || at >= long(n)) continue;
      Audio a;
      a.samples.assign(n, 0.f);
      // Very low-level deterministic noise so that no band sits at the 1e-10 floor.
      uint32_t s = 7;
      for (float& v : a.samples) {
        s = s * 1664525u + 1013904223u;
        v = (float(s >> 8) / float(1u << 24) - 0.5f) * 1e-4f;
      }
      a.samples[size_t(at)] = 1.0f;
      const MatrixRM m = logmel->encode(a);
      Eigen::Index best = -1;
      m.rowwise().sum().maxCoeff(&best);
      EXPECT_EQ(best, Eigen::Index(k)) << "impulse at sample " << at;
    }
  }
}

TEST(Mfcc, FrameDependsOnlyOnItsOwnWindow) {
  // Streaming safety: changing audio more than n_fft/2 samples away from a frame's centre must
  // not change that frame.
  const auto enc = make_encoder("mfcc");
  Audio a = chirp_plus_noise(0.5);
  const MatrixRM before = enc->encode(a);
  for (size_t i = 320 * 12 + 256; i < a.samples.size(); ++i) a.samples[i] = 0.5f;
  const MatrixRM after = enc->encode(a);
  ASSERT_EQ(before.rows(), after.rows());
  for (Eigen::Index t = 0; t <= 12; ++t) EXPECT_EQ(before.row(t), after.row(t)) << "frame " << t;
  EXPECT_NE(before.row(13), after.row(13));
}

// ---------------------------------------------------------------------------------------------
// Mel scale and configuration

TEST(Mfcc, SlaneyMelScale) {
  // Linear below 1 kHz at 3 mels per 200 Hz, then 27 mels per factor 6.4.
  EXPECT_NEAR(hz_to_mel(0.0), 0.0, 1e-12);
  EXPECT_NEAR(hz_to_mel(200.0), 3.0, 1e-12);
  EXPECT_NEAR(hz_to_mel(1000.0), 15.0, 1e-12);
  EXPECT_NEAR(hz_to_mel(6400.0), 42.0, 1e-9);
  EXPECT_NEAR(hz_to_mel(1000.0 * 6.4 * 6.4), 69.0, 1e-9);
  for (double hz : {0.0, 55.0, 999.0, 1000.0, 1001.0, 4321.0, 8000.0})
    EXPECT_NEAR(mel_to_hz(hz_to_mel(hz)), hz, 1e-9 * std::max(1.0, hz));
}

TEST(Mfcc, EncoderDimsAndConfig) {
  const auto mfcc = make_encoder("mfcc");
  EXPECT_EQ(mfcc->name(), "mfcc");
  EXPECT_EQ(mfcc->dims(), 27);
  const json c = mfcc->config();
  EXPECT_EQ(c.at("n_fft"), 512);
  EXPECT_EQ(c.at("n_mels"), 27);
  EXPECT_EQ(c.at("n_mfcc"), 27);
  EXPECT_EQ(c.at("hop"), 320);
  EXPECT_EQ(c.at("fmax").get<double>(), 8000.0);
  // A config round-trips through make_encoder.
  const auto again = make_encoder(c);
  EXPECT_EQ(again->config(), c);
  const auto small = make_encoder(json{{"type", "mfcc"}, {"n_mels", 40}, {"n_mfcc", 13}});
  EXPECT_EQ(small->dims(), 13);
  Audio a = chirp_plus_noise(0.1);
  EXPECT_EQ(small->encode(a).cols(), 13);
  EXPECT_EQ(make_encoder("logmel")->dims(), 40);
}

void expect_config_error(const json& config) {
  EXPECT_THROW(make_encoder(config), Error) << config.dump();
}

TEST(Mfcc, BadConfigsAreErrors) {
  expect_config_error({{"type", "mfcc"}, {"n_fft", 500}});
  expect_config_error({{"type", "mfcc"}, {"n_fft", 32}});
  expect_config_error({{"type", "mfcc"}, {"n_fft", 16384}});
  expect_config_error({{"type", "logmel"}, {"n_fft", 1000}});
  expect_config_error({{"type", "mfcc"}, {"n_mfcc", 28}});  // > n_mels (27)
  expect_config_error({{"type", "mfcc"}, {"n_mels", 20}, {"n_mfcc", 21}});
  expect_config_error({{"type", "mfcc"}, {"n_mfcc", 0}});
  expect_config_error({{"type", "mfcc"}, {"n_mels", 0}});
  expect_config_error({{"type", "logmel"}, {"fmax", 9000}});
  expect_config_error({{"type", "logmel"}, {"fmin", 4000}, {"fmax", 3000}});
  expect_config_error({{"type", "plp"}});
  expect_config_error(json::object());
  try {
    make_encoder("wavlm-large-typo");
    FAIL() << "expected glossa::Error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("wavlm-large-typo"), std::string::npos) << e.what();
  }
}

TEST(Mfcc, AudioNotAt16kHzIsAnError) {
  for (const char* type : {"mfcc", "logmel"}) {
    const auto enc = make_encoder(type);
    Audio a;
    a.sample_rate = 8000;
    a.samples.assign(8000, 0.1f);
    try {
      enc->encode(a);
      ADD_FAILURE() << type << ": expected glossa::Error";
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find("8000"), std::string::npos) << e.what();
    }
  }
}

}  // namespace
}  // namespace glossa::features
