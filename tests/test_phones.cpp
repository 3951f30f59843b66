// The phones stage (src/phones/): the phone file format, ARPAbet normalisation, and phones
// from speech with pocketsphinx on speech synthesised here with espeak-ng (and on a real
// recording from ../shared/data when present): forced alignment to a transcript and free phone
// recognition. Also the `glossa phones` command.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "audio/decode.h"
#include "core/error.h"
#include "phones/phone_seq.h"
#include "phones/recognizer.h"
#include "support/fixtures.h"

namespace glossa::phones {
namespace {

namespace fs = std::filesystem;
using testing::run_command;
using testing::TempDir;
using testing::write_bytes;

// Runs `f` and returns the glossa::Error message it throws ("" when it throws nothing).
template <class F>
std::string error_of(F&& f) {
  try {
    f();
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

bool contains(const std::string& s, const std::string& part) {
  return s.find(part) != std::string::npos;
}

std::vector<std::string> speech_phones(const PhoneSeq& seq) {
  std::vector<std::string> out;
  for (const auto& p : seq)
    if (p.phone != "SIL") out.push_back(p.phone);
  return out;
}

std::vector<std::string> split(const std::string& s) {
  std::vector<std::string> out;
  size_t i = 0;
  while (i < s.size()) {
    const size_t j = std::min(s.find(' ', i), s.size());
    if (j > i) out.push_back(s.substr(i, j - i));
    i = j + 1;
  }
  return out;
}

// Times start at 0, follow on without gaps or overlaps, end at the end of the audio, and no two
// silences are adjacent.
void expect_covers(const PhoneSeq& seq, double seconds) {
  ASSERT_FALSE(seq.empty());
  EXPECT_NO_THROW(validate(seq, "result"));
  EXPECT_DOUBLE_EQ(seq.front().start, 0.0);
  EXPECT_NEAR(seq.back().end, seconds, 1e-9);
  for (size_t i = 0; i < seq.size(); ++i) {
    EXPECT_LE(seq[i].start, seq[i].end) << i;
    if (i > 0) {
      EXPECT_NEAR(seq[i].start, seq[i - 1].end, 1e-9) << i;
      EXPECT_FALSE(seq[i].phone == "SIL" && seq[i - 1].phone == "SIL") << i;
    }
  }
}

// ---------------------------------------------------------------------------------------------
// Phone files and symbols.

TEST(PhoneFile, RoundTrip) {
  TempDir t;
  const PhoneSeq seq = {{"SIL", 0.0, 0.12}, {"HH", 0.12, 0.2},  {"AH", 0.2, 0.31},
                        {"L", 0.31, 0.4},   {"OW", 0.4, 0.655}, {"SIL", 0.655, 1.0}};
  const std::string path = (t / "hello.phones").string();
  write_phone_file(path, seq);
  const PhoneSeq back = read_phone_file(path);
  ASSERT_EQ(back.size(), seq.size());
  for (size_t i = 0; i < seq.size(); ++i) {
    EXPECT_EQ(back[i].phone, seq[i].phone);
    EXPECT_NEAR(back[i].start, seq[i].start, 5e-4);
    EXPECT_NEAR(back[i].end, seq[i].end, 5e-4);
  }
}

TEST(PhoneFile, ReadsStressDigitsCommentsAndPocketsphinxUnits) {
  TempDir t;
  write_bytes(t / "p.txt", "# a comment\n\n0 0.1 sil\n0.1 0.2 ah1\n0.2 0.3 +NSN+\n");
  const PhoneSeq seq = read_phone_file((t / "p.txt").string());
  ASSERT_EQ(seq.size(), 3u);
  EXPECT_EQ(seq[0].phone, "SIL");
  EXPECT_EQ(seq[1].phone, "AH");
  EXPECT_EQ(seq[2].phone, "SIL");
}

TEST(PhoneFile, MalformedFilesGiveAnErrorNamingTheFile) {
  TempDir t;
  struct Case {
    const char* name;
    const char* text;
    const char* says;
  };
  const Case cases[] = {
      {"short_line.txt", "0 0.1 AA\n0.1 0.2\n", "line 2"},
      {"extra_field.txt", "0 0.1 AA x\n", "line 1"},
      {"not_a_number.txt", "zero 0.1 AA\n", "line 1"},
      {"unknown_phone.txt", "0 0.1 AA\n0.1 0.2 QX\n", "QX"},
      {"overlap.txt", "0 0.2 AA\n0.1 0.3 B\n", "before the previous one ends"},
      {"backwards.txt", "0.3 0.2 AA\n", "bad times"},
  };
  for (const auto& c : cases) {
    write_bytes(t / c.name, c.text);
    const std::string path = (t / c.name).string();
    const std::string msg = error_of([&] { read_phone_file(path); });
    EXPECT_TRUE(contains(msg, path)) << c.name << ": " << msg;
    EXPECT_TRUE(contains(msg, c.says)) << c.name << ": " << msg;
  }
  const std::string missing = (t / "missing.txt").string();
  EXPECT_TRUE(contains(error_of([&] { read_phone_file(missing); }), missing));
}

TEST(PhoneSymbols, Normalize) {
  EXPECT_EQ(normalize_phone("ah0"), "AH");
  EXPECT_EQ(normalize_phone("AA1"), "AA");
  EXPECT_EQ(normalize_phone("er2"), "ER");
  EXPECT_EQ(normalize_phone("zh"), "ZH");
  EXPECT_EQ(normalize_phone("SIL"), "SIL");
  EXPECT_EQ(normalize_phone("sil"), "SIL");
  EXPECT_EQ(normalize_phone("<sil>"), "SIL");
  EXPECT_EQ(normalize_phone("+NSN+"), "SIL");
  EXPECT_EQ(normalize_phone("+SPN+"), "SIL");
  EXPECT_EQ(normalize_phone("sp"), "SIL");
  EXPECT_EQ(normalize_phone("QX"), "");
  EXPECT_EQ(normalize_phone("A"), "");
  EXPECT_EQ(normalize_phone(""), "");
  EXPECT_EQ(arpabet().size(), 40u);
  EXPECT_TRUE(is_vowel("OW"));
  EXPECT_FALSE(is_vowel("M"));
}

// ---------------------------------------------------------------------------------------------
// Transcripts and the pronunciation dictionary.

TEST(Transcript, WordsAreLowerCasedWithoutPunctuation) {
  EXPECT_EQ(transcript_words("  Don't STOP, Bob-cat! \"Now\"/then... 'tis  "),
            (std::vector<std::string>{"don't", "stop", "bob", "cat", "now", "then", "tis"}));
  EXPECT_TRUE(transcript_words(" ... !? ").empty());
}

TEST(Transcript, PronunciationsComeFromTheCmuDictionary) {
  EXPECT_EQ(pronunciations("forward"),
            (std::vector<std::vector<std::string>>{{"F", "AO", "R", "W", "ER", "D"}}));
  const auto the = pronunciations("the");
  ASSERT_EQ(the.size(), 2u);  // "the" and "the(2)"
  EXPECT_EQ(the[0], (std::vector<std::string>{"DH", "AH"}));
  EXPECT_EQ(the[1], (std::vector<std::string>{"DH", "IY"}));
}

TEST(Transcript, UnknownWordsNameTheWordAndCanBeGiven) {
  const std::string msg = error_of([] { pronunciations("glorbnaxx"); });
  EXPECT_TRUE(contains(msg, "'glorbnaxx'")) << msg;
  EXPECT_TRUE(contains(msg, "not in the pronunciation dictionary")) << msg;

  RecognizerOptions o;
  o.pronunciations["glorbnaxx"] = {"G L AO1 R B N AE K S"};
  EXPECT_EQ(
      pronunciations("glorbnaxx", o),
      (std::vector<std::vector<std::string>>{{"G", "L", "AO", "R", "B", "N", "AE", "K", "S"}}));
  const std::string two =
      error_of([] { align_phones(Audio{std::vector<float>(8000)}, "zorp zip zarp"); });
  EXPECT_TRUE(contains(two, "'zarp', 'zorp'")) << two;
  o.pronunciations["glorbnaxx"] = {"G L QQ"};
  EXPECT_TRUE(contains(error_of([&] { pronunciations("glorbnaxx", o); }), "'QQ'"));
}

// ---------------------------------------------------------------------------------------------
// Bad input and configuration.

TEST(Recognizer, RejectsEmptyAndWrongRateAudio) {
  Audio empty;
  EXPECT_TRUE(contains(error_of([&] { recognize_phones(empty); }), "empty"));
  EXPECT_TRUE(contains(error_of([&] { align_phones(empty, "go"); }), "empty"));
  Audio wrong_rate;
  wrong_rate.sample_rate = 22050;
  wrong_rate.samples.assign(22050, 0.0f);
  EXPECT_TRUE(contains(error_of([&] { recognize_phones(wrong_rate); }), "22050"));
  EXPECT_TRUE(contains(error_of([&] { align_phones(wrong_rate, "go"); }), "22050"));
  Audio silence;
  silence.samples.assign(kSampleRate / 2, 0.0f);
  EXPECT_TRUE(contains(error_of([&] { align_phones(silence, "!!"); }), "has no words"));
  RecognizerOptions bad;
  bad.beam = 0;
  EXPECT_TRUE(contains(error_of([&] { recognize_phones(silence, bad); }), "beam"));
}

TEST(Recognizer, DigitalSilenceIsRecognisedAsSilence) {
  Audio silence;
  silence.samples.assign(kSampleRate / 2, 0.0f);
  const PhoneSeq seq = recognize_phones(silence);
  ASSERT_EQ(seq.size(), 1u);
  EXPECT_EQ(seq[0].phone, "SIL");
  expect_covers(seq, 0.5);
}

TEST(Recognizer, MissingModelNamesThePathAndThePackage) {
  TempDir t;
  Audio a;
  a.samples.assign(kSampleRate / 2, 0.0f);
  RecognizerOptions o;
  o.model_dir = (t / "nowhere").string();
  const std::string msg = error_of([&] { recognize_phones(a, o); });
  EXPECT_TRUE(contains(msg, o.model_dir)) << msg;
  EXPECT_TRUE(contains(msg, "pocketsphinx-en-us")) << msg;

  // The environment variable overrides the built-in folder; the option overrides both.
  const std::string real = resolve_model_dir();
  ::setenv("GLOSSA_POCKETSPHINX_MODELDIR", (t / "env").c_str(), 1);
  const std::string env_msg = error_of([&] { resolve_model_dir(); });
  EXPECT_NO_THROW(resolve_model_dir(RecognizerOptions{.model_dir = real}));
  ::unsetenv("GLOSSA_POCKETSPHINX_MODELDIR");
  EXPECT_TRUE(contains(env_msg, (t / "env").string())) << env_msg;
  EXPECT_NO_THROW(resolve_model_dir());
}

// ---------------------------------------------------------------------------------------------
// Speech synthesised with espeak-ng.

constexpr const char* kSentence = "Bob may buy big maps.";

class Espeak : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = std::make_unique<TempDir>();
    const fs::path wav = *dir_ / "bob.wav";
    std::string out;
    const int rc =
        run_command(fmt::format("espeak-ng -v en-us -w '{}' '{}'", wav.string(), kSentence), &out);
    if (rc != 0 || !fs::exists(wav)) {
      why_ = fmt::format("espeak-ng could not synthesise the test sentence (exit {}): {}", rc, out);
      return;
    }
    audio_ = std::make_unique<Audio>(audio::load_audio(wav));
    wav_ = wav;
  }
  static void TearDownTestSuite() {
    audio_.reset();
    dir_.reset();
  }
  void SetUp() override {
    if (!audio_) GTEST_SKIP() << why_;
  }
  static const PhoneSeq& aligned() {
    static const PhoneSeq seq = align_phones(*audio_, kSentence);
    return seq;
  }

  static inline std::unique_ptr<TempDir> dir_;
  static inline std::unique_ptr<Audio> audio_;
  static inline fs::path wav_;
  static inline std::string why_;
};

// RMS of the audio between two times.
double rms(const Audio& a, double from, double to) {
  const auto b = static_cast<size_t>(std::max(0.0, from) * a.sample_rate);
  const auto e = std::min(a.samples.size(), static_cast<size_t>(to * a.sample_rate));
  if (e <= b) return 0;
  double s = 0;
  for (size_t i = b; i < e; ++i) s += double(a.samples[i]) * a.samples[i];
  return std::sqrt(s / double(e - b));
}

TEST_F(Espeak, AlignmentGivesTheDictionaryPhonesInOrder) {
  const PhoneSeq& seq = aligned();
  std::vector<std::string> expected;
  for (const auto& word : transcript_words(kSentence)) {
    const auto prons = pronunciations(word);
    ASSERT_EQ(prons.size(), 1u) << word;  // the sentence avoids alternate pronunciations
    expected.insert(expected.end(), prons[0].begin(), prons[0].end());
  }
  EXPECT_EQ(expected, split("B AA B M EY B AY B IH G M AE P S"));
  EXPECT_EQ(speech_phones(seq), expected);
  expect_covers(seq, audio_->seconds());
  // Every phone lasts at least the 3 frames of its HMM.
  for (const auto& p : seq) EXPECT_GE(p.end - p.start, 0.03 - 1e-9) << p.phone << " " << p.start;
  // espeak-ng leaves silence after the sentence, not before it.
  EXPECT_EQ(seq.back().phone, "SIL");
  EXPECT_GT(seq.back().end - seq.back().start, 0.1);
}

// The lips close for /p b/: the sound is much weaker there (closure, voice bar at most) than in
// the vowels. (/m/ is voiced and not reliably quieter in espeak-ng's speech.)
TEST_F(Espeak, BilabialStopsLandOnQuietStretches) {
  const PhoneSeq& seq = aligned();
  double vowel_rms = 0;
  int vowels = 0, stops = 0;
  for (const auto& p : seq)
    if (is_vowel(p.phone)) {
      vowel_rms += rms(*audio_, p.start, p.end);
      ++vowels;
    }
  ASSERT_EQ(vowels, 5);
  vowel_rms /= vowels;
  for (const auto& p : seq) {
    if (p.phone != "P" && p.phone != "B") continue;
    ++stops;
    EXPECT_LT(rms(*audio_, p.start, p.end), 0.5 * vowel_rms) << p.phone << " at " << p.start;
  }
  EXPECT_EQ(stops, 5);
}

// Broad phone class of each 10 ms frame: 0 silence, 1 vowel, 2 consonant.
std::vector<int> frame_classes(const PhoneSeq& seq, double seconds) {
  std::vector<int> out(static_cast<size_t>(seconds * 100));
  for (size_t f = 0; f < out.size(); ++f) {
    const double t = (f + 0.5) / 100.0;
    for (const auto& p : seq)
      if (t >= p.start && t < p.end) {
        out[f] = p.phone == "SIL" ? 0 : is_vowel(p.phone) ? 1 : 2;
        break;
      }
  }
  return out;
}

double agreement(const std::vector<int>& a, const std::vector<int>& b) {
  size_t same = 0;
  const size_t n = std::min(a.size(), b.size());
  for (size_t i = 0; i < n; ++i) same += a[i] == b[i];
  return n ? double(same) / double(n) : 0.0;
}

// Free recognition of synthetic speech gets many phones wrong, but it should still find the
// vowels, consonants and silences where the alignment puts them: about 80% of the frames agree
// (answering "vowel" everywhere would agree on about 45%, a phone sequence shifted by 0.25 s on
// about 45%).
TEST_F(Espeak, RecognitionAgreesWithTheAlignmentInBroadClass) {
  const PhoneSeq rec = recognize_phones(*audio_);
  expect_covers(rec, audio_->seconds());
  const auto phones = speech_phones(rec);
  EXPECT_GE(phones.size(), 8u);
  EXPECT_TRUE(std::any_of(phones.begin(), phones.end(), [](auto& p) { return is_vowel(p); }));
  EXPECT_TRUE(std::any_of(phones.begin(), phones.end(), [](auto& p) { return !is_vowel(p); }));
  const double agree =
      agreement(frame_classes(aligned(), audio_->seconds()), frame_classes(rec, audio_->seconds()));
  EXPECT_GE(agree, 0.6);
}

TEST_F(Espeak, AlignmentCanUseGivenPronunciations) {
  const std::string text = "Bob may buy big mapz";
  EXPECT_TRUE(contains(error_of([&] { align_phones(*audio_, text); }), "'mapz'"));
  RecognizerOptions o;
  o.pronunciations["mapz"] = {"M AE P S"};
  EXPECT_EQ(speech_phones(align_phones(*audio_, text, o)),
            split("B AA B M EY B AY B IH G M AE P S"));
}

TEST_F(Espeak, AlignmentOfATranscriptTooLongForTheAudioFails) {
  Audio part = *audio_;
  part.samples.resize(kSampleRate /
                      4);  // 25 frames; the transcript has 43 phones of 3 frames or more
  const std::string msg = error_of(
      [&] { align_phones(part, "Bob may buy big maps and many more maps to map the bumpy moor"); });
  EXPECT_TRUE(contains(msg, "could not be aligned")) << msg;
}

// ---------------------------------------------------------------------------------------------
// A real recording (pocketsphinx's own test file), when ../shared/data is there.

TEST(RealSpeech, GoForwardTenMeters) {
  const fs::path dir = testing::shared_data_dir();
  const fs::path wav = dir / "speech-samples" / "goforward.wav";
  if (dir.empty() || !fs::exists(wav))
    GTEST_SKIP() << "no ../shared/data/speech-samples/goforward.wav";
  const Audio audio = audio::load_audio(wav);
  const PhoneSeq seq = align_phones(audio, "go forward ten meters");
  EXPECT_EQ(speech_phones(seq), split("G OW F AO R W ER D T EH N M IY T ER Z"));
  expect_covers(seq, audio.seconds());
  // The recording has silence at both ends: the speech lies inside it.
  ASSERT_EQ(seq.front().phone, "SIL");
  ASSERT_EQ(seq.back().phone, "SIL");
  const double speech_start = seq.front().end, speech_end = seq.back().start;
  EXPECT_GT(speech_start, 0.1);
  EXPECT_LT(speech_end, audio.seconds() - 0.1);
  EXPECT_GT(speech_end - speech_start, 1.0);
}

// ---------------------------------------------------------------------------------------------
// The command.

std::string G() { return testing::cli_path().string(); }

TEST(PhonesCommand, MissingAudioGivesAClearError) {
  TempDir t;
  const std::string missing = (t / "missing.wav").string();
  std::string out;
  EXPECT_NE(run_command(G() + " phones " + missing, &out), 0);
  EXPECT_TRUE(contains(out, missing)) << out;
  EXPECT_TRUE(contains(out, "error")) << out;
  EXPECT_FALSE(contains(out, "INFO")) << out;
}

TEST_F(Espeak, CommandAlignsToAPhoneFile) {
  const std::string out_path = (*dir_ / "bob.phones").string();
  std::string out;
  ASSERT_EQ(run_command(fmt::format("{} phones '{}' --text '{}' -o '{}'", G(), wav_.string(),
                                    kSentence, out_path),
                        &out),
            0)
      << out;
  EXPECT_FALSE(contains(out, "INFO")) << out;  // pocketsphinx's log stays quiet
  const PhoneSeq seq = read_phone_file(out_path);
  EXPECT_EQ(speech_phones(seq), speech_phones(aligned()));
  // A word the dictionary lacks, with its pronunciation given.
  const std::string oov =
      fmt::format("{} phones '{}' --text 'Bob may buy big mapz'", G(), wav_.string());
  ASSERT_EQ(run_command(oov + " --pron 'mapz=M AE1 P S'", &out), 0) << out;
  EXPECT_TRUE(contains(out, " P\n")) << out;
}

}  // namespace
}  // namespace glossa::phones
