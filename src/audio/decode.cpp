#include "audio/decode.h"

#include <sndfile.h>

#include <cmath>
#include <memory>

#include "audio/resample.h"
#include "core/error.h"
#include "io/atomic_file.h"

namespace glossa::audio {
namespace fs = std::filesystem;

namespace {

struct SndCloser {
  void operator()(SNDFILE* f) const { sf_close(f); }
};
using SndPtr = std::unique_ptr<SNDFILE, SndCloser>;

}  // namespace

Audio decode_mono(const fs::path& path, DecodeInfo* info) {
  if (!fs::exists(path)) throw file_error(path, "no such file");
  if (fs::is_directory(path)) throw file_error(path, "is a folder, not an audio file");
  if (fs::file_size(path) == 0) throw file_error(path, "empty file");
  SF_INFO sfinfo{};
  SndPtr file(sf_open(path.c_str(), SFM_READ, &sfinfo));
  if (!file)
    throw file_error(path, std::string("cannot decode audio: ") + sf_strerror(nullptr) +
                               " (supported: WAV, FLAC, OGG/Vorbis, MP3, AIFF and the other "
                               "formats of libsndfile)");
  if (sfinfo.channels <= 0 || sfinfo.samplerate <= 0)
    throw file_error(path, "audio has no channels or no sample rate");
  if (info) *info = {sfinfo.samplerate, sfinfo.channels, static_cast<long long>(sfinfo.frames)};
  sf_command(file.get(), SFC_SET_NORM_FLOAT, nullptr, SF_TRUE);
  // libsndfile clamps the frame count to what the file holds; its log still says when the
  // header promised more ("data : 176400 (should be 70546)"), which means a truncated file.
  {
    char log[4096] = {};
    sf_command(file.get(), SFC_GET_LOG_INFO, log, sizeof log);
    const std::string text(log);
    const auto at = text.find("data : ");
    if (at != std::string::npos) {
      const auto eol = text.find('\n', at);
      if (text.substr(at, eol - at).find("should be") != std::string::npos)
        throw file_error(path, "truncated audio: the header promises more data than the file "
                               "holds (" + text.substr(at, eol - at) + ")");
    }
  }

  const int ch = sfinfo.channels;
  std::vector<float> block(4096 * static_cast<size_t>(ch));
  Audio out;
  out.sample_rate = sfinfo.samplerate;
  if (sfinfo.frames > 0 && sfinfo.frames < (1LL << 34)) out.samples.reserve(sfinfo.frames);
  while (true) {
    const sf_count_t got = sf_readf_float(file.get(), block.data(), 4096);
    if (got <= 0) break;
    for (sf_count_t i = 0; i < got; ++i) {
      float sum = 0.f;
      for (int c = 0; c < ch; ++c) sum += block[static_cast<size_t>(i * ch + c)];
      out.samples.push_back(sum / static_cast<float>(ch));
    }
  }
  if (sf_error(file.get()) != SF_ERR_NO_ERROR)
    throw file_error(path, std::string("decoding failed: ") + sf_strerror(file.get()));
  if (out.samples.empty()) throw file_error(path, "audio contains no samples");
  // A header that promises more frames than the data holds means a truncated file.
  if (sfinfo.frames > 0 && sfinfo.frames != SF_COUNT_MAX &&
      static_cast<long long>(out.samples.size()) < sfinfo.frames)
    throw file_error(path, fmt::format("truncated audio: header says {} frames, only {} decoded",
                                       sfinfo.frames, out.samples.size()));
  for (float& s : out.samples) {
    if (!std::isfinite(s)) throw file_error(path, "audio contains NaN or infinite samples");
  }
  if (info) info->source_frames = static_cast<long long>(out.samples.size());
  return out;
}

Audio load_audio(const fs::path& path, DecodeInfo* info) {
  Audio mono = decode_mono(path, info);
  if (mono.sample_rate == kSampleRate) return mono;
  return resample(mono, kSampleRate);
}

void write_wav(const fs::path& path, const Audio& audio, bool float32) {
  if (audio.sample_rate <= 0) throw file_error(path, "cannot write audio with no sample rate");
  io::write_via_temp(path, [&](const fs::path& tmp) {
    SF_INFO info{};
    info.samplerate = audio.sample_rate;
    info.channels = 1;
    info.format = SF_FORMAT_WAV | (float32 ? SF_FORMAT_FLOAT : SF_FORMAT_PCM_16);
    SndPtr file(sf_open(tmp.c_str(), SFM_WRITE, &info));
    if (!file) throw file_error(path, std::string("cannot write WAV: ") + sf_strerror(nullptr));
    if (!float32) sf_command(file.get(), SFC_SET_CLIPPING, nullptr, SF_TRUE);
    const sf_count_t n = static_cast<sf_count_t>(audio.samples.size());
    if (sf_writef_float(file.get(), audio.samples.data(), n) != n)
      throw file_error(path, std::string("write failed: ") + sf_strerror(file.get()));
  });
}

}  // namespace glossa::audio
