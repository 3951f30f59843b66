// Text-to-speech front end (src/synth/tts.h) on eSpeak NG and Flite: audio format, phones that
// match the CMU pronunciation, phone times that cover the audio and line up with its energy,
// rate and pitch control, voice specs, errors; plus the internals that turn synthesiser events
// into phones (src/synth/engine.h).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "core/error.h"
#include "phones/phone_seq.h"
#include "synth/engine.h"
#include "synth/tts.h"

namespace glossa::synth {
namespace {

using phones::PhoneSeq;

constexpr const char* kCat = "the cat sat on a mat";
constexpr const char* kCatCmu = "DH AH K AE T S AE T AA N AH M AE T";
constexpr const char* kBirch = "The birch canoe slid on the smooth planks.";
constexpr const char* kBirchCmu =
    "DH AH B ER CH K AH N UW S L IH D AA N DH AH S M UW DH P L AE NG K S";

std::vector<std::string> words(const std::string& s) {
  std::istringstream in(s);
  std::vector<std::string> out;
  for (std::string w; in >> w;) out.push_back(w);
  return out;
}

std::string join(const std::vector<std::string>& v) {
  std::string out;
  for (const auto& s : v) out += (out.empty() ? "" : " ") + s;
  return out;
}

size_t edit_distance(const std::vector<std::string>& a, const std::vector<std::string>& b) {
  std::vector<size_t> row(b.size() + 1);
  for (size_t j = 0; j <= b.size(); ++j) row[j] = j;
  for (size_t i = 1; i <= a.size(); ++i) {
    size_t diag = row[0];
    row[0] = i;
    for (size_t j = 1; j <= b.size(); ++j) {
      const size_t up = row[j];
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diag + (a[i - 1] == b[j - 1] ? 0 : 1)});
      diag = up;
    }
  }
  return row[b.size()];
}

std::vector<std::string> speech_phones(const PhoneSeq& seq) {
  std::vector<std::string> out;
  for (const auto& p : seq)
    if (p.phone != "SIL") out.push_back(p.phone);
  return out;
}

size_t sample_at(const Audio& a, double t) {
  return std::min(a.samples.size(), static_cast<size_t>(std::lround(t * a.sample_rate)));
}

double rms(const Audio& a, double from, double to) {
  const size_t b = sample_at(a, from), e = sample_at(a, to);
  if (e <= b) return 0;
  double s = 0;
  for (size_t i = b; i < e; ++i) s += double(a.samples[i]) * a.samples[i];
  return std::sqrt(s / double(e - b));
}

// RMS over all SIL spans and over all phone spans.
void span_energy(const Utterance& u, double* sil, double* speech, double* sil_seconds) {
  double es = 0, ep = 0;
  size_t ns = 0, np = 0;
  for (const auto& p : u.phones) {
    const size_t b = sample_at(u.audio, p.start), e = sample_at(u.audio, p.end);
    double s = 0;
    for (size_t i = b; i < e; ++i) s += double(u.audio.samples[i]) * u.audio.samples[i];
    (p.phone == "SIL" ? es : ep) += s;
    (p.phone == "SIL" ? ns : np) += e - b;
  }
  *sil = ns ? std::sqrt(es / double(ns)) : 0;
  *speech = np ? std::sqrt(ep / double(np)) : 0;
  *sil_seconds = double(ns) / u.audio.sample_rate;
}

// Median F0 (Hz) of the clearly voiced 40 ms frames, by normalised autocorrelation.
double median_f0(const Audio& a) {
  const int w = 640, min_lag = 32, max_lag = 320;  // 50..500 Hz
  std::vector<double> f0;
  for (size_t s = 0; s + w + max_lag < a.samples.size(); s += 320) {
    double e = 0;
    for (int i = 0; i < w; ++i) e += double(a.samples[s + i]) * a.samples[s + i];
    if (e / w < 1e-3) continue;
    double best = 0;
    int best_lag = 0;
    for (int lag = min_lag; lag <= max_lag; ++lag) {
      double c = 0, e2 = 0;
      for (int i = 0; i < w; ++i) {
        c += double(a.samples[s + i]) * a.samples[s + i + lag];
        e2 += double(a.samples[s + i + lag]) * a.samples[s + i + lag];
      }
      c /= std::sqrt(e * e2) + 1e-12;
      if (c > best) best = c, best_lag = lag;
    }
    if (best > 0.6) f0.push_back(double(a.sample_rate) / best_lag);
  }
  if (f0.empty()) return 0;
  std::nth_element(f0.begin(), f0.begin() + long(f0.size() / 2), f0.end());
  return f0[f0.size() / 2];
}

// Everything every utterance must satisfy.
void check_utterance(const Utterance& u, const std::string& what) {
  SCOPED_TRACE(what);
  EXPECT_EQ(u.audio.sample_rate, 16000);
  EXPECT_GT(u.audio.seconds(), 0.5);
  EXPECT_LT(u.audio.seconds(), 5.0);
  EXPECT_GT(rms(u.audio, 0, u.audio.seconds()), 0.01) << "audio is (nearly) silent";
  for (float x : u.audio.samples) ASSERT_TRUE(std::isfinite(x) && std::abs(x) <= 1.0f);
  ASSERT_NO_THROW(phones::validate(u.phones, what));
  ASSERT_FALSE(u.phones.empty());
  EXPECT_EQ(u.phones.front().start, 0.0);
  EXPECT_NEAR(u.phones.back().end, u.audio.seconds(), 1e-9);
  for (size_t i = 0; i < u.phones.size(); ++i) {
    EXPECT_GT(u.phones[i].end, u.phones[i].start) << "phone " << i << " has no duration";
    if (i == 0) continue;
    EXPECT_NEAR(u.phones[i].start, u.phones[i - 1].end, 1e-9) << "gap before phone " << i;
    EXPECT_FALSE(u.phones[i].phone == "SIL" && u.phones[i - 1].phone == "SIL")
        << "adjacent SIL at " << i;
  }
}

// Speech energy lies in the phones, not in the SIL between them: proves the times line up.
void check_energy_alignment(const Utterance& u, const std::string& what) {
  double sil = 0, speech = 0, sil_seconds = 0;
  span_energy(u, &sil, &speech, &sil_seconds);
  if (sil_seconds < 0.01) return;  // no silence to speak of
  EXPECT_GT(speech, 3 * sil) << what << ": RMS in SIL " << sil << ", in phones " << speech;
}

// ---------------------------------------------------------------------------------------------
// Every standard voice.

class StandardVoice : public ::testing::TestWithParam<Voice> {};

// Speaks `text`; its speech phones must be within 3 edits of the CMU pronunciation `cmu`, and
// its energy must fall inside them.
void check_sentence(const Voice& v, const char* text, const char* cmu) {
  const Utterance u = speak(text, v);
  check_utterance(u, describe(v));
  const auto got = speech_phones(u.phones);
  EXPECT_LE(edit_distance(got, words(cmu)), 3u)
      << describe(v) << " said " << join(got) << "; CMU: " << cmu;
  check_energy_alignment(u, describe(v));
}

TEST_P(StandardVoice, SpeaksTheCatSentenceWithAlignedCmuPhones) {
  check_sentence(GetParam(), kCat, kCatCmu);
}

TEST_P(StandardVoice, SpeaksAHarvardSentence) {
  // The non-rhotic RP voice has no R in "birch" (and says [ə] for "the" before a consonant).
  check_sentence(GetParam(), kBirch, kBirchCmu);
}

TEST_P(StandardVoice, RoundTripsThroughTheCompactForm) {
  const Voice& v = GetParam();
  EXPECT_EQ(parse_voice(format_voice(v)), v) << format_voice(v);
}

std::string voice_test_name(const ::testing::TestParamInfo<Voice>& info) {
  std::string s = info.param.engine + "_" + info.param.name;
  for (char& c : s)
    if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
  return s;
}

INSTANTIATE_TEST_SUITE_P(Synth, StandardVoice, ::testing::ValuesIn(standard_voices()),
                         voice_test_name);

TEST(Synth, StandardVoicesAreDistinctAndCoverBothEngines) {
  const auto voices = standard_voices();
  EXPECT_GE(voices.size(), 8u);
  size_t espeak = 0, flite = 0;
  for (size_t i = 0; i < voices.size(); ++i) {
    (voices[i].engine == "espeak" ? espeak : flite)++;
    EXPECT_EQ(voices[i].rate, 1.0);
    EXPECT_EQ(voices[i].pitch, 1.0);
    for (size_t j = 0; j < i; ++j) EXPECT_FALSE(voices[i] == voices[j]) << describe(voices[i]);
  }
  EXPECT_GE(espeak, 4u);
  EXPECT_GE(flite, 3u);
}

// ---------------------------------------------------------------------------------------------
// Each engine.

class Engine : public ::testing::TestWithParam<const char*> {};

Voice engine_voice(const std::string& engine) {
  return engine == "espeak" ? Voice{"espeak", "en-us"} : Voice{"flite", "slt"};
}

TEST_P(Engine, FasterRateGivesAShorterUtteranceWithTheSamePhones) {
  Voice v = engine_voice(GetParam());
  const Utterance normal = speak(kBirch, v);
  v.rate = 1.6;
  const Utterance fast = speak(kBirch, v);
  v.rate = 0.7;
  const Utterance slow = speak(kBirch, v);
  check_utterance(fast, describe(v));
  EXPECT_LT(fast.audio.seconds(), 0.8 * normal.audio.seconds());
  EXPECT_GT(slow.audio.seconds(), 1.2 * normal.audio.seconds());
  EXPECT_EQ(speech_phones(fast.phones), speech_phones(normal.phones));
  EXPECT_EQ(speech_phones(slow.phones), speech_phones(normal.phones));
  check_energy_alignment(fast, "fast");
  check_energy_alignment(slow, "slow");
}

TEST_P(Engine, HigherPitchFactorRaisesF0) {
  Voice v = engine_voice(GetParam());
  v.pitch = 0.7;
  const double low = median_f0(speak(kCat, v).audio);
  v.pitch = 1.4;
  const double high = median_f0(speak(kCat, v).audio);
  EXPECT_GT(low, 50.0);
  EXPECT_GT(high, 1.15 * low) << "F0 " << low << " Hz at pitch 0.7, " << high << " at 1.4";
}

// Both engines add random noise (aspiration, mixed excitation), so repeated calls differ in the
// last bits of the audio and by a sample or so in the times, never in the phones.
void expect_same_utterance(const Utterance& a, const Utterance& b, const std::string& what) {
  EXPECT_NEAR(a.audio.seconds(), b.audio.seconds(), 0.002) << what;
  ASSERT_EQ(a.phones.size(), b.phones.size()) << what;
  for (size_t i = 0; i < a.phones.size(); ++i) {
    EXPECT_EQ(a.phones[i].phone, b.phones[i].phone) << what << " phone " << i;
    EXPECT_NEAR(a.phones[i].start, b.phones[i].start, 0.002) << what << " phone " << i;
  }
}

TEST_P(Engine, RepeatedCallsGiveTheSamePhones) {
  const Voice v = engine_voice(GetParam());
  expect_same_utterance(speak(kCat, v), speak(kCat, v), describe(v));
}

TEST_P(Engine, TextWithoutSpeechIsAnError) {
  const Voice v = engine_voice(GetParam());
  const auto message = [&](const std::string& text) -> std::string {
    try {
      speak(text, v);
    } catch (const Error& e) {
      return e.what();
    }
    return "(no error)";
  };
  EXPECT_NE(message("").find("empty text"), std::string::npos) << message("");
  EXPECT_NE(message(" \t\n").find("empty text"), std::string::npos) << message(" \t\n");
  EXPECT_NE(message("...").find("'...': the text produced no speech"), std::string::npos)
      << message("...");
}

INSTANTIATE_TEST_SUITE_P(Synth, Engine, ::testing::Values("espeak", "flite"));

TEST(Synth, DifferentVoicesGiveDifferentAudio) {
  // Sample-by-sample comparison would prove nothing (both engines add random noise): the voices
  // must differ in duration or in F0.
  const std::vector<Voice> voices = {{"espeak", "en-us"},
                                     {"espeak", "en-us+f2"},
                                     {"flite", "slt"},
                                     {"flite", "kal16"},
                                     {"flite", "awb"}};
  std::vector<double> seconds, f0;
  for (const auto& v : voices) {
    const Utterance u = speak(kCat, v);
    seconds.push_back(u.audio.seconds());
    f0.push_back(median_f0(u.audio));
  }
  for (size_t i = 0; i < voices.size(); ++i)
    for (size_t j = 0; j < i; ++j) {
      const double dur = std::abs(seconds[i] / seconds[j] - 1), pitch = std::abs(f0[i] / f0[j] - 1);
      EXPECT_TRUE(dur > 0.03 || pitch > 0.1)
          << describe(voices[i]) << " vs " << describe(voices[j]) << ": " << seconds[i] << " s, "
          << f0[i] << " Hz vs " << seconds[j] << " s, " << f0[j] << " Hz";
    }
  // Female and male voices differ in pitch.
  EXPECT_GT(f0[1], 1.4 * f0[0]);
  EXPECT_GT(f0[2], 1.4 * f0[3]);
}

// eSpeak reports a stop after its closure; the closure must end up in the stop, so the start of
// each voiceless stop that follows a vowel is (nearly) silent.
TEST(Synth, EspeakStopsIncludeTheirClosure) {
  const Utterance u = speak(kCat, {"espeak", "en-us"});
  size_t checked = 0;
  for (size_t i = 1; i < u.phones.size(); ++i) {
    const auto& p = u.phones[i];
    const auto& prev = u.phones[i - 1];
    if ((p.phone != "K" && p.phone != "T") || !phones::is_vowel(prev.phone)) continue;
    const double closure = rms(u.audio, p.start, p.start + 0.02);
    const double vowel =
        rms(u.audio, (prev.start + prev.end) / 2 - 0.01, (prev.start + prev.end) / 2 + 0.01);
    EXPECT_LT(closure, 0.1 * vowel) << p.phone << " at " << p.start;
    ++checked;
  }
  EXPECT_GE(checked, 3u);
}

// eSpeak folds a post-vocalic l into the vowel (its event has no duration); it must still get
// its own share of time.
TEST(Synth, EspeakKeepsFoldedLiquids) {
  const Utterance u = speak("feel the bell", {"espeak", "en-us"});
  check_utterance(u, "feel the bell");
  size_t ls = 0;
  for (const auto& p : u.phones)
    if (p.phone == "L") {
      ++ls;
      EXPECT_GT(p.end - p.start, 0.02);
    }
  EXPECT_EQ(ls, 2u) << join(speech_phones(u.phones));
}

TEST(Synth, NonRhoticVoiceDropsPostVocalicR) {
  const auto us = speech_phones(speak("far", {"espeak", "en-us"}).phones);
  const auto rp = speech_phones(speak("far", {"espeak", "en-gb-x-rp"}).phones);
  EXPECT_EQ(join(us), "F AA R");
  EXPECT_EQ(join(rp), "F AA");
}

TEST(Synth, ConcurrentCallsAreSafe) {
  const Voice e{"espeak", "en-us"}, f{"flite", "slt"};
  const Utterance ref_e = speak(kCat, e), ref_f = speak(kCat, f);
  std::vector<Utterance> got(4);
  std::vector<std::thread> threads;
  for (size_t i = 0; i < got.size(); ++i)
    threads.emplace_back([&, i] { got[i] = speak(kCat, i % 2 ? f : e); });
  for (auto& t : threads) t.join();
  for (size_t i = 0; i < got.size(); ++i)
    expect_same_utterance(got[i], i % 2 ? ref_f : ref_e, "thread " + std::to_string(i));
}

// ---------------------------------------------------------------------------------------------
// Voice specs.

TEST(Synth, DescribeAndFormat) {
  const Voice v{"espeak", "en-us+m3", 1.1, 0.9};
  EXPECT_EQ(describe(v), "espeak:en-us+m3 rate 1.10 pitch 0.90");
  EXPECT_EQ(format_voice(v), "espeak:en-us+m3@1.1,0.9");
  EXPECT_EQ(format_voice({"flite", "slt"}), "flite:slt");
  EXPECT_EQ(format_voice({"flite", "slt", 1.25}), "flite:slt@1.25");
  EXPECT_EQ(format_voice({"flite", "slt", 1.0, 0.8}), "flite:slt@1,0.8");
}

TEST(Synth, ParseVoiceRoundTripsAndCanonicalises) {
  for (const Voice& v : {Voice{"espeak", "en-us+f2", 1.2, 0.9}, Voice{"espeak", "en", 0.5, 2.0},
                         Voice{"flite", "kal16", 2.5, 0.25}, Voice{"flite", "awb", 1.0 / 1.7, 1.0},
                         Voice{"flite", "rms", 0.8, 1.0}})
    EXPECT_EQ(parse_voice(format_voice(v)), v) << format_voice(v);
  EXPECT_EQ(parse_voice("espeak:EN-US+M3"), (Voice{"espeak", "en-us+m3"}));
  EXPECT_EQ(parse_voice("Flite:SLT@1.5"), (Voice{"flite", "slt", 1.5}));
  EXPECT_EQ(parse_voice("espeak:en-gb-x-rp@0.9,1.1"), (Voice{"espeak", "en-gb-x-rp", 0.9, 1.1}));
}

void expect_error(const std::string& spec, const std::string& needle) {
  try {
    parse_voice(spec);
    ADD_FAILURE() << "expected glossa::Error for '" << spec << "'";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find(needle), std::string::npos)
        << "'" << spec << "': message lacks '" << needle << "': " << e.what();
  }
}

TEST(Synth, ParseVoiceRejectsInvalidSpecs) {
  expect_error("", "engine:name");
  expect_error("slt", "engine:name");
  expect_error(":slt", "engine:name");
  expect_error("espeak:", "engine:name");
  expect_error("festival:kal", "espeak, flite");
  expect_error("flite:kal", "awb, kal16, rms, slt");  // the 8 kHz kal is not linked
  expect_error("flite:slt@fast", "rate 'fast'");
  expect_error("flite:slt@", "rate ''");
  expect_error("flite:slt@1.2,x", "pitch 'x'");
  expect_error("flite:slt@1.2,", "pitch ''");
  expect_error("flite:slt@1.2x", "rate '1.2x'");
  expect_error("flite:slt@nan", "rate 'nan'");
  expect_error("flite:slt@0.1", "rate 0.1 is outside");
  expect_error("flite:slt@1,3", "pitch 3 is outside");
  expect_error("flite:rms@1,1.2", "cannot change pitch");
  expect_error("espeak:de", "en-us");  // English voices only; the message lists them
  expect_error("espeak:mb-en1", "not an English");
  expect_error("espeak:en-us+nosuch", "m3");
}

TEST(Synth, SpeakRejectsInvalidVoices) {
  EXPECT_THROW(speak(kCat, {"festival", "kal"}), Error);
  EXPECT_THROW(speak(kCat, {"espeak", "fr"}), Error);
  EXPECT_THROW(speak(kCat, {"flite", "slt", 10.0}), Error);
  EXPECT_THROW(speak(kCat, {"espeak", "en-us", 1.0, -1.0}), Error);
}

TEST(Synth, VoiceNames) {
  const auto e = voice_names("espeak");
  EXPECT_NE(std::find(e.begin(), e.end(), "en-us"), e.end());
  EXPECT_NE(std::find(e.begin(), e.end(), "+m3"), e.end());
  EXPECT_EQ(voice_names("flite"), (std::vector<std::string>{"awb", "kal16", "rms", "slt"}));
  EXPECT_THROW(voice_names("festival"), Error);
}

// ---------------------------------------------------------------------------------------------
// Internals: eSpeak mnemonics and the marks -> phones conversion.

TEST(SynthInternals, EspeakMnemonicsMapToArpabet) {
  using detail::espeak_to_arpabet;
  using V = std::vector<std::string>;
  EXPECT_EQ(espeak_to_arpabet("D", true, false), V{"DH"});
  EXPECT_EQ(espeak_to_arpabet("@2", true, false), V{"AH"});
  EXPECT_EQ(espeak_to_arpabet("tS", true, false), V{"CH"});
  EXPECT_EQ(espeak_to_arpabet("3:", true, false), V{"ER"});
  EXPECT_EQ(espeak_to_arpabet("3", true, false), V{"ER"});
  EXPECT_EQ(espeak_to_arpabet("3", false, false), V{"AH"});
  EXPECT_EQ(espeak_to_arpabet("A@", true, false), (V{"AA", "R"}));
  EXPECT_EQ(espeak_to_arpabet("A@", false, false), V{"AA"});
  EXPECT_EQ(espeak_to_arpabet("@L", false, false), (V{"AH", "L"}));
  EXPECT_EQ(espeak_to_arpabet("aI3", true, false), (V{"AY", "ER"}));
  EXPECT_EQ(espeak_to_arpabet("aa", true, false), V{"AE"});
  EXPECT_EQ(espeak_to_arpabet("aa", false, true), V{"AA"});
  EXPECT_EQ(espeak_to_arpabet("t#", true, false), V{"T"});
  EXPECT_EQ(espeak_to_arpabet("_:", true, false), V{"SIL"});
  EXPECT_EQ(espeak_to_arpabet("_", true, false), V{"SIL"});
  EXPECT_TRUE(espeak_to_arpabet(";", true, false).empty());
  // Unknown: longest known prefix, else AH for vowels, else no phone of its own.
  EXPECT_EQ(espeak_to_arpabet("oU#", true, false), V{"OW"});
  EXPECT_EQ(espeak_to_arpabet("eI@x", true, false), V{"EY"});
  EXPECT_EQ(espeak_to_arpabet("y:", true, false), V{"AH"});  // [yː]: no near ARPAbet vowel
  EXPECT_TRUE(espeak_to_arpabet("*", true, false).empty());
  EXPECT_TRUE(espeak_to_arpabet("", true, false).empty());
  for (const char* m : {"a",  "E", "I", "i:", "0",  "O:", "U", "u:", "V", "aI", "aU", "OI", "eI",
                        "oU", "T", "S", "Z",  "dZ", "N",  "j", "w",  "r", "l",  "h",  "?",  "x"})
    for (const auto& p : espeak_to_arpabet(m, true, false))
      EXPECT_TRUE(phones::is_arpabet(p)) << m << " -> " << p;
}

TEST(SynthInternals, MarksBecomeContiguousPhones) {
  using detail::Mark;
  const std::vector<Mark> marks = {{{"DH"}, 0.1},  {{"AA", "R"}, 0.2}, {{}, 0.4},
                                   {{"SIL"}, 0.5}, {{"SIL"}, 0.6},     {{"T"}, 0.7}};
  const PhoneSeq seq = detail::marks_to_phones(marks, 1.0, "test");
  ASSERT_EQ(seq.size(), 6u);
  EXPECT_EQ(seq[0].phone, "SIL");  // leading gap
  EXPECT_DOUBLE_EQ(seq[0].end, 0.1);
  EXPECT_EQ(seq[1].phone, "DH");
  EXPECT_EQ(seq[2].phone, "AA");  // 60% of 0.2..0.4
  EXPECT_NEAR(seq[2].end, 0.32, 1e-12);
  EXPECT_EQ(seq[3].phone, "R");  // the rest, plus the phone-less span 0.4..0.5
  EXPECT_DOUBLE_EQ(seq[3].end, 0.5);
  EXPECT_EQ(seq[4].phone, "SIL");  // two SIL marks merged
  EXPECT_DOUBLE_EQ(seq[4].start, 0.5);
  EXPECT_DOUBLE_EQ(seq[4].end, 0.7);
  EXPECT_EQ(seq[5].phone, "T");  // the last phone runs to the end of the audio
  EXPECT_DOUBLE_EQ(seq[5].end, 1.0);
}

TEST(SynthInternals, MarksAreClampedToTheAudio) {
  using detail::Mark;
  // Flite's kal16 ends its last pause after the wave does; marks past the end vanish.
  const PhoneSeq seq = detail::marks_to_phones(
      {{{"SIL"}, 0.0}, {{"K"}, 0.2}, {{"AE"}, 0.5}, {{"SIL"}, 0.9}, {{"SIL"}, 1.3}}, 1.0, "test");
  ASSERT_EQ(seq.size(), 4u);
  EXPECT_EQ(seq.back().phone, "SIL");
  EXPECT_DOUBLE_EQ(seq.back().end, 1.0);
  EXPECT_THROW(detail::marks_to_phones({{{"SIL"}, 0.0}}, 1.0, "test"), Error);
  EXPECT_THROW(detail::marks_to_phones({{{"AA"}, 0.0}}, 0.0, "test"), Error);
}

TEST(SynthInternals, LinkingRMergesIntoTheRColouredVowel) {
  PhoneSeq seq = {{"S", 0, 0.1},    {"ER", 0.1, 0.2}, {"R", 0.2, 0.25}, {"IH", 0.25, 0.3},
                  {"AA", 0.3, 0.4}, {"R", 0.4, 0.45}, {"R", 0.45, 0.5}};
  detail::merge_rhotic_r(seq);
  ASSERT_EQ(seq.size(), 5u);
  EXPECT_EQ(seq[1].phone, "ER");
  EXPECT_DOUBLE_EQ(seq[1].end, 0.25);
  EXPECT_EQ(seq[4].phone, "R");
  EXPECT_DOUBLE_EQ(seq[4].start, 0.4);
  EXPECT_DOUBLE_EQ(seq[4].end, 0.5);
}

TEST(SynthInternals, QuotesLongTextShortly) {
  EXPECT_EQ(detail::quote_text("hi"), "'hi'");
  const std::string long_text(100, 'a');
  EXPECT_EQ(detail::quote_text(long_text), "'" + std::string(60, 'a') + "...'");
  // Never cuts a UTF-8 sequence in two.
  const std::string umlauts = std::string(59, 'a') + "\xc3\xbc" + std::string(10, 'b');
  EXPECT_EQ(detail::quote_text(umlauts), "'" + std::string(59, 'a') + "...'");
}

TEST(SynthInternals, FlitePhonesMapToArpabet) {
  using detail::flite_to_arpabet;
  using V = std::vector<std::string>;
  EXPECT_EQ(flite_to_arpabet("pau"), V{"SIL"});
  EXPECT_EQ(flite_to_arpabet("ax"), V{"AH"});
  EXPECT_EQ(flite_to_arpabet("dh"), V{"DH"});
  EXPECT_EQ(flite_to_arpabet("ng"), V{"NG"});
  EXPECT_EQ(flite_to_arpabet("en"), (V{"AH", "N"}));
  EXPECT_TRUE(flite_to_arpabet("xx").empty());
}

}  // namespace
}  // namespace glossa::synth
