#pragma once
// Carstens AG501 position files (`.pos`) and a corpus source over a folder of them.
//
// Layout of an AG501 `.pos` file (header "AG50xDATA_V003"; V002 has the same layout):
//   line 1   the magic text "AG50xDATA_V003"
//   line 2   the total header size in bytes, as decimal digits (e.g. "00000070"); the
//            samples start at this byte offset from the start of the file
//   then     key=value lines, among them NumberOfChannels=N and SamplingFrequencyHz=F,
//            followed by padding (a NUL and 0x1A) up to the header size
//   samples  little-endian float32, sample by sample; in each sample channel by channel
//            (channel 1 first); for each channel 7 values: x, y, z (mm), phi, theta (degrees),
//            rms (fit residual), extra (unused). Invalid samples hold NaN.
// The AG500 wrote the same 7-value samples without any header (see read_ag500_pos).
#include <filesystem>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "core/matrix.h"
#include "ema/source.h"

namespace glossa::ema {

inline constexpr int kPosValuesPerChannel = 7;  // x y z phi theta rms extra

struct PosFile {
  double rate = 0.0;  // samples per second
  int channels = 0;
  int values_per_channel = kPosValuesPerChannel;
  MatrixRM data;  // samples x (channels * values_per_channel), channel c (0-based) at c * 7
};

// Reads an AG501 `.pos` file (V003 or V002 header). Throws glossa::Error naming the file on a
// bad magic, a malformed header, zero channels, no samples or a partial last sample.
PosFile read_ag501_pos(const std::filesystem::path& path);

// Reads a headerless AG500 `.pos` file: the same 7-value float32 samples, with the channel count
// and rate given by the caller (the AG500 recorded 12 channels at 200 Hz).
PosFile read_ag500_pos(const std::filesystem::path& path, int channels = 12, double rate = 200.0);

struct Ag501Channel {
  int channel = 0;     // 1-based, as the AG501 numbers its channels
  std::string sensor;  // e.g. "TT"; REF-UI, REF-LM, REF-RM name head-reference sensors
};

// Parses "1=TD,2=TB,3=REF-UI" (spaces around items allowed). Throws glossa::Error quoting the
// text on a malformed item, a channel below 1, or a repeated channel or sensor.
std::vector<Ag501Channel> parse_channel_map(std::string_view text);

struct Ag501Options {
  std::vector<Ag501Channel> channels;  // which channels to keep, in landmark order
  std::string speaker;                 // empty: the folder's name
  bool headerless_ag500 = false;       // read AG500 files without header (12 channels, 200 Hz)
};

// A folder of `<id>.pos` files (in `dir` or `dir/pos`) with `<id>.wav` beside each or in
// `dir/wav`. Positions keep the device's own axes and mm; reference sensors stay in the
// sequence (the importer stabilises on them and drops them).
std::unique_ptr<CorpusSource> open_ag501_source(const std::filesystem::path& dir,
                                                const Ag501Options& opt);

}  // namespace glossa::ema
