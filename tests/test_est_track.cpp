// EST track reader and source (MOCHA-TIMIT, mngu0), on fixtures written byte by byte here.
#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>
#include <initializer_list>
#include <limits>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "audio/decode.h"
#include "core/error.h"
#include "ema/readers/est_track.h"
#include "support/fixtures.h"

namespace glossa::ema {
namespace {

namespace fs = std::filesystem;
using testing::TempDir;
using testing::write_bytes;

constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();

std::string f32(float v, bool big_endian) {
  uint32_t u = std::bit_cast<uint32_t>(v);
  if ((std::endian::native == std::endian::big) != big_endian) u = __builtin_bswap32(u);
  std::string out(4, '\0');
  std::memcpy(out.data(), &u, 4);
  return out;
}

struct Frame {
  float time;
  bool valid;
  std::vector<float> values;
};

std::vector<Frame> frames_at(double rate, int count, int channels) {
  std::vector<Frame> frames;
  for (int f = 0; f < count; ++f) {
    Frame fr{static_cast<float>(f / rate), true, {}};
    for (int c = 0; c < channels; ++c) fr.values.push_back(1000.0f * (c + 1) + f);
    frames.push_back(fr);
  }
  return frames;
}

std::string channel_lines(const std::vector<std::string>& names) {
  std::string out;
  for (size_t i = 0; i < names.size(); ++i) out += fmt::format("Channel_{} {}\n", i, names[i]);
  return out;
}

// The header and data the way speech_tools' save_est_binary_ts writes them.
std::string est_binary(const std::vector<std::string>& names, const std::vector<Frame>& frames,
                       bool big_endian = false) {
  std::string out = fmt::format(
      "EST_File Track\nDataType binary\nByteOrder {}\nNumFrames {}\nNumChannels {}\n"
      "EqualSpace 1\nBreaksPresent true\nCommentChar ;\n\n",
      big_endian ? "10" : "01", frames.size(), names.size());
  out += channel_lines(names) + "EST_Header_End\n";
  for (const Frame& f : frames) {
    out += f32(f.time, big_endian) + f32(f.valid ? 1.0f : 0.0f, big_endian);
    for (const float v : f.values) out += f32(v, big_endian);
  }
  return out;
}

std::string est_ascii(const std::vector<std::string>& names, const std::vector<Frame>& frames,
                      bool breaks = true) {
  std::string out = fmt::format("EST_File Track\nDataType ascii\nNumFrames {}\nNumChannels {}\n",
                                frames.size(), names.size());
  if (breaks) out += "BreaksPresent true\n";
  out += "CommentChar ;\n" + channel_lines(names) + "EST_Header_End\n";
  for (const Frame& f : frames) {
    out += fmt::format("{}\t", f.time);
    if (breaks) out += f.valid ? "1 \t" : "0 \t";
    for (const float v : f.values) out += fmt::format("{} ", v);
    out += "\n";
  }
  return out;
}

template <class F>
void expect_error(F&& f, std::initializer_list<std::string_view> needles) {
  try {
    f();
    ADD_FAILURE() << "expected a glossa::Error";
  } catch (const Error& e) {
    const std::string what = e.what();
    for (const auto needle : needles) {
      EXPECT_NE(what.find(needle), std::string::npos) << "'" << needle << "' not in: " << what;
    }
  }
}

void write_wav(const fs::path& path) {
  Audio audio;
  audio.samples.assign(1600, 0.0f);
  audio::write_wav(path, audio);
}

void expect_track(const EstTrack& t, const std::vector<std::string>& names,
                  const std::vector<Frame>& frames) {
  EXPECT_EQ(t.channel_names, names);
  ASSERT_EQ(t.times.size(), frames.size());
  ASSERT_EQ(t.valid.size(), frames.size());
  ASSERT_EQ(t.values.rows(), static_cast<Eigen::Index>(frames.size()));
  ASSERT_EQ(t.values.cols(), static_cast<Eigen::Index>(names.size()));
  for (size_t f = 0; f < frames.size(); ++f) {
    EXPECT_FLOAT_EQ(t.times[f], frames[f].time);
    EXPECT_EQ(t.valid[f], frames[f].valid ? 1.0f : 0.0f);
    for (size_t c = 0; c < names.size(); ++c) {
      const float want = frames[f].values[c];
      const float got = t.values(static_cast<Eigen::Index>(f), static_cast<Eigen::Index>(c));
      if (std::isnan(want)) {
        EXPECT_TRUE(std::isnan(got));
      } else {
        EXPECT_EQ(got, want);
      }
    }
  }
}

const std::vector<std::string> kTwo = {"a_x", "a_y"};

TEST(EstTrack, ReadsLittleEndianBinary) {
  TempDir tmp;
  auto frames = frames_at(500, 4, 2);
  frames[2].valid = false;
  frames[1].values[0] = kNaN;
  write_bytes(tmp / "le.ema", est_binary(kTwo, frames));
  const EstTrack t = read_est_track(tmp / "le.ema");
  expect_track(t, kTwo, frames);
  EXPECT_EQ(t.rate(), 500.0);
}

TEST(EstTrack, ReadsBigEndianBinary) {
  TempDir tmp;
  auto frames = frames_at(200, 3, 2);
  frames[0].valid = false;
  write_bytes(tmp / "be.ema", est_binary(kTwo, frames, /*big_endian=*/true));
  const EstTrack t = read_est_track(tmp / "be.ema");
  expect_track(t, kTwo, frames);
  EXPECT_EQ(t.rate(), 200.0);
}

TEST(EstTrack, ReadsAscii) {
  TempDir tmp;
  auto frames = frames_at(100, 3, 2);
  frames[1].valid = false;
  frames[2].values[1] = kNaN;
  write_bytes(tmp / "a.ema", est_ascii(kTwo, frames));
  expect_track(read_est_track(tmp / "a.ema"), kTwo, frames);

  const auto plain = frames_at(100, 2, 2);
  write_bytes(tmp / "nobreaks.ema", est_ascii(kTwo, plain, /*breaks=*/false));
  expect_track(read_est_track(tmp / "nobreaks.ema"), kTwo, plain);
}

TEST(EstTrack, HeaderKeysInAnyOrderAndPaddedNames) {
  TempDir tmp;
  const auto frames = frames_at(200, 2, 2);
  std::string bytes =
      "EST_File Track\nDataType binary\nNumFrames 2\nByteOrder 01\nNumChannels 2\n"
      "EqualSpace 1\nBreaksPresent true\nCommentChar ;\n\n; a comment\n"
      "Channel_1 v_y \nChannel_0 v_x \nEST_Header_End\n";
  for (const Frame& f : frames) {
    bytes += f32(f.time, false) + f32(1, false) + f32(f.values[0], false) + f32(f.values[1], false);
  }
  write_bytes(tmp / "m.ema", bytes);
  expect_track(read_est_track(tmp / "m.ema"), {"v_x", "v_y"}, frames);
}

TEST(EstTrack, RateNeedsTwoFrames) {
  EstTrack t;
  EXPECT_EQ(t.rate(), 0.0);
  t.times = {0.5f};
  EXPECT_EQ(t.rate(), 0.0);
  t.times = {0.0f, 0.004f, 0.008f};
  EXPECT_EQ(t.rate(), 250.0);
}

TEST(EstTrack, RejectsMalformedFiles) {
  TempDir tmp;
  const auto check = [&](const std::string& name, const std::string& bytes,
                         std::string_view problem) {
    SCOPED_TRACE(name);
    write_bytes(tmp / name, bytes);
    expect_error([&] { read_est_track(tmp / name); }, {name, problem});
  };
  const auto frames = frames_at(500, 3, 2);
  const std::string good = est_binary(kTwo, frames);
  const auto replaced = [&](std::string_view from, std::string_view to) {
    std::string s = good;
    s.replace(s.find(from), from.size(), to);
    return s;
  };

  check("magic.ema", "EST_Flie Track\n" + good.substr(15), "not an EST file");
  check("empty.ema", "", "empty file");
  check("wave.ema", replaced("EST_File Track", "EST_File wave"), "not an EST Track");
  check("no_frames.ema", replaced("NumFrames 3\n", ""), "NumFrames");
  check("no_channels.ema", replaced("NumChannels 2\n", ""), "NumChannels");
  check("bad_frames.ema", replaced("NumFrames 3", "NumFrames three"), "NumFrames");
  check("no_end.ema", replaced("EST_Header_End\n", "EST_Header_Ends\n"), "EST_Header_End");
  check("order.ema", replaced("ByteOrder 01", "ByteOrder 11"), "ByteOrder");
  check("type.ema", replaced("DataType binary", "DataType float"), "DataType");
  check("channel.ema", replaced("Channel_1 a_y", "Channel_7 a_y"), "Channel_7");
  check("truncated.ema", good.substr(0, good.size() - 3), "truncated");
  check("trailing.ema", good + "junk", "unexpected bytes");

  const std::string ascii = est_ascii(kTwo, frames);
  check("few.ema", ascii.substr(0, ascii.rfind("\n", ascii.size() - 2) + 1), "data has 8 values");
  check("many.ema", ascii + "0.008 1 5 6\n", "data has 16 values");
  std::string word = ascii;
  word.replace(word.find("2001"), 4, "oops");
  check("word.ema", word, "'oops' is not a number");
}

// MOCHA-TIMIT's channel order (x of five coils, then their y, ...), one name padded as in fsew0.
const std::vector<std::string> kMochaNames = {"ui_x", "li_x", "ul_x", "ll_x", "tt_x", "ui_y",
                                              "li_y", "ul_y", "ll_y", "tt_y", "tb_x", "td_x",
                                              "v_x ", "bn_x", "tb_y", "td_y", "v_y ", "bn_y"};

class EstSourceTest : public ::testing::Test {
 protected:
  void SetUp() override {
    corpus_ = tmp_.path() / "fsew0";
    frames_ = frames_at(500, 5, static_cast<int>(kMochaNames.size()));
    frames_[3].valid = false;
    frames_[1].values[9] = kNaN;  // tt_y
    write_bytes(corpus_ / "ema" / "fsew0_002.ema", est_binary(kMochaNames, frames_));
    write_bytes(corpus_ / "ema" / "fsew0_001.ema", est_binary(kMochaNames, frames_at(500, 2, 18)));
    write_wav(corpus_ / "wav" / "fsew0_001.wav");
    write_wav(corpus_ / "wav" / "fsew0_002.wav");
  }

  float raw(int frame, std::string_view channel) const {
    for (size_t c = 0; c < kMochaNames.size(); ++c) {
      if (kMochaNames[c].starts_with(channel)) return frames_[frame].values[c];
    }
    ADD_FAILURE() << channel;
    return 0;
  }

  TempDir tmp_;
  fs::path corpus_;
  std::vector<Frame> frames_;
};

TEST_F(EstSourceTest, LoadsMochaIntoTheHeadFrame) {
  const auto source = open_est_source(corpus_, EstOptions::mocha());
  EXPECT_EQ(source->format(), "est");
  EXPECT_EQ(source->ids(), (std::vector<std::string>{"fsew0_001", "fsew0_002"}));

  const RawUtterance utt = source->load("fsew0_002");
  EXPECT_EQ(utt.speaker, "fsew0");
  EXPECT_EQ(utt.audio_path, corpus_ / "wav" / "fsew0_002.wav");
  EXPECT_EQ(utt.ema.set.names, (std::vector<std::string>{"TT", "TB", "TD", "UL", "LL", "LI", "V",
                                                         "REF-UI", "REF-BN"}));
  EXPECT_EQ(utt.ema.rate, 500.0);
  ASSERT_EQ(utt.ema.frames(), 5u);
  const auto& p = utt.ema.positions;
  const std::vector<std::string> coils = {"tt", "tb", "td", "ul", "ll", "li", "v", "ui", "bn"};
  for (int f = 0; f < 5; ++f) {
    for (size_t l = 0; l < coils.size(); ++l) {
      const auto col = static_cast<Eigen::Index>(3 * l);
      if (f == 3 || (f == 1 && l == 0)) {  // a break, and TT with its y missing
        EXPECT_TRUE(p.row(f).segment(col, 3).array().isNaN().all()) << f << " " << l;
        continue;
      }
      EXPECT_FLOAT_EQ(p(f, col), -0.01f * raw(f, coils[l] + "_x"));
      EXPECT_EQ(p(f, col + 1), 0.0f);
      EXPECT_FLOAT_EQ(p(f, col + 2), 0.01f * raw(f, coils[l] + "_y"));
    }
  }
}

TEST_F(EstSourceTest, OptionalChannelsBecomeNaNRequiredOnesAreErrors) {
  std::vector<std::string> names = kMochaNames;
  names[12] = "vx";  // velum x renamed: V is optional
  write_bytes(corpus_ / "ema" / "fsew0_001.ema", est_binary(names, frames_at(500, 2, 18)));
  const auto source = open_est_source(corpus_, EstOptions::mocha());
  const RawUtterance utt = source->load("fsew0_001");
  EXPECT_TRUE(utt.ema.positions.middleCols(3 * 6, 3).array().isNaN().all());
  EXPECT_FALSE(utt.ema.positions.middleCols(0, 3).array().isNaN().any());

  names[4] = "tip_x";
  write_bytes(corpus_ / "ema" / "fsew0_001.ema", est_binary(names, frames_at(500, 2, 18)));
  expect_error([&] { source->load("fsew0_001"); }, {"fsew0_001.ema", "'tt_x'"});
}

TEST_F(EstSourceTest, MissingAudioNamesTheUtterance) {
  fs::remove(corpus_ / "wav" / "fsew0_001.wav");
  const auto source = open_est_source(corpus_, EstOptions::mocha());
  expect_error([&] { source->load("fsew0_001"); }, {"fsew0_001.ema", "no audio", "'fsew0_001'"});
  EXPECT_NO_THROW(source->load("fsew0_002"));
}

TEST_F(EstSourceTest, SingleFrameHasNoRate) {
  write_bytes(corpus_ / "ema" / "fsew0_001.ema", est_binary(kMochaNames, frames_at(500, 1, 18)));
  const auto source = open_est_source(corpus_, EstOptions::mocha());
  expect_error([&] { source->load("fsew0_001"); }, {"fsew0_001.ema", "frame rate"});
}

TEST_F(EstSourceTest, LoadsMngu0FlatLayout) {
  const fs::path dir = tmp_.path() / "mngu0";
  std::vector<std::string> names;
  for (const std::string s : {"T3", "T2", "T1", "ref", "jaw", "upperlip", "lowerlip"}) {
    for (const std::string k : {"px", "py", "pz", "ox", "oy", "oz", "rms"}) {
      names.push_back(s + "_" + k);
    }
  }
  const auto frames = frames_at(200, 3, static_cast<int>(names.size()));
  write_bytes(dir / "mngu0_s1_0001.ema", est_binary(names, frames));
  write_wav(dir / "mngu0_s1_0001.wav");
  const auto source = open_est_source(dir, EstOptions::mngu0());
  const RawUtterance utt = source->load("mngu0_s1_0001");
  EXPECT_EQ(utt.ema.set.names, (std::vector<std::string>{"TT", "TB", "TD", "UL", "LL", "LI"}));
  EXPECT_EQ(utt.ema.rate, 200.0);
  const auto at = [&](int f, const std::string& channel) {
    const auto it = std::find(names.begin(), names.end(), channel);
    return frames[f].values[static_cast<size_t>(it - names.begin())];
  };
  EXPECT_EQ(utt.ema.positions(2, 0), at(2, "T1_py"));
  EXPECT_EQ(utt.ema.positions(2, 1), at(2, "T1_px"));
  EXPECT_EQ(utt.ema.positions(2, 2), at(2, "T1_pz"));
  EXPECT_EQ(utt.ema.positions(1, 5 * 3 + 2), at(1, "jaw_pz"));
}

TEST_F(EstSourceTest, RejectsBadSetups) {
  EstOptions opt = EstOptions::mocha();
  expect_error([&] { open_est_source(corpus_ / "nothing", opt); }, {"nothing"});
  fs::create_directories(tmp_.path() / "empty");
  expect_error([&] { open_est_source(tmp_.path() / "empty", opt); }, {"empty", ".ema"});
  opt.channels.push_back({"tt_z", "TT", 2});
  expect_error([&] { open_est_source(corpus_, opt); }, {"TT.z", "twice"});
  opt.channels = {{"a", "A", 3}};
  expect_error([&] { open_est_source(corpus_, opt); }, {"axis 3"});
  opt.channels.clear();
  expect_error([&] { open_est_source(corpus_, opt); }, {"no channel mapping"});
  const auto source = open_est_source(corpus_, EstOptions::mocha());
  expect_error([&] { source->load("fsew0_999"); }, {"fsew0_999"});
}

}  // namespace
}  // namespace glossa::ema
