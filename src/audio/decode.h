#pragma once
// Decoding of WAV, FLAC, OGG/Vorbis, MP3 and the other formats libsndfile reads, at any rate and
// channel count, into glossa's internal 16 kHz mono Audio.
#include <filesystem>

#include "audio/audio.h"

namespace glossa::audio {

struct DecodeInfo {
  int source_rate = 0;
  int source_channels = 0;
  long long source_frames = 0;
};

// Decodes, mixes to mono (channel mean) and resamples to 16 kHz. Throws glossa::Error naming
// the file when it is missing, unreadable, empty or truncated.
Audio load_audio(const std::filesystem::path& path, DecodeInfo* info = nullptr);

// Decodes without resampling (mono mix only).
Audio decode_mono(const std::filesystem::path& path, DecodeInfo* info = nullptr);

// Writes 16-bit PCM WAV (or float WAV when `float32`), atomically.
void write_wav(const std::filesystem::path& path, const Audio& audio, bool float32 = false);

}  // namespace glossa::audio
