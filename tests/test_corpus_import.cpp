// Corpus readers (npy + meta.json, IMT'22 layout) and the importer: dropouts, length
// reconciliation, neutral poses, malformed inputs; STEM-E2VA when ../shared/data has it.
#include <gtest/gtest.h>

#include <cmath>

#include "audio/decode.h"
#include "core/error.h"
#include "ema/corpus.h"
#include "ema/import.h"
#include "ema/readers/imt22.h"
#include "ema/readers/npy_meta.h"
#include "io/npy.h"
#include "support/fixtures.h"

namespace glossa {
namespace {
namespace fs = std::filesystem;

Audio tone(double seconds) {
  Audio a;
  a.samples.resize(static_cast<size_t>(seconds * 16000));
  for (size_t i = 0; i < a.samples.size(); ++i)
    a.samples[i] = 0.3f * static_cast<float>(std::sin(2 * M_PI * 220 * i / 16000.0));
  return a;
}

// An npy-layout source: 2 sensors at 250 Hz, `frames` samples, offset by speaker.
void write_npy_source(const fs::path& dir, const std::string& id, size_t frames, double seconds,
                      float offset, bool nan_run = false, size_t nan_len = 0) {
  std::vector<float> d(frames * 2 * 3);
  for (size_t f = 0; f < frames; ++f)
    for (size_t c = 0; c < 6; ++c) d[f * 6 + c] = offset + static_cast<float>(c) + 0.01f * f;
  if (nan_run)
    for (size_t f = 10; f < 10 + nan_len; ++f) d[f * 6 + 0] = NAN;
  io::write_npy(dir / (id + ".npy"), d.data(), {frames, 2, 3});
  audio::write_wav(dir / (id + ".wav"), tone(seconds));
}

void write_meta(const fs::path& dir) {
  testing::write_bytes(dir / "meta.json",
                       R"({"ema": {"sample_rate_hz": 250, "sensors": [{"code": "TT"}, {"code": "UL"}]},
                           "speakers": {"AAA": {}, "BBB": {}}, "emotions": {"NE": "neutral"}})");
}

TEST(NpyMetaSource, ParsesIdsAndShapes) {
  testing::TempDir t;
  write_meta(t.path());
  write_npy_source(t.path(), "AAANE01", 500, 2.0, 0);
  auto src = ema::open_npy_meta_source(t.path());
  ASSERT_EQ(src->ids(), std::vector<std::string>{"AAANE01"});
  const auto u = src->load("AAANE01");
  EXPECT_EQ(u.speaker, "AAA");
  EXPECT_EQ(u.text, "01");
  EXPECT_EQ(u.tags.at("emotion"), "NE");
  EXPECT_EQ(u.ema.rate, 250);
  EXPECT_EQ(u.ema.frames(), 500u);
  EXPECT_EQ(u.ema.set.names, (std::vector<std::string>{"TT", "UL"}));
}

TEST(NpyMetaSource, WrongShapeAndMissingMetaAreClearErrors) {
  testing::TempDir t;
  EXPECT_THROW(ema::open_npy_meta_source(t.path()), Error);
  write_meta(t.path());
  std::vector<float> d(100 * 3 * 3, 1.f);
  io::write_npy(t / "AAANE02.npy", d.data(), {100, 3, 3});
  audio::write_wav(t / "AAANE02.wav", tone(0.4));
  auto src = ema::open_npy_meta_source(t.path());
  try {
    src->load("AAANE02");
    FAIL() << "expected an error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("AAANE02.npy"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("shape"), std::string::npos) << e.what();
  }
}

TEST(Import, NormalisesFillsGapsSkipsLongDropoutsAndEstimatesNeutral) {
  testing::TempDir t;
  const fs::path src = t / "src";
  fs::create_directories(src);
  write_meta(src);
  write_npy_source(src, "AAANE01", 500, 2.0, 0.f, true, 5);      // 20 ms gap: filled
  write_npy_source(src, "BBBNE01", 500, 2.0, 40.f);               // other origin
  write_npy_source(src, "AAANE02", 500, 2.0, 0.f, true, 200);     // 0.8 s gap: skipped
  write_npy_source(src, "BBBNE02", 500, 1.9, 40.f);               // audio 0.1 s short
  write_npy_source(src, "AAANE03", 500, 4.0, 0.f);                // 2 s longer audio: skipped
  auto source = ema::open_npy_meta_source(src);
  ema::ImportOptions o;
  o.out = t / "corpus";
  const auto r = ema::import_corpus(*source, o);
  EXPECT_EQ(r.imported, 3u);
  EXPECT_EQ(r.skipped, 2u);

  const auto c = ema::Corpus::load(t / "corpus");
  ASSERT_EQ(c.utterances().size(), 3u);
  const auto& a = c.utterance("AAANE01");
  EXPECT_EQ(a.frames, 100u);  // 500 samples at 250 Hz -> 100 frames at 50 fps
  const auto lm = c.load_landmarks(a);
  EXPECT_TRUE(lm.positions.allFinite());
  // Nearest-neighbour: frame k is source sample 5k.
  EXPECT_NEAR(lm.positions(3, 1), 1.f + 0.01f * 15, 1e-5);
  // Length reconciled: 1.9 s of audio -> 95 frames, landmarks trimmed to match.
  EXPECT_EQ(c.utterance("BBBNE02").frames, 95u);
  EXPECT_EQ(c.load_audio(c.utterance("BBBNE02")).samples.size(), 95u * 320);
  // Neutral poses sit 40 mm apart, as the origins do.
  EXPECT_NEAR(c.speaker("BBB").neutral(0) - c.speaker("AAA").neutral(0), 40.f, 0.5f);
  // The manifest reports what was skipped and why.
  const std::string m = c.manifest().dump();
  EXPECT_NE(m.find("dropout"), std::string::npos);
  EXPECT_NE(m.find("lengths differ"), std::string::npos);
}

TEST(Import, RefusesToWriteIntoAForeignFolder) {
  testing::TempDir t;
  const fs::path src = t / "src";
  fs::create_directories(src);
  write_meta(src);
  write_npy_source(src, "AAANE01", 500, 2.0, 0.f);
  testing::write_bytes(t / "busy" / "precious.txt", "do not overwrite");
  auto source = ema::open_npy_meta_source(src);
  ema::ImportOptions o;
  o.out = t / "busy";
  EXPECT_THROW(ema::import_corpus(*source, o), Error);
}

TEST(Imt22Source, PairsFilesTranscriptsAndSplitLists) {
  testing::TempDir t;
  fs::create_directories(t / "wav");
  fs::create_directories(t / "landmarks");
  std::vector<float> d(60 * 30);
  for (size_t i = 0; i < d.size(); ++i) d[i] = static_cast<float>(i % 30);
  for (const char* id : {"0001", "0002"}) {
    io::write_npy(t / "landmarks" / (std::string(id) + ".npy"), d.data(), {60, 30});
    audio::write_wav(t / "wav" / (std::string(id) + ".wav"), tone(1.2));
  }
  testing::write_bytes(t / "transcripts.txt", "0001 The birch canoe slid\n0002 Glue the sheet\n");
  testing::write_bytes(t / "test.txt", "0002\n");
  testing::write_bytes(t / "train.txt", "0001\n");
  auto src = ema::open_imt22_source(t.path());
  ASSERT_EQ(src->ids().size(), 2u);
  const auto u = src->load("0002");
  EXPECT_EQ(u.transcript, "Glue the sheet");
  EXPECT_EQ(u.tags.at("split"), "test");
  EXPECT_EQ(u.ema.set, LandmarkSet::imt22());
  EXPECT_FLOAT_EQ(u.ema.positions(0, 29), 29.f);
  // Wrong width is refused with the file's name.
  std::vector<float> bad(60 * 21);
  io::write_npy(t / "landmarks" / "0001.npy", bad.data(), {60, 21});
  try {
    src->load("0001");
    FAIL();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("0001.npy"), std::string::npos);
  }
}

TEST(StemE2va, ImportsBothSpeakersWithSeparateNeutrals) {
  const fs::path data = testing::shared_data_dir();
  if (data.empty() || !fs::exists(data / "stem-e2va" / "meta.json"))
    GTEST_SKIP() << "../shared/data/stem-e2va is absent; skipping the real-data import test";
  auto source = ema::open_npy_meta_source(data / "stem-e2va");
  EXPECT_EQ(source->ids().size(), 223u);
  const auto u = source->load("CXYFNE01");
  EXPECT_EQ(u.speaker, "CXY");
  EXPECT_EQ(u.text, "01");
  EXPECT_EQ(u.ema.set, LandmarkSet::stem7());
  EXPECT_EQ(u.ema.rate, 250);
  // Import a few utterances per speaker and check the neutral poses lie far apart.
  testing::TempDir t;
  fs::create_directories(t / "src");
  fs::copy_file(data / "stem-e2va" / "meta.json", t / "src" / "meta.json");
  for (const char* id : {"CXYFNE01", "CXYFNE02", "DPMNE01", "DPMNE02"})
    for (const char* ext : {".npy", ".wav"})
      fs::create_symlink(data / "stem-e2va" / (std::string(id) + ext), t / "src" / (std::string(id) + ext));
  auto sub = ema::open_npy_meta_source(t / "src");
  ema::ImportOptions o;
  o.out = t / "corpus";
  EXPECT_EQ(ema::import_corpus(*sub, o).imported, 4u);
  const auto c = ema::Corpus::load(t / "corpus");
  const float dist = (c.speaker("CXY").neutral - c.speaker("DPM").neutral).norm();
  EXPECT_GT(dist, 20.f);
}

}  // namespace
}  // namespace glossa
