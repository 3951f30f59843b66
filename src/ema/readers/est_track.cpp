#include "ema/readers/est_track.h"

#include <algorithm>
#include <bit>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <map>
#include <set>
#include <string_view>
#include <unordered_map>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "core/error.h"
#include "io/atomic_file.h"

namespace glossa::ema {
namespace fs = std::filesystem;
namespace {

constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();

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

bool parse_float(std::string_view s, float& out) {
  const auto [ptr, ec] = std::from_chars(s.data(), s.data() + s.size(), out);
  return !s.empty() && ec == std::errc() && ptr == s.data() + s.size();
}

std::string printable(std::string_view s, size_t max_chars = 24) {
  std::string out;
  for (const char c : s.substr(0, max_chars)) out += (c >= 32 && c < 127) ? c : '?';
  if (s.size() > max_chars) out += "...";
  return out;
}

float read_f32(const char* p, bool big_endian) {
  uint32_t u;
  std::memcpy(&u, p, 4);
  if ((std::endian::native == std::endian::big) != big_endian) u = __builtin_bswap32(u);
  return std::bit_cast<float>(u);
}

struct Header {
  std::map<std::string, std::string, std::less<>> keys;
  std::vector<std::string> channel_names;
  long long frames = 0;
  long long channels = 0;
  long long aux_channels = 0;
  bool binary = false;
  bool big_endian = false;
  bool breaks = false;
  std::string comment;
};

long long header_count(const fs::path& path, const Header& h, std::string_view key, bool required) {
  const auto it = h.keys.find(key);
  if (it == h.keys.end()) {
    if (required) throw file_error(path, fmt::format("EST header has no {}", key));
    return 0;
  }
  long long n = 0;
  if (!parse_int(it->second, n) || n < 0 || n > 1'000'000'000) {
    throw file_error(path, fmt::format("EST header: {} '{}' is not a plausible count", key,
                                       printable(it->second)));
  }
  return n;
}

// Parses the header; leaves `rest` at the first byte after the EST_Header_End line.
Header read_header(const fs::path& path, std::string_view& rest) {
  std::string_view line;
  if (rest.empty()) throw file_error(path, "empty file, not an EST track");
  if (!rest.starts_with("EST_File") || !next_line(rest, line)) {
    throw file_error(path, fmt::format("not an EST file: it starts with '{}', not 'EST_File'",
                                       printable(rest.substr(0, rest.find('\n')))));
  }
  const std::string_view type = trim(line.substr(8));
  if (type != "Track" && type != "track") {
    throw file_error(path, fmt::format("an EST '{}' file, not an EST Track", printable(type)));
  }
  Header h;
  std::vector<std::pair<long long, std::string>> names;
  bool ended = false;
  while (next_line(rest, line)) {
    const std::string_view t = trim(line);
    if (t == "EST_Header_End") {
      ended = true;
      break;
    }
    if (t.empty() || (!h.comment.empty() && t.starts_with(h.comment))) continue;
    const auto space = t.find_first_of(" \t");
    const std::string_view key = t.substr(0, space);
    const std::string_view value =
        space == std::string_view::npos ? std::string_view{} : trim(t.substr(space));
    if (key.starts_with("Channel_")) {
      long long index = -1;
      if (!parse_int(key.substr(8), index) || index < 0) {
        throw file_error(path, fmt::format("EST header: bad channel key '{}'", printable(key)));
      }
      names.emplace_back(index, std::string(value));
    } else {
      h.keys[std::string(key)] = std::string(value);
      if (key == "CommentChar") h.comment = std::string(value);
    }
  }
  if (!ended) throw file_error(path, "EST header has no EST_Header_End line");

  h.frames = header_count(path, h, "NumFrames", true);
  h.channels = header_count(path, h, "NumChannels", true);
  h.aux_channels = header_count(path, h, "NumAuxChannels", false);
  if (h.channels > 100'000) {
    throw file_error(path, fmt::format("EST header: implausible NumChannels {}", h.channels));
  }
  // Like speech_tools: the key's presence, whatever its value, means per-frame break flags.
  h.breaks = h.keys.contains("BreaksPresent");

  const auto data_type = h.keys.find("DataType");
  const std::string type_value = data_type == h.keys.end() ? "ascii" : data_type->second;
  if (type_value != "ascii" && type_value != "binary") {
    throw file_error(path, fmt::format("EST header: unknown DataType '{}' (ascii or binary)",
                                       printable(type_value)));
  }
  h.binary = type_value == "binary";
  // speech_tools writes "01" on little-endian machines and "10" on big-endian ones; a missing
  // ByteOrder means the writer's own order, which for all files we know is little-endian.
  const auto order = h.keys.find("ByteOrder");
  if (order != h.keys.end()) {
    if (order->second != "01" && order->second != "10") {
      throw file_error(path, fmt::format("EST header: ByteOrder '{}' is neither 01 nor 10",
                                         printable(order->second)));
    }
    h.big_endian = order->second == "10";
  }
  if (h.binary && h.aux_channels > 0) {
    throw file_error(path, "binary EST tracks with aux channels are not supported");
  }

  h.channel_names.assign(static_cast<size_t>(h.channels), std::string{});
  for (auto& [index, name] : names) {
    if (index >= h.channels) {
      throw file_error(path, fmt::format("EST header names Channel_{} but NumChannels is {}", index,
                                         h.channels));
    }
    h.channel_names[static_cast<size_t>(index)] = std::move(name);
  }
  return h;
}

// Called once the data is known to hold all frames, so a bogus NumFrames allocates nothing.
void allocate(const Header& h, EstTrack& track) {
  track.times.assign(static_cast<size_t>(h.frames), 0.0f);
  track.valid.assign(static_cast<size_t>(h.frames), 1.0f);
  track.values.resize(h.frames, h.channels);
}

void read_binary(const fs::path& path, const Header& h, std::string_view data, EstTrack& track) {
  const uint64_t per_frame = 1 + (h.breaks ? 1 : 0) + static_cast<uint64_t>(h.channels);
  const uint64_t need = static_cast<uint64_t>(h.frames) * per_frame * 4;
  if (data.size() < need) {
    throw file_error(path, fmt::format("truncated: {} frames of {} float32 need {} bytes after the "
                                       "header, the file has {}",
                                       h.frames, per_frame, need, data.size()));
  }
  if (data.size() > need) {
    throw file_error(path, fmt::format("{} unexpected bytes after the {} frames the header "
                                       "declares",
                                       data.size() - need, h.frames));
  }
  allocate(h, track);
  const char* p = data.data();
  const auto next = [&] {
    const float v = read_f32(p, h.big_endian);
    p += 4;
    return v;
  };
  for (long long f = 0; f < h.frames; ++f) {
    track.times[static_cast<size_t>(f)] = next();
    if (h.breaks) track.valid[static_cast<size_t>(f)] = next() != 0.0f ? 1.0f : 0.0f;
    for (long long c = 0; c < h.channels; ++c) track.values(f, c) = next();
  }
}

void read_ascii(const fs::path& path, const Header& h, std::string_view data, EstTrack& track) {
  std::vector<std::string_view> tokens;
  std::string_view line;
  while (next_line(data, line)) {
    const std::string_view t = trim(line);
    if (t.empty() || (!h.comment.empty() && t.starts_with(h.comment))) continue;
    size_t pos = 0;
    while ((pos = t.find_first_not_of(" \t", pos)) != std::string_view::npos) {
      const size_t end = std::min(t.find_first_of(" \t", pos), t.size());
      tokens.push_back(t.substr(pos, end - pos));
      pos = end;
    }
  }
  const uint64_t per_frame =
      1 + (h.breaks ? 1 : 0) + static_cast<uint64_t>(h.channels + h.aux_channels);
  const uint64_t need = static_cast<uint64_t>(h.frames) * per_frame;
  if (tokens.size() != need) {
    throw file_error(path,
                     fmt::format("the header declares {} frames of {} values ({} in all), the "
                                 "data has {} values",
                                 h.frames, per_frame, need, tokens.size()));
  }
  allocate(h, track);
  size_t i = 0;
  const auto next = [&](long long frame) {
    float v = 0;
    if (!parse_float(tokens[i], v)) {
      throw file_error(path,
                       fmt::format("frame {}: '{}' is not a number", frame, printable(tokens[i])));
    }
    ++i;
    return v;
  };
  for (long long f = 0; f < h.frames; ++f) {
    track.times[static_cast<size_t>(f)] = next(f);
    if (h.breaks) track.valid[static_cast<size_t>(f)] = next(f) != 0.0f ? 1.0f : 0.0f;
    for (long long c = 0; c < h.channels; ++c) track.values(f, c) = next(f);
    i += static_cast<size_t>(h.aux_channels);  // aux channels hold strings; not needed here
  }
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

class EstSource final : public CorpusSource {
 public:
  EstSource(const fs::path& dir, EstOptions opt) : dir_(dir), opt_(std::move(opt)) {
    if (!fs::is_directory(dir_)) {
      throw file_error(dir_, fs::exists(dir_) ? "not a folder" : "no such folder");
    }
    check_options();
    if (opt_.speaker.empty()) opt_.speaker = folder_name(dir_);
    for (const fs::path& candidate : {dir_, dir_ / "ema", dir_ / "ema_basic_data"}) {
      ids_ = stems_with_extension(candidate, ".ema");
      if (!ids_.empty()) {
        ema_dir_ = candidate;
        break;
      }
    }
    if (ids_.empty()) throw file_error(dir_, "no <id>.ema files in this folder or in ema/");
  }

  std::string format() const override { return "est"; }
  std::vector<std::string> ids() const override { return ids_; }

  RawUtterance load(const std::string& id) const override {
    const fs::path path = ema_dir_ / (id + ".ema");
    if (!std::binary_search(ids_.begin(), ids_.end(), id)) {
      throw file_error(path, fmt::format("no utterance '{}' in this corpus", id));
    }
    const EstTrack track = read_est_track(path);
    if (track.times.empty()) throw file_error(path, "the track has no frames");
    const double rate = track.rate();
    if (!(rate > 0) || !std::isfinite(rate)) {
      throw file_error(path,
                       "cannot tell the frame rate: needs 2 or more frames with rising times");
    }

    RawUtterance utt;
    utt.id = id;
    utt.speaker = opt_.speaker;
    utt.text = id;
    utt.audio_path = find_audio(id, path);
    utt.ema.set.names = sensors_;
    utt.ema.rate = rate;
    utt.ema.positions = to_positions(path, track);
    return utt;
  }

  nlohmann::json describe() const override {
    nlohmann::json map = nlohmann::json::object();
    for (const auto& ch : opt_.channels) {
      map[ch.channel] = fmt::format("{}.{}", ch.sensor, "xyz"[ch.axis]);
    }
    return {{"format", format()},
            {"folder", dir_.string()},
            {"speaker", opt_.speaker},
            {"file_format", "Edinburgh Speech Tools track (.ema)"},
            {"scale_to_mm", opt_.scale_to_mm},
            {"axis_sign", opt_.axis_sign},
            {"axes",
             "head frame: x back->front, y right->left (0 for 2D midsagittal data), "
             "z bottom->top; origin as in the corpus"},
            {"channel_map", map}};
  }

 private:
  void check_options() {
    if (opt_.channels.empty()) throw Error("EST source: no channel mapping given");
    if (!std::isfinite(opt_.scale_to_mm) || opt_.scale_to_mm == 0) {
      throw Error(fmt::format("EST source: scale_to_mm {} is not usable", opt_.scale_to_mm));
    }
    std::set<std::pair<std::string, int>> seen;
    for (const auto& ch : opt_.channels) {
      if (ch.channel.empty() || ch.sensor.empty()) {
        throw Error("EST source: a mapping entry has an empty channel or sensor name");
      }
      if (ch.axis < 0 || ch.axis > 2) {
        throw Error(
            fmt::format("EST source: channel {} maps to axis {} (0, 1 or 2)", ch.channel, ch.axis));
      }
      if (!seen.emplace(ch.sensor, ch.axis).second) {
        throw Error(fmt::format("EST source: {}.{} is mapped twice", ch.sensor, "xyz"[ch.axis]));
      }
      if (std::find(sensors_.begin(), sensors_.end(), ch.sensor) == sensors_.end()) {
        sensors_.push_back(ch.sensor);
      }
    }
  }

  MatrixRM to_positions(const fs::path& path, const EstTrack& track) const {
    std::unordered_map<std::string, Eigen::Index> index;
    for (size_t c = 0; c < track.channel_names.size(); ++c) {
      index.emplace(track.channel_names[c], static_cast<Eigen::Index>(c));
    }
    const auto frames = static_cast<Eigen::Index>(track.times.size());
    MatrixRM pos = MatrixRM::Zero(frames, 3 * static_cast<Eigen::Index>(sensors_.size()));
    for (size_t s = 0; s < sensors_.size(); ++s) {
      const auto col0 = 3 * static_cast<Eigen::Index>(s);
      for (const auto& ch : opt_.channels) {
        if (ch.sensor != sensors_[s]) continue;
        const auto it = index.find(ch.channel);
        if (it == index.end() && !ch.optional) {
          throw file_error(
              path, fmt::format("no channel '{}' (for {}); the file has: {}", ch.channel, ch.sensor,
                                fmt::join(track.channel_names, " ")));
        }
        if (it == index.end()) {
          pos.middleCols(col0, 3).setConstant(kNaN);
          break;
        }
        const float k = opt_.scale_to_mm * opt_.axis_sign[static_cast<size_t>(ch.axis)];
        pos.col(col0 + ch.axis) = track.values.col(it->second) * k;
      }
      // A sensor with any coordinate missing is missing as a whole.
      for (Eigen::Index f = 0; f < frames; ++f) {
        if (pos.row(f).segment(col0, 3).array().isNaN().any()) {
          pos.row(f).segment(col0, 3).setConstant(kNaN);
        }
      }
    }
    for (Eigen::Index f = 0; f < frames; ++f) {
      if (track.valid[static_cast<size_t>(f)] == 0.0f) pos.row(f).setConstant(kNaN);
    }
    return pos;
  }

  fs::path find_audio(const std::string& id, const fs::path& ema_path) const {
    const std::vector<fs::path> candidates = {
        ema_dir_ / (id + ".wav"), dir_ / "wav" / (id + ".wav"), dir_ / "wav_16kHz" / (id + ".wav")};
    for (const fs::path& p : candidates) {
      if (fs::is_regular_file(p)) return p;
    }
    throw file_error(ema_path, fmt::format("no audio for utterance '{}' (looked for {} and {})", id,
                                           candidates[0].string(), candidates[1].string()));
  }

  fs::path dir_;
  fs::path ema_dir_;
  EstOptions opt_;
  std::vector<std::string> sensors_;
  std::vector<std::string> ids_;
};

}  // namespace

double EstTrack::rate() const {
  if (times.size() < 2) return 0.0;
  const double span = static_cast<double>(times.back()) - times.front();
  if (!(span > 0)) return 0.0;
  const double rate = static_cast<double>(times.size() - 1) / span;
  // float32 time stamps turn 500 Hz into 499.9999...; keep the whole rate they stand for.
  const double whole = std::round(rate);
  return std::abs(rate - whole) < 1e-5 * whole ? whole : rate;
}

EstTrack read_est_track(const fs::path& path) {
  const std::string bytes = io::read_file(path);
  std::string_view rest(bytes);
  const Header h = read_header(path, rest);
  EstTrack track;
  track.channel_names = h.channel_names;
  if (h.binary) {
    read_binary(path, h, rest, track);
  } else {
    read_ascii(path, h, rest, track);
  }
  return track;
}

EstOptions EstOptions::mocha() {
  struct Coil {
    const char* prefix;
    const char* sensor;
    bool optional;
  };
  // Velum and nose-bridge coils are optional so that a speaker recorded without them still
  // loads (those sensors are then NaN).
  constexpr Coil coils[] = {{"tt", "TT", false}, {"tb", "TB", false},     {"td", "TD", false},
                            {"ul", "UL", false}, {"ll", "LL", false},     {"li", "LI", false},
                            {"v", "V", true},    {"ui", "REF-UI", false}, {"bn", "REF-BN", true}};
  EstOptions opt;
  for (const Coil& coil : coils) {
    opt.channels.push_back({fmt::format("{}_x", coil.prefix), coil.sensor, 0, coil.optional});
    opt.channels.push_back({fmt::format("{}_y", coil.prefix), coil.sensor, 2, coil.optional});
  }
  // Units and directions as MOCHAtools (Qin & Carreira-Perpinan) read them: values / 100 are mm,
  // and in that plot the lips sit near x = 0 with the velum at x = +60 and the nose bridge up.
  opt.scale_to_mm = 0.01f;
  opt.axis_sign = {-1.0f, 1.0f, 1.0f};
  return opt;
}

// mngu0 names each AG500 sensor's position px (lateral), py (front-back), pz (vertical), in mm.
// The sign of py and px is not documented where we could check: they are taken as they are
// (x = py, y = px, z = pz); flip axis_sign if the tongue tip comes out behind the dorsum.
EstOptions EstOptions::mngu0() {
  EstOptions opt;
  const std::vector<std::pair<std::string, std::string>> sensors = {
      {"T1", "TT"},       {"T2", "TB"},       {"T3", "TD"},
      {"upperlip", "UL"}, {"lowerlip", "LL"}, {"jaw", "LI"}};
  for (const auto& [name, sensor] : sensors) {
    opt.channels.push_back({name + "_py", sensor, 0, false});
    opt.channels.push_back({name + "_px", sensor, 1, false});
    opt.channels.push_back({name + "_pz", sensor, 2, false});
  }
  return opt;
}

std::unique_ptr<CorpusSource> open_est_source(const fs::path& dir, const EstOptions& opt) {
  return std::make_unique<EstSource>(dir, opt);
}

}  // namespace glossa::ema
