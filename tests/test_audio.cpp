// Audio decoding and resampling (src/audio/decode.h, resample.h) on files written here with
// libsndfile: WAV, FLAC, OGG/Vorbis and MP3 at 44.1 kHz stereo.
#include <gtest/gtest.h>
#include <sndfile.h>

#include <cmath>
#include <complex>
#include <filesystem>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "audio/decode.h"
#include "audio/resample.h"
#include "core/error.h"
#include "io/atomic_file.h"
#include "support/fixtures.h"

namespace glossa::audio {
namespace {

namespace fs = std::filesystem;
using testing::TempDir;
using testing::write_bytes;

constexpr double kToneHz = 1000.0;
constexpr double kAmp = 0.5;
constexpr int kSourceRate = 44100;
constexpr double kSeconds = 2.0;

// Writes `frames` interleaved stereo frames with libsndfile. Returns false (with `why`) when
// this libsndfile cannot write the format.
bool write_stereo(const fs::path& path, int format, const std::vector<float>& interleaved, int rate,
                  std::string* why) {
  SF_INFO info{};
  info.samplerate = rate;
  info.channels = 2;
  info.format = format;
  if (!sf_format_check(&info)) {
    *why = "sf_format_check rejects the format";
    return false;
  }
  SNDFILE* f = sf_open(path.c_str(), SFM_WRITE, &info);
  if (!f) {
    *why = sf_strerror(nullptr);
    return false;
  }
  const sf_count_t frames = static_cast<sf_count_t>(interleaved.size() / 2);
  const sf_count_t wrote = sf_writef_float(f, interleaved.data(), frames);
  sf_close(f);
  if (wrote != frames) {
    *why = "short write";
    return false;
  }
  return true;
}

// Both channels carry the same 1 kHz sine.
std::vector<float> stereo_sine(int rate, double seconds, double hz, double amp) {
  const auto n = static_cast<size_t>(std::lround(seconds * rate));
  std::vector<float> out(2 * n);
  for (size_t i = 0; i < n; ++i) {
    const auto v = static_cast<float>(amp * std::sin(2.0 * M_PI * hz * double(i) / rate));
    out[2 * i] = v;
    out[2 * i + 1] = v;
  }
  return out;
}

// Magnitude of the DFT of `x` at frequency `hz` (Goertzel-style direct sum), normalised so a
// sine of amplitude A over a whole number of periods gives A.
double tone_amplitude(const std::vector<float>& x, size_t begin, size_t end, double hz, int rate) {
  std::complex<double> acc = 0;
  for (size_t i = begin; i < end; ++i)
    acc += double(x[i]) * std::polar(1.0, -2.0 * M_PI * hz * double(i) / rate);
  return 2.0 * std::abs(acc) / double(end - begin);
}

// Frequency from the number of upward zero crossings, with linear interpolation at both ends.
double zero_crossing_frequency(const std::vector<float>& x, size_t begin, size_t end, int rate) {
  double first = -1, last = -1;
  int crossings = 0;
  for (size_t i = begin + 1; i < end; ++i) {
    if (x[i - 1] < 0 && x[i] >= 0) {
      const double t = double(i - 1) + double(-x[i - 1]) / double(x[i] - x[i - 1]);
      if (first < 0) first = t;
      last = t;
      ++crossings;
    }
  }
  if (crossings < 2) return 0;
  return double(crossings - 1) * rate / (last - first);
}

double rms(const std::vector<float>& x, size_t begin, size_t end) {
  double s = 0;
  for (size_t i = begin; i < end; ++i) s += double(x[i]) * x[i];
  return std::sqrt(s / double(end - begin));
}

template <typename F>
void expect_file_error(const fs::path& path, F&& f, const std::string& needle = "") {
  try {
    f();
    ADD_FAILURE() << "expected glossa::Error for " << path;
  } catch (const Error& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find(path.string()), std::string::npos)
        << "message does not name the file: " << what;
    if (!needle.empty())
      EXPECT_NE(what.find(needle), std::string::npos)
          << "message lacks '" << needle << "': " << what;
  } catch (const std::exception& e) {
    ADD_FAILURE() << "threw a non-glossa exception: " << e.what();
  }
}

struct FormatCase {
  const char* name;
  const char* ext;
  int format;
  double amp_tolerance;  // relative
};

class DecodeFormat : public ::testing::TestWithParam<FormatCase> {};

TEST_P(DecodeFormat, SineComesOutAs16kMono) {
  const FormatCase& fc = GetParam();
  TempDir dir;
  const fs::path path = dir / (std::string("tone.") + fc.ext);
  std::string why;
  if (!write_stereo(path, fc.format, stereo_sine(kSourceRate, kSeconds, kToneHz, kAmp), kSourceRate,
                    &why)) {
    if (std::string(fc.name) == "mp3")
      GTEST_SKIP() << "this libsndfile (" << sf_version_string() << ") cannot write MP3: " << why;
    FAIL() << "cannot write the " << fc.name << " fixture: " << why;
  }

  DecodeInfo info;
  const Audio a = load_audio(path, &info);
  EXPECT_EQ(a.sample_rate, kSampleRate);
  EXPECT_EQ(info.source_rate, kSourceRate);
  EXPECT_EQ(info.source_channels, 2);
  // Duration within 1% (lossy codecs may add or trim a little padding).
  EXPECT_NEAR(a.seconds(), kSeconds, 0.01 * kSeconds) << fc.name;
  ASSERT_GT(a.samples.size(), size_t(kSampleRate));

  // Analyse the middle second, away from codec start-up and the end.
  const size_t begin = a.samples.size() / 2 - kSampleRate / 2;
  const size_t end = begin + kSampleRate;
  const double f = zero_crossing_frequency(a.samples, begin, end, kSampleRate);
  EXPECT_NEAR(f, kToneHz, 0.005 * kToneHz) << fc.name << ": zero-crossing frequency";
  const double at_tone = tone_amplitude(a.samples, begin, end, kToneHz, kSampleRate);
  EXPECT_NEAR(at_tone, kAmp, fc.amp_tolerance * kAmp) << fc.name << ": DFT amplitude at 1 kHz";
  EXPECT_NEAR(rms(a.samples, begin, end) * std::sqrt(2.0), kAmp, fc.amp_tolerance * kAmp)
      << fc.name << ": RMS amplitude";
  // Nothing much elsewhere in the spectrum.
  for (double other : {250.0, 500.0, 2000.0, 3000.0, 6000.0})
    EXPECT_LT(tone_amplitude(a.samples, begin, end, other, kSampleRate), 0.01 * kAmp)
        << fc.name << " at " << other << " Hz";
}

INSTANTIATE_TEST_SUITE_P(
    Formats, DecodeFormat,
    ::testing::Values(FormatCase{"wav", "wav", SF_FORMAT_WAV | SF_FORMAT_PCM_16, 0.01},
                      FormatCase{"flac", "flac", SF_FORMAT_FLAC | SF_FORMAT_PCM_16, 0.01},
                      FormatCase{"vorbis", "ogg", SF_FORMAT_OGG | SF_FORMAT_VORBIS, 0.05},
                      FormatCase{"mp3", "mp3", SF_FORMAT_MPEG | SF_FORMAT_MPEG_LAYER_III, 0.05}),
    [](const ::testing::TestParamInfo<FormatCase>& p) { return std::string(p.param.name); });

TEST(Decode, MonoMixIsTheChannelMean) {
  TempDir dir;
  const fs::path path = dir / "antiphase.wav";
  // L = +x, R = -x in float WAV: the mean is exactly zero.
  std::vector<float> st = stereo_sine(kSourceRate, 0.5, 440.0, 0.8);
  for (size_t i = 1; i < st.size(); i += 2) st[i] = -st[i];
  std::string why;
  ASSERT_TRUE(write_stereo(path, SF_FORMAT_WAV | SF_FORMAT_FLOAT, st, kSourceRate, &why)) << why;

  const Audio raw = decode_mono(path);
  EXPECT_EQ(raw.sample_rate, kSourceRate);
  ASSERT_EQ(raw.samples.size(), st.size() / 2);
  float peak = 0;
  for (float v : raw.samples) peak = std::max(peak, std::abs(v));
  EXPECT_LT(peak, 1e-6f);
  const Audio a = load_audio(path);
  peak = 0;
  for (float v : a.samples) peak = std::max(peak, std::abs(v));
  EXPECT_LT(peak, 1e-5f);

  // And a mix that is not zero: L = x, R = 0.5 x gives 0.75 x.
  const fs::path path2 = dir / "unequal.wav";
  std::vector<float> st2 = stereo_sine(kSourceRate, 0.1, 440.0, 0.8);
  for (size_t i = 1; i < st2.size(); i += 2) st2[i] *= 0.5f;
  ASSERT_TRUE(write_stereo(path2, SF_FORMAT_WAV | SF_FORMAT_FLOAT, st2, kSourceRate, &why));
  const Audio b = decode_mono(path2);
  ASSERT_EQ(b.samples.size(), st2.size() / 2);
  for (size_t i = 0; i < b.samples.size(); ++i)
    ASSERT_NEAR(b.samples[i], 0.75f * st2[2 * i], 1e-6f) << i;
}

TEST(Decode, SixteenKilohertzInputIsNotResampled) {
  TempDir dir;
  const fs::path path = dir / "mono16k.wav";
  Audio in;
  in.sample_rate = kSampleRate;
  for (int i = 0; i < 1600; ++i) in.samples.push_back(float(i % 100) / 100.0f - 0.5f);
  write_wav(path, in, /*float32=*/true);
  DecodeInfo info;
  const Audio out = load_audio(path, &info);
  EXPECT_EQ(info.source_rate, kSampleRate);
  EXPECT_EQ(info.source_channels, 1);
  EXPECT_EQ(info.source_frames, 1600);
  EXPECT_EQ(out.samples, in.samples);
}

// ---------------------------------------------------------------------------------------------
// Errors: each a glossa::Error naming the file.

TEST(DecodeErrors, MissingFile) {
  TempDir dir;
  const fs::path path = dir / "nope.wav";
  expect_file_error(path, [&] { load_audio(path); });
}

TEST(DecodeErrors, EmptyFile) {
  TempDir dir;
  const fs::path path = dir / "empty.wav";
  write_bytes(path, "");
  expect_file_error(
      path, [&] { load_audio(path); }, "empty");
}

TEST(DecodeErrors, Folder) {
  TempDir dir;
  const fs::path path = dir / "folder.wav";
  fs::create_directories(path);
  expect_file_error(path, [&] { load_audio(path); });
}

TEST(DecodeErrors, GarbageWithWavName) {
  TempDir dir;
  const fs::path path = dir / "garbage.wav";
  std::string junk;
  uint32_t s = 12345;
  for (int i = 0; i < 4096; ++i) {
    s = s * 1664525u + 1013904223u;
    junk += static_cast<char>(s >> 24);
  }
  write_bytes(path, junk);
  expect_file_error(path, [&] { load_audio(path); });
}

TEST(DecodeErrors, WavHeaderOnlyHasNoSamples) {
  TempDir dir;
  const fs::path path = dir / "nodata.wav";
  std::string why;
  ASSERT_TRUE(write_stereo(path, SF_FORMAT_WAV | SF_FORMAT_PCM_16, {}, kSourceRate, &why)) << why;
  ASSERT_GT(fs::file_size(path), 0u);
  expect_file_error(path, [&] { load_audio(path); });
}

TEST(DecodeErrors, WavTruncatedInTheData) {
  TempDir dir;
  const fs::path full = dir / "full.wav";
  std::string why;
  ASSERT_TRUE(write_stereo(full, SF_FORMAT_WAV | SF_FORMAT_PCM_16,
                           stereo_sine(kSourceRate, 1.0, kToneHz, kAmp), kSourceRate, &why))
      << why;
  const std::string bytes = io::read_file(full);
  // 44-byte canonical header + 44100 * 4 bytes of data; keep the header (which still says
  // 44100 frames) and the first 40% of the data.
  ASSERT_EQ(bytes.size(), 44u + 44100u * 4u);
  const fs::path cut = dir / "cut.wav";
  write_bytes(cut, bytes.substr(0, 44 + 17640 * 4));
  try {
    const Audio a = load_audio(cut);
    ADD_FAILURE() << "BUG: src/audio/decode.cpp decode_mono accepts a WAV cut in its data chunk "
                     "(header: 44100 frames, file: 17640): libsndfile clamps SF_INFO.frames to "
                     "what the file holds, so the 'header says more frames' check never fires; "
                     "got "
                  << a.samples.size() << " samples at 16 kHz instead of glossa::Error";
  } catch (const Error& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find(cut.string()), std::string::npos) << what;
    EXPECT_NE(what.find("truncated"), std::string::npos) << what;
  }
}

// ---------------------------------------------------------------------------------------------
// write_wav

TEST(WriteWav, Pcm16RoundTrip) {
  TempDir dir;
  const fs::path path = dir / "out" / "speech.wav";
  Audio in;
  in.sample_rate = kSampleRate;
  for (int i = 0; i < 8000; ++i)
    in.samples.push_back(static_cast<float>(0.7 * std::sin(2.0 * M_PI * 300.0 * i / kSampleRate)));
  in.samples.push_back(1.5f);  // clipped to full scale, not wrapped
  in.samples.push_back(-1.5f);
  write_wav(path, in);
  DecodeInfo info;
  const Audio out = decode_mono(path, &info);
  EXPECT_EQ(out.sample_rate, kSampleRate);
  EXPECT_EQ(info.source_channels, 1);
  ASSERT_EQ(out.samples.size(), in.samples.size());
  for (size_t i = 0; i + 2 < in.samples.size(); ++i)
    ASSERT_NEAR(out.samples[i], in.samples[i], 1.0f / 32768.0f) << i;
  EXPECT_GT(out.samples[in.samples.size() - 2], 0.999f);
  EXPECT_LT(out.samples[in.samples.size() - 1], -0.999f);
}

TEST(WriteWav, Float32RoundTripIsExactAndAtomic) {
  TempDir dir;
  const fs::path path = dir / "f.wav";
  Audio first;
  first.sample_rate = 22050;
  first.samples = {0.1f, -0.2f, 0.3f};
  write_wav(path, first, true);
  Audio second;
  second.sample_rate = 8000;
  for (int i = 0; i < 1000; ++i) second.samples.push_back(float(i) * 1e-3f - 0.5f);
  write_wav(path, second, true);  // replaces the first file whole
  DecodeInfo info;
  const Audio out = decode_mono(path, &info);
  EXPECT_EQ(out.sample_rate, 8000);
  EXPECT_EQ(out.samples, second.samples);
  size_t entries = 0;
  for ([[maybe_unused]] const auto& e : fs::directory_iterator(dir.path())) ++entries;
  EXPECT_EQ(entries, 1u) << "a temporary file was left behind";
}

TEST(WriteWav, NoSampleRateIsAnError) {
  TempDir dir;
  const fs::path path = dir / "bad.wav";
  Audio a;
  a.sample_rate = 0;
  a.samples = {0.f};
  expect_file_error(path, [&] { write_wav(path, a); });
  EXPECT_FALSE(fs::exists(path));
}

// ---------------------------------------------------------------------------------------------
// resample

TEST(Resample, OutputLengthIsRoundedRatio) {
  for (size_t n : {0u, 2u, 3u, 100u, 441u, 44099u, 44100u, 44101u}) {
    const std::vector<float> x(n, 0.25f);
    const auto y = resample(x, 1, 44100, 16000);
    EXPECT_EQ(y.size(), static_cast<size_t>(std::llround(double(n) * 16000 / 44100))) << n;
  }
  // Interleaved stereo: frames, not samples, follow the formula.
  const std::vector<float> st(2 * 4800, 0.f);
  EXPECT_EQ(resample(st, 2, 48000, 16000).size(), 2u * 1600u);
}

TEST(Resample, InputTooShortForOneOutputFrame) {
  const std::vector<float> x(1, 0.25f);
  EXPECT_TRUE(resample(x, 1, 44100, 16000).empty());
  const std::vector<float> st(2, 0.25f);
  EXPECT_TRUE(resample(st, 2, 48000, 16000).empty());
}

TEST(Resample, SameRateIsIdentity) {
  const std::vector<float> x = {0.1f, -0.4f, 0.9f};
  EXPECT_EQ(resample(x, 1, 16000, 16000), x);
}

TEST(Resample, KeepsPassbandAndRemovesAboveNyquist) {
  const int in_rate = 48000;
  std::vector<float> low(in_rate), high(in_rate);
  for (int i = 0; i < in_rate; ++i) {
    low[i] = static_cast<float>(0.5 * std::sin(2.0 * M_PI * 1000.0 * i / in_rate));
    high[i] = static_cast<float>(0.5 * std::sin(2.0 * M_PI * 11000.0 * i / in_rate));
  }
  const auto a = resample(low, 1, in_rate, kSampleRate);
  const auto b = resample(high, 1, in_rate, kSampleRate);
  ASSERT_EQ(a.size(), size_t(kSampleRate));
  const size_t begin = 4000, end = 12000;
  EXPECT_NEAR(tone_amplitude(a, begin, end, 1000.0, kSampleRate), 0.5, 0.005);
  // 11 kHz is above the 8 kHz Nyquist of 16 kHz: it must not alias to 5 kHz.
  EXPECT_LT(rms(b, begin, end), 0.005);
  EXPECT_LT(tone_amplitude(b, begin, end, 5000.0, kSampleRate), 0.005);
}

TEST(Resample, AudioOverloadSetsTheRate) {
  Audio in;
  in.sample_rate = 8000;
  in.samples.assign(800, 0.f);
  const Audio out = resample(in, 16000);
  EXPECT_EQ(out.sample_rate, 16000);
  EXPECT_EQ(out.samples.size(), 1600u);
}

TEST(Resample, BadArgumentsThrow) {
  const std::vector<float> x(10, 0.f);
  EXPECT_THROW(resample(x, 0, 16000, 8000), Error);
  EXPECT_THROW(resample(x, 1, 0, 8000), Error);
  EXPECT_THROW(resample(x, 1, 16000, -1), Error);
}

}  // namespace
}  // namespace glossa::audio
