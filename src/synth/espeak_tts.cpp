// eSpeak NG back end. The library is used in synchronous mode with phoneme events: a callback
// collects the 16-bit samples (22050 Hz) and one event per phoneme, whose sample position is
// where eSpeak starts generating that phoneme. eSpeak keeps global state and is not
// thread-safe, so everything here runs under one mutex and the library is initialised once.
//
// eSpeak emits the event of a stop after the stop's closure silence (the "prepause"), so the
// closure would count as part of the previous phone. attach_closures() moves such a stop's start
// back over the quiet stretch right before its event, which is where the closure really is.
#include <espeak-ng/speak_lib.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstring>
#include <map>
#include <mutex>
#include <set>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "audio/resample.h"
#include "core/error.h"
#include "synth/engine.h"

namespace glossa::synth::detail {
namespace {

std::string lower(std::string s) {
  for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

struct PhonemeEvent {
  std::string name;
  long sample = 0;  // position in samples from the start of the message
  int ms = 0;       // the same position in milliseconds (coarser)
};

// What the synth callback collects for one espeak_Synth call.
struct Collector {
  std::vector<short> pcm;
  std::vector<PhonemeEvent> events;
};

// How a voice pronounces the lexical sets whose realisation differs between English accents.
struct Accent {
  bool rhotic = true;
  bool broad_a = false;
};

struct State {
  int sample_rate = 0;
  std::string error;                      // non-empty when initialisation failed
  std::vector<std::string> bases;         // English voice names (languages), lower case
  std::vector<std::string> variants;      // variant names as espeak spells them
  std::map<std::string, Accent> accents;  // by base name
};

std::mutex g_mutex;
Collector* g_collector = nullptr;  // the call in progress (guarded by g_mutex)

int synth_callback(short* wav, int count, espeak_EVENT* events) {
  Collector* c = g_collector;
  if (!c) return 0;
  if (wav && count > 0) c->pcm.insert(c->pcm.end(), wav, wav + count);
  for (espeak_EVENT* e = events; e && e->type != espeakEVENT_LIST_TERMINATED; ++e) {
    if (e->type != espeakEVENT_PHONEME) continue;
    // Up to 8 bytes, zero-terminated only when shorter.
    const size_t len = strnlen(e->id.string, sizeof e->id.string);
    c->events.push_back({std::string(e->id.string, len), e->sample, e->audio_position});
  }
  return 0;  // go on
}

// Collects the English voices and variants espeak knows. mbrola voices are left out: they need
// an external program and do not produce phoneme events the same way.
void list_voices(State& s) {
  std::set<std::string> bases;
  if (const espeak_VOICE** vs = espeak_ListVoices(nullptr)) {
    for (; *vs; ++vs) {
      const espeak_VOICE* v = *vs;
      if (!v->identifier || std::strncmp(v->identifier, "mb/", 3) == 0 || !v->languages) continue;
      // languages: repeated [priority byte][name\0], ended by a zero priority byte.
      for (const char* p = v->languages; *p;) {
        const std::string lang = lower(p + 1);
        p += 1 + std::strlen(p + 1) + 1;
        if (lang == "en" || lang.rfind("en-", 0) == 0) bases.insert(lang);
      }
    }
  }
  s.bases.assign(bases.begin(), bases.end());
  espeak_VOICE spec{};
  spec.languages = "variant";
  if (const espeak_VOICE** vs = espeak_ListVoices(&spec)) {
    for (; *vs; ++vs) {
      const char* id = (*vs)->identifier;
      if (!id) continue;
      const char* slash = std::strrchr(id, '/');
      s.variants.emplace_back(slash ? slash + 1 : id);
    }
  }
  std::sort(s.variants.begin(), s.variants.end(),
            [](const std::string& a, const std::string& b) { return lower(a) < lower(b); });
}

// The engine, initialised on first use. Call with g_mutex held.
State& state() {
  static State s;
  static bool tried = false;
  if (!tried) {
    tried = true;
    // DONT_EXIT: without it espeak calls exit() when its data files are missing.
    const int rate =
        espeak_Initialize(AUDIO_OUTPUT_SYNCHRONOUS, 0, nullptr,
                          espeakINITIALIZE_PHONEME_EVENTS | espeakINITIALIZE_DONT_EXIT);
    if (rate <= 0) {
      s.error = "espeak-ng: initialisation failed (is espeak-ng-data installed?)";
    } else {
      s.sample_rate = rate;
      espeak_SetSynthCallback(synth_callback);
      list_voices(s);
      if (s.bases.empty()) s.error = "espeak-ng: no English voices found";
    }
  }
  if (!s.error.empty()) throw Error(s.error);
  return s;
}

std::string join(const std::vector<std::string>& v) {
  std::string out;
  for (const auto& s : v) out += (out.empty() ? "" : ", ") + s;
  return out;
}

std::string canonical_name(const State& s, const std::string& name) {
  const auto plus = name.find('+');
  const std::string base = lower(name.substr(0, plus));
  const std::string variant = plus == std::string::npos ? "" : name.substr(plus + 1);
  const auto invalid = [&](const std::string& why) {
    return Error(fmt::format(
        "espeak voice '{}': {}; valid voices: {}, each optionally followed by +variant with "
        "variant one of: {}",
        name, why, join(s.bases), join(s.variants)));
  };
  if (std::find(s.bases.begin(), s.bases.end(), base) == s.bases.end())
    throw invalid(fmt::format("'{}' is not an English espeak-ng voice", base));
  if (plus == std::string::npos) return base;
  for (const auto& v : s.variants)
    if (lower(v) == lower(variant)) return base + "+" + v;
  throw invalid(fmt::format("'{}' is not an espeak-ng voice variant", variant));
}

// IPA of one word in the current voice, through espeak's own translator.
std::string ipa_of(const char* word) {
  const void* p = word;
  const char* ipa = espeak_TextToPhonemes(&p, espeakCHARS_UTF8, espeakPHONEMES_IPA);
  return ipa ? ipa : "";
}

Accent accent_of(State& s, const std::string& base) {
  if (auto it = s.accents.find(base); it != s.accents.end()) return it->second;
  if (espeak_SetVoiceByName(base.c_str()) != EE_OK)
    throw Error(fmt::format("espeak-ng: cannot load voice '{}'", base));
  Accent a;
  const std::string car = ipa_of("car");
  a.rhotic = car.find("ɹ") != std::string::npos || car.find('r') != std::string::npos;
  a.broad_a = ipa_of("bath").find("ɑ") != std::string::npos;
  s.accents[base] = a;
  return a;
}

bool is_stop(const std::vector<std::string>& phones) {
  static const std::set<std::string> stops = {"P", "B", "T", "D", "K", "G", "CH", "JH"};
  return !phones.empty() && stops.count(phones.front()) > 0;
}

bool is_pause(const std::vector<std::string>& phones) {
  return phones.empty() || (phones.size() == 1 && phones[0] == "SIL");
}

// eSpeak folds a post-vocalic l into the vowel before it ("adel", "feel"): the vowel's span holds
// both sounds and the l's own event comes at (or a few ms before) the next one. Such a folded
// phone (zero length, or an L/R under 25 ms right after a vowel) gets the last 40% of the
// previous phone's span on top of its own.
void split_folded_phones(std::vector<Mark>& marks, double end_time) {
  constexpr double kZero = 0.003, kShortLiquid = 0.025, kMinSpan = 0.02, kShare = 0.4;
  for (size_t i = 1; i < marks.size(); ++i) {
    const Mark& prev = marks[i - 1];
    const auto& p = marks[i].phones;
    if (is_pause(p) || is_pause(prev.phones)) continue;
    const double own = (i + 1 < marks.size() ? marks[i + 1].start : end_time) - marks[i].start;
    const bool liquid = p.front() == "L" || p.front() == "R";
    const bool folded =
        own <= kZero || (liquid && own < kShortLiquid && phones::is_vowel(prev.phones.back()));
    const double span = marks[i].start - prev.start;
    if (folded && span >= kMinSpan) marks[i].start = prev.start + (1 - kShare) * span;
  }
}

// Moves the start of each stop that follows a speech phone back over the quiet stretch (the
// closure eSpeak generated before the stop's event), measured on 1 ms frames of `pcm`. "Quiet"
// is below 4% of the 95th percentile frame level, so the breath noise of the breathy variants
// (f2, whisper...) still counts as quiet; the last 12 ms before the event may be louder
// (pre-release breath). The previous phone keeps at least 15 ms; a closure is at most 150 ms.
void attach_closures(std::vector<Mark>& marks, const std::vector<short>& pcm, int sample_rate) {
  const int frame = std::max(1, sample_rate / 1000);
  const size_t frames = pcm.size() / static_cast<size_t>(frame);
  if (frames < 10) return;
  std::vector<double> env(frames);
  for (size_t f = 0; f < frames; ++f) {
    double sum = 0;
    for (int k = 0; k < frame; ++k) {
      const double x = pcm[f * frame + k];
      sum += x * x;
    }
    env[f] = std::sqrt(sum / frame);
  }
  std::vector<double> sorted = env;
  const auto p95 = sorted.begin() + static_cast<long>(0.95 * static_cast<double>(frames - 1));
  std::nth_element(sorted.begin(), p95, sorted.end());
  const double quiet = std::max(0.04 * *p95, 2.0);
  constexpr long kGuard = 12, kMinClosure = 5, kMaxClosure = 150, kMinKeep = 15;
  const double frame_s = static_cast<double>(frame) / sample_rate;
  const auto frame_of = [&](double t) { return static_cast<long>(std::floor(t / frame_s)); };

  for (size_t i = 1; i < marks.size(); ++i) {
    if (!is_stop(marks[i].phones) || is_pause(marks[i - 1].phones)) continue;
    const long event = std::min(frame_of(marks[i].start), static_cast<long>(frames));
    const long limit = std::max({frame_of(marks[i - 1].start) + kMinKeep, event - kMaxClosure, 0L});
    long closure = event;
    for (long f = event - 1; f >= limit; --f) {
      if (env[static_cast<size_t>(f)] < quiet) {
        if (closure - f <= 1 || event - f <= kGuard)
          closure = f;
        else
          break;
      } else if (event - f > kGuard) {
        break;
      }
    }
    if (event - closure >= kMinClosure) marks[i].start = static_cast<double>(closure) * frame_s;
  }
}

}  // namespace

std::vector<std::string> espeak_voice_names() {
  std::lock_guard lock(g_mutex);
  const State& s = state();
  std::vector<std::string> out = s.bases;
  for (const auto& v : s.variants) out.push_back("+" + v);
  return out;
}

std::string espeak_canonical_name(const std::string& name) {
  std::lock_guard lock(g_mutex);
  return canonical_name(state(), name);
}

Utterance espeak_speak(const std::string& text, const Voice& voice) {
  std::lock_guard lock(g_mutex);
  State& s = state();
  const std::string name = canonical_name(s, voice.name);
  const Accent accent = accent_of(s, name.substr(0, name.find('+')));
  if (espeak_SetVoiceByName(name.c_str()) != EE_OK)
    throw Error(fmt::format("espeak-ng: cannot load voice '{}'", name));
  const int default_rate = espeak_GetParameter(espeakRATE, 0);
  const long rate = std::lround((default_rate > 0 ? default_rate : espeakRATE_NORMAL) * voice.rate);
  espeak_SetParameter(espeakRATE, static_cast<int>(std::clamp(rate, 80L, 450L)), 0);
  espeak_SetParameter(espeakPITCH,
                      static_cast<int>(std::clamp(std::lround(50 * voice.pitch), 0L, 100L)), 0);

  Collector c;
  g_collector = &c;
  const espeak_ERROR err = espeak_Synth(text.c_str(), text.size() + 1, 0, POS_CHARACTER, 0,
                                        espeakCHARS_UTF8, nullptr, nullptr);
  if (err == EE_OK) espeak_Synchronize();
  g_collector = nullptr;
  const std::string what = fmt::format("espeak-ng ({}) on {}", name, quote_text(text));
  if (err != EE_OK) throw Error(fmt::format("{}: synthesis failed (error {})", what, int(err)));
  if (c.pcm.empty()) throw Error(fmt::format("{}: produced no audio", what));

  const int sr = s.sample_rate;
  const long total = static_cast<long>(c.pcm.size());
  std::vector<Mark> marks;
  marks.reserve(c.events.size());
  for (const auto& e : c.events) {
    // `sample` is exact; fall back to the millisecond position should it ever disagree.
    long at = e.sample;
    if (std::abs(static_cast<double>(at) * 1000.0 / sr - e.ms) > 2.0)
      at = std::lround(static_cast<double>(e.ms) * sr / 1000.0);
    at = std::clamp(at, 0L, total);
    marks.push_back(
        {espeak_to_arpabet(e.name, accent.rhotic, accent.broad_a), static_cast<double>(at) / sr});
  }
  split_folded_phones(marks, static_cast<double>(total) / sr);
  attach_closures(marks, c.pcm, sr);

  Audio raw;
  raw.sample_rate = sr;
  raw.samples.resize(c.pcm.size());
  for (size_t i = 0; i < c.pcm.size(); ++i)
    raw.samples[i] = static_cast<float>(c.pcm[i]) / 32768.0f;
  Utterance u;
  u.audio = sr == kSampleRate ? std::move(raw) : audio::resample(raw, kSampleRate);
  clamp_samples(u.audio);
  u.phones = marks_to_phones(marks, u.audio.seconds(), what);
  merge_rhotic_r(u.phones);
  return u;
}

}  // namespace glossa::synth::detail
