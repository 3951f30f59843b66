#include "ema/readers/ag501_pos.h"

#include <algorithm>
#include <bit>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <set>

#include <fmt/format.h>

#include "core/error.h"
#include "io/atomic_file.h"

namespace glossa::ema {
namespace fs = std::filesystem;
namespace {

constexpr std::string_view kMagicPrefix = "AG50xDATA_V00";

std::string_view trim(std::string_view s) {
  const auto first = s.find_first_not_of(" \t\r\n");
  if (first == std::string_view::npos) return {};
  const auto last = s.find_last_not_of(" \t\r\n");
  return s.substr(first, last - first + 1);
}

// Takes the next '\n'-terminated line off `rest` (without the '\n' or a trailing '\r').
bool next_line(std::string_view& rest, std::string_view& line) {
  if (rest.empty()) return false;
  const auto end = rest.find('\n');
  line = rest.substr(0, end);
  rest = end == std::string_view::npos ? std::string_view{} : rest.substr(end + 1);
  if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
  return true;
}

bool parse_int(std::string_view s, long long& out) {
  const auto [ptr, ec] = std::from_chars(s.data(), s.data() + s.size(), out);
  return !s.empty() && ec == std::errc() && ptr == s.data() + s.size();
}

bool parse_double(std::string_view s, double& out) {
  const auto [ptr, ec] = std::from_chars(s.data(), s.data() + s.size(), out);
  return !s.empty() && ec == std::errc() && ptr == s.data() + s.size() && std::isfinite(out);
}

// Binary junk must not end up in an error message.
std::string printable(std::string_view s, size_t max_chars = 24) {
  std::string out;
  for (const char c : s.substr(0, max_chars)) out += (c >= 32 && c < 127) ? c : '?';
  if (s.size() > max_chars) out += "...";
  return out;
}

float little_endian_f32(const char* p) {
  uint32_t u;
  std::memcpy(&u, p, 4);
  if constexpr (std::endian::native == std::endian::big) u = __builtin_bswap32(u);
  return std::bit_cast<float>(u);
}

PosFile decode_samples(const fs::path& path, std::string_view bytes, int channels, double rate) {
  const size_t sample_bytes = static_cast<size_t>(channels) * kPosValuesPerChannel * 4;
  if (bytes.empty()) throw file_error(path, "no samples after the header");
  if (bytes.size() % sample_bytes != 0) {
    throw file_error(path, fmt::format("truncated: {} bytes of samples is not a whole number of "
                                       "{}-byte samples ({} channels x 7 float32); the last "
                                       "sample is partial",
                                       bytes.size(), sample_bytes, channels));
  }
  PosFile pos;
  pos.rate = rate;
  pos.channels = channels;
  pos.values_per_channel = kPosValuesPerChannel;
  const auto rows = static_cast<Eigen::Index>(bytes.size() / sample_bytes);
  pos.data.resize(rows, static_cast<Eigen::Index>(channels) * kPosValuesPerChannel);
  float* out = pos.data.data();
  for (size_t i = 0; i < bytes.size() / 4; ++i) out[i] = little_endian_f32(bytes.data() + 4 * i);
  return pos;
}

std::string folder_name(const fs::path& dir) {
  fs::path p = fs::absolute(dir).lexically_normal();
  if (p.filename().empty()) p = p.parent_path();
  return p.filename().string();
}

std::vector<std::string> stems_with_extension(const fs::path& dir, std::string_view ext) {
  std::vector<std::string> stems;
  std::error_code ec;
  if (!fs::is_directory(dir, ec)) return stems;
  for (const auto& entry : fs::directory_iterator(dir)) {
    if (entry.is_regular_file() && entry.path().extension() == ext) {
      stems.push_back(entry.path().stem().string());
    }
  }
  std::sort(stems.begin(), stems.end());
  return stems;
}

class Ag501Source final : public CorpusSource {
 public:
  Ag501Source(const fs::path& dir, Ag501Options opt) : dir_(dir), opt_(std::move(opt)) {
    if (!fs::is_directory(dir_)) {
      throw file_error(dir_, fs::exists(dir_) ? "not a folder" : "no such folder");
    }
    check_channel_map();
    if (opt_.speaker.empty()) opt_.speaker = folder_name(dir_);
    for (const fs::path& candidate : {dir_, dir_ / "pos"}) {
      ids_ = stems_with_extension(candidate, ".pos");
      if (!ids_.empty()) {
        pos_dir_ = candidate;
        break;
      }
    }
    if (ids_.empty()) throw file_error(dir_, "no <id>.pos files in this folder or in pos/");
  }

  std::string format() const override { return "ag501"; }
  std::vector<std::string> ids() const override { return ids_; }

  RawUtterance load(const std::string& id) const override {
    const fs::path pos_path = pos_dir_ / (id + ".pos");
    if (!std::binary_search(ids_.begin(), ids_.end(), id)) {
      throw file_error(pos_path, fmt::format("no utterance '{}' in this corpus", id));
    }
    const PosFile pos = opt_.headerless_ag500 ? read_ag500_pos(pos_path) : read_ag501_pos(pos_path);

    RawUtterance utt;
    utt.id = id;
    utt.speaker = opt_.speaker;
    utt.text = id;
    utt.audio_path = find_audio(id, pos_path);
    utt.ema.rate = pos.rate;
    const auto sensors = static_cast<Eigen::Index>(opt_.channels.size());
    utt.ema.positions.resize(pos.data.rows(), 3 * sensors);
    for (Eigen::Index s = 0; s < sensors; ++s) {
      const Ag501Channel& ch = opt_.channels[static_cast<size_t>(s)];
      if (ch.channel > pos.channels) {
        throw file_error(pos_path, fmt::format("channel {} ({}) is not in the file, which has {} "
                                               "channels",
                                               ch.channel, ch.sensor, pos.channels));
      }
      const Eigen::Index col = static_cast<Eigen::Index>(ch.channel - 1) * kPosValuesPerChannel;
      utt.ema.positions.middleCols(3 * s, 3) = pos.data.middleCols(col, 3);
      utt.ema.set.names.push_back(ch.sensor);
    }
    return utt;
  }

  nlohmann::json describe() const override {
    nlohmann::json map = nlohmann::json::object();
    for (const auto& ch : opt_.channels) map[std::to_string(ch.channel)] = ch.sensor;
    return {{"format", format()},
            {"folder", dir_.string()},
            {"speaker", opt_.speaker},
            {"file_format", opt_.headerless_ag500 ? "AG500 .pos (headerless, 12 channels, 200 Hz)"
                                                  : "AG501 .pos (AG50xDATA_V003/V002)"},
            {"axes",
             "device axes as recorded (x, y, z in mm); head frame after stabilisation "
             "on the REF sensors"},
            {"channel_map", map}};
  }

 private:
  void check_channel_map() const {
    if (opt_.channels.empty()) {
      throw Error(
          "AG501 source: no channel map; name the sensor on each channel, e.g. "
          "1=REF-UI,2=TT,3=TB");
    }
    std::set<int> channels;
    std::set<std::string> names;
    for (const auto& ch : opt_.channels) {
      if (ch.channel < 1) {
        throw Error(fmt::format("AG501 channel map: channel {} is invalid (channels count from 1)",
                                ch.channel));
      }
      if (ch.sensor.empty()) {
        throw Error(fmt::format("AG501 channel map: channel {} has no sensor name", ch.channel));
      }
      if (!channels.insert(ch.channel).second) {
        throw Error(fmt::format("AG501 channel map: channel {} is given twice", ch.channel));
      }
      if (!names.insert(ch.sensor).second) {
        throw Error(fmt::format("AG501 channel map: sensor {} is given twice", ch.sensor));
      }
    }
  }

  fs::path find_audio(const std::string& id, const fs::path& pos_path) const {
    const fs::path beside = pos_dir_ / (id + ".wav");
    const fs::path in_wav = dir_ / "wav" / (id + ".wav");
    for (const fs::path& p : {beside, in_wav}) {
      if (fs::is_regular_file(p)) return p;
    }
    throw file_error(pos_path, fmt::format("no audio for utterance '{}' (looked for {} and {})", id,
                                           beside.string(), in_wav.string()));
  }

  fs::path dir_;
  fs::path pos_dir_;
  Ag501Options opt_;
  std::vector<std::string> ids_;
};

}  // namespace

PosFile read_ag501_pos(const fs::path& path) {
  const std::string bytes = io::read_file(path);
  std::string_view rest(bytes);
  if (bytes.empty()) throw file_error(path, "empty file, not an AG501 position file");
  std::string_view magic;
  next_line(rest, magic);
  if (!magic.starts_with(kMagicPrefix)) {
    throw file_error(path, fmt::format("not an AG501 position file: it starts with '{}', not "
                                       "the header 'AG50xDATA_V003'",
                                       printable(magic)));
  }
  if (magic != "AG50xDATA_V003" && magic != "AG50xDATA_V002") {
    throw file_error(path, fmt::format("unsupported AG501 file version '{}' (V002 and V003 are "
                                       "read)",
                                       printable(magic)));
  }

  std::string_view size_line;
  long long header_size = 0;
  if (!next_line(rest, size_line) || !parse_int(trim(size_line), header_size)) {
    throw file_error(path, fmt::format("malformed header: the second line should give the header "
                                       "size in bytes, found '{}'",
                                       printable(size_line)));
  }
  const auto consumed = static_cast<long long>(bytes.size() - rest.size());
  if (header_size < consumed || header_size > static_cast<long long>(bytes.size())) {
    throw file_error(path, fmt::format("malformed header: header size {} does not fit a file of {} "
                                       "bytes",
                                       header_size, bytes.size()));
  }

  std::string_view fields = std::string_view(bytes).substr(
      static_cast<size_t>(consumed), static_cast<size_t>(header_size - consumed));
  fields = fields.substr(0, fields.find_first_of(std::string_view("\0\x1a", 2)));
  long long channels = -1;
  double rate = -1.0;
  std::string_view line;
  while (next_line(fields, line)) {
    if (trim(line).empty()) continue;
    const auto eq = line.find('=');
    if (eq == std::string_view::npos) {
      throw file_error(
          path, fmt::format("malformed header: line '{}' is not key=value", printable(line, 60)));
    }
    const std::string_view key = trim(line.substr(0, eq));
    const std::string_view value = trim(line.substr(eq + 1));
    if (key == "NumberOfChannels" && !parse_int(value, channels)) {
      throw file_error(path, fmt::format("malformed header: NumberOfChannels='{}' is not a whole "
                                         "number",
                                         printable(value)));
    }
    if (key == "SamplingFrequencyHz" && (!parse_double(value, rate) || rate <= 0)) {
      throw file_error(path, fmt::format("malformed header: SamplingFrequencyHz='{}' is not a "
                                         "positive number",
                                         printable(value)));
    }
  }
  if (channels < 0) throw file_error(path, "malformed header: no NumberOfChannels");
  if (rate < 0) throw file_error(path, "malformed header: no SamplingFrequencyHz");
  if (channels == 0) throw file_error(path, "the header declares zero channels");
  if (channels > 4096) {
    throw file_error(path, fmt::format("implausible NumberOfChannels={}", channels));
  }
  return decode_samples(path, std::string_view(bytes).substr(static_cast<size_t>(header_size)),
                        static_cast<int>(channels), rate);
}

PosFile read_ag500_pos(const fs::path& path, int channels, double rate) {
  if (channels <= 0 || !(rate > 0) || !std::isfinite(rate)) {
    throw file_error(path, fmt::format("AG500 reader needs a positive channel count and rate "
                                       "(got {} channels at {} Hz)",
                                       channels, rate));
  }
  const std::string bytes = io::read_file(path);
  return decode_samples(path, bytes, channels, rate);
}

std::vector<Ag501Channel> parse_channel_map(std::string_view text) {
  const auto fail = [&](const std::string& why) {
    return Error(fmt::format("channel map '{}': {}", text, why));
  };
  std::vector<Ag501Channel> out;
  std::set<int> channels;
  std::set<std::string> names;
  if (trim(text).empty()) throw fail("empty; expected CHANNEL=SENSOR items such as 1=TT,2=TB");
  size_t start = 0;
  while (start <= text.size()) {
    const size_t comma = std::min(text.find(',', start), text.size());
    const std::string_view item = trim(text.substr(start, comma - start));
    start = comma + 1;
    const auto eq = item.find('=');
    if (item.empty() || eq == std::string_view::npos) {
      throw fail(fmt::format("item '{}' is not CHANNEL=SENSOR", item));
    }
    const std::string_view number = trim(item.substr(0, eq));
    const std::string sensor(trim(item.substr(eq + 1)));
    long long channel = 0;
    if (!parse_int(number, channel) || channel < 1 || channel > std::numeric_limits<int>::max()) {
      throw fail(fmt::format("'{}' is not a channel number (channels count from 1)", number));
    }
    if (sensor.empty() || sensor.find_first_of(" \t=") != std::string::npos) {
      throw fail(fmt::format("item '{}' needs a sensor name without spaces", item));
    }
    if (!channels.insert(static_cast<int>(channel)).second) {
      throw fail(fmt::format("channel {} is given twice", channel));
    }
    if (!names.insert(sensor).second) throw fail(fmt::format("sensor {} is given twice", sensor));
    out.push_back({static_cast<int>(channel), sensor});
  }
  return out;
}

std::unique_ptr<CorpusSource> open_ag501_source(const fs::path& dir, const Ag501Options& opt) {
  return std::make_unique<Ag501Source>(dir, opt);
}

}  // namespace glossa::ema
