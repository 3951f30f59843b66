// AG501 .pos reader and source, on fixtures written byte by byte here.
#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstring>
#include <initializer_list>
#include <limits>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "audio/decode.h"
#include "core/error.h"
#include "ema/readers/ag501_pos.h"
#include "support/fixtures.h"

namespace glossa::ema {
namespace {

namespace fs = std::filesystem;
using testing::TempDir;
using testing::write_bytes;

constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();

std::string f32le(float v) {
  uint32_t u = std::bit_cast<uint32_t>(v);
  if constexpr (std::endian::native == std::endian::big) u = __builtin_bswap32(u);
  std::string out(4, '\0');
  std::memcpy(out.data(), &u, 4);
  return out;
}

// The header as the AG501 writes it: magic, 8-digit total header size, key=value lines, padding.
std::string pos_header(std::string_view fields, std::string_view magic = "AG50xDATA_V003") {
  const size_t size = magic.size() + 1 + 9 + fields.size() + 2;
  return fmt::format("{}\n{:08d}\n{}", magic, size, fields) + std::string("\0\x1a", 2);
}

std::string pos_header(int channels, double rate) {
  return pos_header(fmt::format("NumberOfChannels={}\nSamplingFrequencyHz={}\n", channels, rate));
}

float value(int sample, int channel, int k) { return 100.0f * sample + 10.0f * channel + k + 0.5f; }

std::string samples(int count, int channels) {
  std::string out;
  for (int s = 0; s < count; ++s)
    for (int c = 0; c < channels; ++c)
      for (int k = 0; k < kPosValuesPerChannel; ++k) out += f32le(value(s, c, k));
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

TEST(Ag501Pos, ReadsHeaderAndSamples) {
  TempDir tmp;
  const fs::path p = tmp / "u.pos";
  write_bytes(p, pos_header(3, 250) + samples(4, 3));
  const PosFile pos = read_ag501_pos(p);
  EXPECT_EQ(pos.rate, 250.0);
  EXPECT_EQ(pos.channels, 3);
  EXPECT_EQ(pos.values_per_channel, 7);
  ASSERT_EQ(pos.data.rows(), 4);
  ASSERT_EQ(pos.data.cols(), 21);
  for (int s = 0; s < 4; ++s)
    for (int c = 0; c < 3; ++c)
      for (int k = 0; k < 7; ++k) EXPECT_EQ(pos.data(s, c * 7 + k), value(s, c, k));
}

TEST(Ag501Pos, ReadsThePublishedV002HeaderOf70Bytes) {
  TempDir tmp;
  const fs::path p = tmp / "v2.pos";
  const std::string header =
      std::string("AG50xDATA_V002\n00000070\nNumberOfChannels=16\nSamplingFrequencyHz=250\n") +
      std::string("\0\x1a", 2);
  ASSERT_EQ(header.size(), 70u);
  write_bytes(p, header + samples(2, 16));
  const PosFile pos = read_ag501_pos(p);
  EXPECT_EQ(pos.channels, 16);
  EXPECT_EQ(pos.rate, 250.0);
  ASSERT_EQ(pos.data.rows(), 2);
  EXPECT_EQ(pos.data(1, 15 * 7 + 2), value(1, 15, 2));
}

TEST(Ag501Pos, KeepsNaN) {
  TempDir tmp;
  const fs::path p = tmp / "nan.pos";
  std::string data = samples(2, 1);
  data.replace(7 * 4, 4, f32le(kNaN));  // sample 1, x
  write_bytes(p, pos_header(1, 1250) + data);
  const PosFile pos = read_ag501_pos(p);
  EXPECT_TRUE(std::isnan(pos.data(1, 0)));
  EXPECT_EQ(pos.data(1, 1), value(1, 0, 1));
}

TEST(Ag501Pos, RejectsMalformedFiles) {
  TempDir tmp;
  const auto check = [&](const std::string& name, const std::string& bytes,
                         std::string_view problem) {
    SCOPED_TRACE(name);
    write_bytes(tmp / name, bytes);
    expect_error([&] { read_ag501_pos(tmp / name); }, {name, problem});
  };
  check("empty.pos", "", "empty");
  check("bad_magic.pos", "HELLO WORLD\n00000070\n" + samples(1, 1), "not an AG501");
  check("version.pos", "AG50xDATA_V009\n00000030\n", "unsupported");
  check("size_text.pos", "AG50xDATA_V003\nabc\nNumberOfChannels=1\n", "header size");
  check("size_big.pos", "AG50xDATA_V003\n00099999\nNumberOfChannels=1\n", "does not fit");
  check("no_channels.pos", pos_header("SamplingFrequencyHz=250\n") + samples(1, 1),
        "NumberOfChannels");
  check("no_rate.pos", pos_header("NumberOfChannels=1\n") + samples(1, 1), "SamplingFrequencyHz");
  check("bad_rate.pos",
        pos_header("NumberOfChannels=1\nSamplingFrequencyHz=fast\n") + samples(1, 1),
        "SamplingFrequencyHz");
  check("bad_count.pos", pos_header("NumberOfChannels=x2\nSamplingFrequencyHz=250\n"),
        "NumberOfChannels");
  check("not_kv.pos", pos_header("NumberOfChannels=1\ngarbage line\n") + samples(1, 1),
        "key=value");
  check("zero.pos", pos_header(0, 250), "zero channels");
  check("no_samples.pos", pos_header(2, 250), "no samples");
  check("truncated.pos", pos_header(2, 250) + samples(3, 2) + std::string(5, '\0'), "partial");
}

TEST(Ag501Pos, ReadsHeaderlessAg500) {
  TempDir tmp;
  const fs::path p = tmp / "ag500.pos";
  write_bytes(p, samples(3, 12));
  const PosFile pos = read_ag500_pos(p);
  EXPECT_EQ(pos.channels, 12);
  EXPECT_EQ(pos.rate, 200.0);
  ASSERT_EQ(pos.data.rows(), 3);
  EXPECT_EQ(pos.data(2, 11 * 7 + 6), value(2, 11, 6));
  write_bytes(p, samples(3, 12) + "xy");
  expect_error([&] { read_ag500_pos(p); }, {"ag500.pos", "partial"});
}

TEST(Ag501ChannelMap, Parses) {
  const auto map = parse_channel_map(" 1=TD, 2=TB ,10=REF-UI");
  ASSERT_EQ(map.size(), 3u);
  EXPECT_EQ(map[0].channel, 1);
  EXPECT_EQ(map[0].sensor, "TD");
  EXPECT_EQ(map[1].sensor, "TB");
  EXPECT_EQ(map[2].channel, 10);
  EXPECT_EQ(map[2].sensor, "REF-UI");
}

TEST(Ag501ChannelMap, RejectsMalformedText) {
  for (const std::string text :
       {"", "1=TT,", "TT", "x=TT", "0=TT", "-1=TT", "1=", "1=T T", "1=TT,1=TB", "1=TT,2=TT"}) {
    SCOPED_TRACE(text);
    expect_error([&] { parse_channel_map(text); }, {"channel map"});
  }
}

class Ag501SourceTest : public ::testing::Test {
 protected:
  void SetUp() override {
    corpus_ = tmp_.path() / "spk01";
    std::string b = samples(5, 4);
    b.replace((2 * 4 * 7 + 1 * 7 + 1) * 4, 4, f32le(kNaN));  // sample 2, channel 2 (1-based), y
    write_bytes(corpus_ / "pos" / "b.pos", pos_header(4, 250) + b);
    write_bytes(corpus_ / "pos" / "a.pos", pos_header(4, 250) + samples(3, 4));
    write_wav(corpus_ / "wav" / "a.wav");
    write_wav(corpus_ / "wav" / "b.wav");
    opt_.channels = parse_channel_map("2=TT,4=REF-UI,1=TB");
  }

  TempDir tmp_;
  fs::path corpus_;
  Ag501Options opt_;
};

TEST_F(Ag501SourceTest, ListsAndLoadsUtterances) {
  const auto source = open_ag501_source(corpus_, opt_);
  EXPECT_EQ(source->format(), "ag501");
  EXPECT_EQ(source->ids(), (std::vector<std::string>{"a", "b"}));

  const RawUtterance utt = source->load("b");
  EXPECT_EQ(utt.id, "b");
  EXPECT_EQ(utt.speaker, "spk01");
  EXPECT_EQ(utt.audio_path, corpus_ / "wav" / "b.wav");
  EXPECT_EQ(utt.ema.set.names, (std::vector<std::string>{"TT", "REF-UI", "TB"}));
  EXPECT_EQ(utt.ema.rate, 250.0);
  ASSERT_EQ(utt.ema.frames(), 5u);
  ASSERT_EQ(utt.ema.dims(), 9u);
  const int channel_of[] = {1, 3, 0};  // 0-based channels of TT, REF-UI, TB
  for (int s = 0; s < 5; ++s) {
    for (int l = 0; l < 3; ++l) {
      for (int axis = 0; axis < 3; ++axis) {
        const float got = utt.ema.positions(s, l * 3 + axis);
        if (s == 2 && l == 0 && axis == 1) {
          EXPECT_TRUE(std::isnan(got));
        } else {
          EXPECT_EQ(got, value(s, channel_of[l], axis)) << s << " " << l << " " << axis;
        }
      }
    }
  }
  EXPECT_FALSE(source->describe().empty());
}

TEST_F(Ag501SourceTest, FlatLayoutAndSpeakerOption) {
  const fs::path flat = tmp_.path() / "flat";
  write_bytes(flat / "u1.pos", pos_header(4, 1250) + samples(2, 4));
  write_wav(flat / "u1.wav");
  opt_.speaker = "S9";
  const auto source = open_ag501_source(flat, opt_);
  const RawUtterance utt = source->load("u1");
  EXPECT_EQ(utt.speaker, "S9");
  EXPECT_EQ(utt.audio_path, flat / "u1.wav");
  EXPECT_EQ(utt.ema.rate, 1250.0);
}

TEST_F(Ag501SourceTest, MissingAudioNamesTheUtterance) {
  fs::remove(corpus_ / "wav" / "a.wav");
  const auto source = open_ag501_source(corpus_, opt_);
  expect_error([&] { source->load("a"); }, {"a.pos", "no audio", "'a'"});
  EXPECT_NO_THROW(source->load("b"));
}

TEST_F(Ag501SourceTest, ChannelBeyondTheFileIsAnError) {
  opt_.channels = parse_channel_map("1=TT,5=TB");
  const auto source = open_ag501_source(corpus_, opt_);
  expect_error([&] { source->load("a"); }, {"a.pos", "channel 5"});
}

TEST_F(Ag501SourceTest, RejectsBadSetups) {
  expect_error([&] { open_ag501_source(corpus_ / "nothing", opt_); }, {"nothing"});
  fs::create_directories(tmp_.path() / "empty");
  expect_error([&] { open_ag501_source(tmp_.path() / "empty", opt_); }, {"empty", ".pos"});
  opt_.channels.clear();
  expect_error([&] { open_ag501_source(corpus_, opt_); }, {"channel map"});
  opt_.channels = {{1, "TT"}, {2, "TT"}};
  expect_error([&] { open_ag501_source(corpus_, opt_); }, {"TT", "twice"});
  opt_.channels = {{1, "TT"}};
  const auto source = open_ag501_source(corpus_, opt_);
  expect_error([&] { source->load("zzz"); }, {"zzz"});
}

}  // namespace
}  // namespace glossa::ema
