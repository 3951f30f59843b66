// Flite back end. The phones and their times are Flite's own: the items of the utterance's
// "Segment" relation, each with its name (CMU US phoneset, lower case, "pau" for silence) and
// its "end" time in seconds; a segment starts where the previous one ends. All four linked
// voices synthesise at 16 kHz; anything else would be resampled.
//
// Rate and pitch go through voice features: duration_stretch = default stretch / rate, and
// int_f0_target_mean = default mean * pitch (for the clustergen voices slt/rms/awb the default
// mean is the one in their cg_db). Voices are shared objects whose features persist, so both
// are set again for every call; all calls run under one mutex.
#include <flite.h>
// flite.h must come first: cst_cg.h relies on its declarations and, unlike flite.h, has no
// extern "C" block of its own.
extern "C" {
#include <cst_cg.h>
}

#include <algorithm>
#include <map>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "audio/resample.h"
#include "core/error.h"
#include "synth/engine.h"

extern "C" {
cst_voice* register_cmu_us_slt(const char* voxdir);
cst_voice* register_cmu_us_kal16(const char* voxdir);
cst_voice* register_cmu_us_rms(const char* voxdir);
cst_voice* register_cmu_us_awb(const char* voxdir);
}

namespace glossa::synth::detail {
namespace {

struct FliteVoice {
  cst_voice* voice = nullptr;
  float stretch = 1.0f;  // the voice's own duration_stretch
  float f0_mean = 0;     // its own int_f0_target_mean (0: unknown, use f0_shift)
  bool pitch_ok = true;  // false for voices whose F0 model reads no pitch feature
};

using Register = cst_voice* (*)(const char*);

const std::map<std::string, Register>& registry() {
  static const std::map<std::string, Register> r = {{"awb", register_cmu_us_awb},
                                                    {"kal16", register_cmu_us_kal16},
                                                    {"rms", register_cmu_us_rms},
                                                    {"slt", register_cmu_us_slt}};
  return r;
}

std::mutex g_mutex;

// The registered voice, loaded on first use. Call with g_mutex held.
FliteVoice& flite_voice(const std::string& name) {
  static std::map<std::string, FliteVoice> voices;
  static bool initialised = false;
  if (auto it = voices.find(name); it != voices.end()) return it->second;
  const auto reg = registry().find(name);
  if (reg == registry().end()) {
    std::string valid;
    for (const auto& [n, f] : registry()) valid += (valid.empty() ? "" : ", ") + n;
    throw Error(fmt::format("flite voice '{}' is unknown; valid voices: {}", name, valid));
  }
  if (!initialised) {
    flite_init();
    initialised = true;
  }
  FliteVoice v;
  v.voice = reg->second(nullptr);
  if (!v.voice) throw Error(fmt::format("flite: cannot register voice '{}'", name));
  v.stretch = get_param_float(v.voice->features, "duration_stretch", 1.0f);
  if (v.stretch <= 0) v.stretch = 1.0f;
  if (feat_present(v.voice->features, "int_f0_target_mean")) {
    v.f0_mean = get_param_float(v.voice->features, "int_f0_target_mean", 0.0f);
  } else if (feat_present(v.voice->features, "cg_db")) {
    const cst_cg_db* db = val_cg_db(feat_val(v.voice->features, "cg_db"));
    if (db) v.f0_mean = db->f0_mean;
  }
  // Clustergen voices with a SPAM F0 model (rms) compute F0 from accent trees alone and ignore
  // int_f0_target_mean and f0_shift.
  if (feat_present(v.voice->features, "cg_db")) {
    const cst_cg_db* db = val_cg_db(feat_val(v.voice->features, "cg_db"));
    if (db && db->spamf0) v.pitch_ok = false;
  }
  return voices.emplace(name, v).first->second;
}

struct UtteranceDeleter {
  void operator()(cst_utterance* u) const { delete_utterance(u); }
};

}  // namespace

std::vector<std::string> flite_voice_names() {
  std::vector<std::string> out;
  for (const auto& [name, f] : registry()) out.push_back(name);
  return out;
}

std::vector<std::string> flite_to_arpabet(std::string_view name) {
  static const std::map<std::string_view, std::vector<std::string>> special = {
      {"pau", {"SIL"}}, {"h#", {"SIL"}},     {"brth", {"SIL"}},   {"ssil", {"SIL"}},
      {"ax", {"AH"}},   {"axr", {"ER"}},     {"dx", {"T"}},       {"hv", {"HH"}},
      {"nx", {"N"}},    {"el", {"AH", "L"}}, {"em", {"AH", "M"}}, {"en", {"AH", "N"}},
  };
  if (auto it = special.find(name); it != special.end()) return it->second;
  const std::string p = phones::normalize_phone(name);
  if (p.empty()) return {};
  return {p};
}

void flite_check_pitch(const std::string& name, double pitch) {
  std::lock_guard lock(g_mutex);
  if (pitch != 1.0 && !flite_voice(name).pitch_ok)
    throw Error(fmt::format(
        "flite voice '{}' cannot change pitch (its SPAM F0 model ignores int_f0_target_mean); "
        "use pitch 1",
        name));
}

Utterance flite_speak(const std::string& text, const Voice& voice) {
  flite_check_pitch(voice.name, voice.pitch);
  std::lock_guard lock(g_mutex);
  FliteVoice& v = flite_voice(voice.name);
  const std::string what = fmt::format("flite ({}) on {}", voice.name, quote_text(text));
  flite_feat_set_float(v.voice->features, "duration_stretch",
                       static_cast<float>(v.stretch / voice.rate));
  if (v.f0_mean > 0) {
    flite_feat_set_float(v.voice->features, "int_f0_target_mean",
                         static_cast<float>(v.f0_mean * voice.pitch));
  } else {
    flite_feat_set_float(v.voice->features, "f0_shift", static_cast<float>(voice.pitch));
  }

  std::unique_ptr<cst_utterance, UtteranceDeleter> utt(flite_synth_text(text.c_str(), v.voice));
  if (!utt) throw Error(fmt::format("{}: synthesis failed", what));
  const cst_wave* wave = utt_wave(utt.get());
  if (!wave || cst_wave_num_samples(wave) <= 0 || cst_wave_sample_rate(wave) <= 0)
    throw Error(fmt::format("{}: produced no audio", what));

  Audio raw;
  raw.sample_rate = cst_wave_sample_rate(wave);
  const int channels = std::max(1, cst_wave_num_channels(wave));
  const int n = cst_wave_num_samples(wave);
  raw.samples.resize(static_cast<size_t>(n));
  for (int i = 0; i < n; ++i)  // first channel only
    raw.samples[static_cast<size_t>(i)] =
        static_cast<float>(wave->samples[static_cast<size_t>(i) * channels]) / 32768.0f;

  std::vector<Mark> marks;
  double start = 0;
  cst_relation* segments = utt_relation(utt.get(), "Segment");
  for (cst_item* s = segments ? relation_head(segments) : nullptr; s; s = item_next(s)) {
    const std::string name = item_feat_string(s, "name");
    std::vector<std::string> p = flite_to_arpabet(name);
    if (p.empty()) throw Error(fmt::format("{}: unknown phone '{}'", what, name));
    marks.push_back({std::move(p), start});
    start = std::max(start, static_cast<double>(item_feat_float(s, "end")));
  }

  Utterance u;
  u.audio = raw.sample_rate == kSampleRate ? std::move(raw) : audio::resample(raw, kSampleRate);
  clamp_samples(u.audio);
  u.phones = marks_to_phones(marks, u.audio.seconds(), what);
  return u;
}

}  // namespace glossa::synth::detail
