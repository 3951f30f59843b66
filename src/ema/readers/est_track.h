#pragma once
// Edinburgh Speech Tools track files (`EST_File Track`), the format of the `.ema` files of
// MOCHA-TIMIT and mngu0, and a corpus source over a folder of them.
//
// Layout, as speech_tools' EST_TrackFile.cc writes and reads it:
//   EST_File Track
//   DataType binary            ("ascii" or "binary"; missing means ascii)
//   ByteOrder 01               ("01" little-endian, "10" big-endian; binary only)
//   NumFrames 1234
//   NumChannels 20
//   EqualSpace 1
//   BreaksPresent true         (present: every frame carries a break/valid flag)
//   CommentChar ;
//   Channel_0 ui_x             (one line per channel, 0-based)
//   EST_Header_End
// then per frame: the time (s), the flag if BreaksPresent (0 = break, no value), then the
// NumChannels values; binary: float32 in ByteOrder, right after the newline that ends
// EST_Header_End; ascii: whitespace-separated numbers.
#include <array>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "core/matrix.h"
#include "ema/source.h"

namespace glossa::ema {

struct EstTrack {
  std::vector<float> times;  // seconds, one per frame
  std::vector<float> valid;  // 1 = value, 0 = break; all 1 when the file has no breaks
  std::vector<std::string> channel_names;
  MatrixRM values;  // frames x channels

  // Frames per second from the frame times; 0 when it cannot be told (fewer than 2 frames).
  double rate() const;
};

// Throws glossa::Error naming the file on a bad magic, missing header keys, truncated binary
// data or a wrong number of values in ascii data.
EstTrack read_est_track(const std::filesystem::path& path);

// One track channel feeding one coordinate of a glossa sensor.
struct EstChannel {
  std::string channel;    // track channel name, e.g. "tt_x"
  std::string sensor;     // glossa sensor name, e.g. "TT"
  int axis = 0;           // head-frame axis: 0 x back->front, 1 y right->left, 2 z bottom->top
  bool optional = false;  // absent from a file: the sensor is NaN there instead of an error
};

struct EstOptions {
  std::vector<EstChannel> channels;         // sensors in order of first appearance
  float scale_to_mm = 1.0f;                 // file unit -> mm
  std::array<float, 3> axis_sign{1, 1, 1};  // applied per head-frame axis after scaling
  std::string speaker;                      // empty: the folder's name

  // MOCHA-TIMIT: 2D midsagittal coils in 1/100 mm, x growing towards the back, y upwards.
  static EstOptions mocha();
  // mngu0 (day 1, AG500): 3D sensors T1 T2 T3 jaw upperlip lowerlip, mm.
  static EstOptions mngu0();
};

// A folder of `<id>.ema` (in `dir`, `dir/ema` or `dir/ema_basic_data`) with `<id>.wav` beside
// each or in `dir/wav` (or `dir/wav_16kHz`). Sensor coordinates a corpus lacks (y for the 2D
// MOCHA coils) are 0; frames flagged as breaks are NaN.
std::unique_ptr<CorpusSource> open_est_source(const std::filesystem::path& dir,
                                              const EstOptions& opt);

}  // namespace glossa::ema
