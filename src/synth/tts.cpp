#include "synth/tts.h"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <string>
#include <string_view>
#include <vector>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "core/error.h"
#include "synth/engine.h"

namespace glossa::synth {
namespace {

std::string lower(std::string s) {
  for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

void check_factors(const Voice& v, const std::string& what) {
  if (!std::isfinite(v.rate) || v.rate < kMinRate || v.rate > kMaxRate)
    throw Error(fmt::format("{}: rate {} is outside {}..{}", what, v.rate, kMinRate, kMaxRate));
  if (!std::isfinite(v.pitch) || v.pitch < kMinPitch || v.pitch > kMaxPitch)
    throw Error(fmt::format("{}: pitch {} is outside {}..{}", what, v.pitch, kMinPitch, kMaxPitch));
}

// Checks engine, name and factors; returns the voice with its name in canonical spelling.
Voice checked(Voice v, const std::string& what) {
  v.engine = lower(v.engine);
  if (v.engine == "espeak") {
    v.name = detail::espeak_canonical_name(v.name);
  } else if (v.engine == "flite") {
    const auto names = detail::flite_voice_names();
    const std::string name = lower(v.name);
    if (std::find(names.begin(), names.end(), name) == names.end())
      throw Error(fmt::format("{}: flite voice '{}' is unknown; valid voices: {}", what, v.name,
                              fmt::join(names, ", ")));
    v.name = name;
    check_factors(v, what);
    detail::flite_check_pitch(v.name, v.pitch);
  } else {
    throw Error(
        fmt::format("{}: unknown engine '{}'; valid engines: espeak, flite", what, v.engine));
  }
  check_factors(v, what);
  return v;
}

bool blank(const std::string& s) {
  return std::all_of(s.begin(), s.end(),
                     [](unsigned char c) { return std::isspace(c) || std::iscntrl(c); });
}

bool parse_double(const std::string& s, double* out) {
  if (s.empty()) return false;
  const char* end = s.data() + s.size();
  const auto [ptr, ec] = std::from_chars(s.data(), end, *out);
  return ec == std::errc() && ptr == end && std::isfinite(*out);
}

}  // namespace

namespace detail {

phones::PhoneSeq marks_to_phones(const std::vector<Mark>& marks, double duration,
                                 const std::string& what) {
  if (!(duration > 0)) throw Error(fmt::format("{}: the synthesiser produced no audio", what));
  // Boundaries clamped to the audio and made non-decreasing; mark i spans [b[i], b[i + 1]].
  std::vector<double> b(marks.size() + 1, duration);
  double last = 0;
  for (size_t i = 0; i < marks.size(); ++i) {
    last = std::max(last, std::clamp(marks[i].start, 0.0, duration));
    b[i] = last;
  }
  phones::PhoneSeq seq;
  if (!marks.empty() && b[0] > 0) seq.push_back({"SIL", 0, b[0]});
  if (marks.empty()) seq.push_back({"SIL", 0, duration});
  double pending = -1;  // start of a phone-less span waiting for the next phone
  for (size_t i = 0; i < marks.size(); ++i) {
    const auto& p = marks[i].phones;
    double s = b[i];
    const double e = b[i + 1];
    if (p.empty()) {
      if (!seq.empty())
        seq.back().end = e;
      else
        pending = s;
      continue;
    }
    if (pending >= 0) {
      s = pending;
      pending = -1;
    }
    const double d = e - s;
    for (size_t k = 0; k < p.size(); ++k) {
      // One phone takes the span; several: the first 60%, the others share the rest.
      const double share = p.size() == 1 ? 1.0 : (k == 0 ? 0.6 : 0.4 / double(p.size() - 1));
      const double start = seq.empty() ? 0.0 : std::max(seq.back().end, s);
      const double end = k + 1 == p.size() ? e : std::min(e, start + share * d);
      seq.push_back({p[k], start, end});
    }
  }
  if (pending >= 0 && !seq.empty()) seq.back().end = duration;

  // Drop zero-length phones (only ever produced by clamping to the audio), merge SIL runs.
  phones::PhoneSeq out;
  for (auto& p : seq) {
    if (p.end - p.start <= 1e-9) continue;
    if (!out.empty() && out.back().phone == "SIL" && p.phone == "SIL") {
      out.back().end = p.end;
      continue;
    }
    if (!out.empty()) p.start = out.back().end;  // contiguous
    out.push_back(std::move(p));
  }
  if (out.empty() || std::all_of(out.begin(), out.end(),
                                 [](const phones::TimedPhone& p) { return p.phone == "SIL"; }))
    throw Error(fmt::format("{}: the text produced no speech", what));
  out.front().start = 0;
  out.back().end = duration;
  phones::validate(out, what);
  return out;
}

std::string quote_text(const std::string& text) {
  constexpr size_t kMax = 60;
  if (text.size() <= kMax) return fmt::format("'{}'", text);
  size_t cut = kMax;
  while (cut > 0 && (static_cast<unsigned char>(text[cut]) & 0xC0) == 0x80) --cut;  // UTF-8
  return fmt::format("'{}...'", std::string_view(text).substr(0, cut));
}

void clamp_samples(Audio& audio) {
  for (float& x : audio.samples) x = std::clamp(x, -1.0f, 1.0f);
}

void merge_rhotic_r(phones::PhoneSeq& seq) {
  phones::PhoneSeq out;
  for (auto& p : seq) {
    if (!out.empty() && p.phone == "R" && (out.back().phone == "ER" || out.back().phone == "R")) {
      out.back().end = p.end;
      continue;
    }
    out.push_back(std::move(p));
  }
  seq = std::move(out);
}

}  // namespace detail

Utterance speak(const std::string& text, const Voice& voice) {
  if (blank(text)) throw Error("synth: empty text");
  const Voice v = checked(voice, "synth");
  return v.engine == "espeak" ? detail::espeak_speak(text, v) : detail::flite_speak(text, v);
}

std::vector<Voice> standard_voices() {
  std::vector<Voice> out;
  // eSpeak: the US voice with male, female and Klatt-synthesiser variants, and British RP.
  for (const char* name :
       {"en-us", "en-us+m3", "en-us+m7", "en-us+f2", "en-us+f4", "en-us+klatt4", "en-gb-x-rp"})
    out.push_back({"espeak", name, 1.0, 1.0});
  // Flite: US female (slt), US male (rms), diphone male (kal16), Scottish male (awb).
  for (const char* name : {"slt", "rms", "kal16", "awb"}) out.push_back({"flite", name, 1.0, 1.0});
  return out;
}

std::string describe(const Voice& v) {
  return fmt::format("{}:{} rate {:.2f} pitch {:.2f}", v.engine, v.name, v.rate, v.pitch);
}

std::string format_voice(const Voice& v) {
  std::string out = v.engine + ":" + v.name;
  if (v.rate != 1.0 || v.pitch != 1.0) out += fmt::format("@{}", v.rate);
  if (v.pitch != 1.0) out += fmt::format(",{}", v.pitch);
  return out;
}

Voice parse_voice(const std::string& spec) {
  const std::string what = fmt::format("voice '{}'", spec);
  const std::string form = "expected engine:name[@rate[,pitch]], e.g. espeak:en-us+m3@1.2,0.9";
  const auto colon = spec.find(':');
  if (colon == std::string::npos || colon == 0)
    throw Error(fmt::format("{}: no engine; {}", what, form));
  Voice v;
  v.engine = spec.substr(0, colon);
  const auto at = spec.find('@', colon + 1);
  v.name = spec.substr(colon + 1, at == std::string::npos ? std::string::npos : at - colon - 1);
  if (v.name.empty()) throw Error(fmt::format("{}: no voice name; {}", what, form));
  if (at != std::string::npos) {
    const std::string factors = spec.substr(at + 1);
    const auto comma = factors.find(',');
    const std::string rate = factors.substr(0, comma);
    if (!parse_double(rate, &v.rate))
      throw Error(fmt::format("{}: rate '{}' is not a number; {}", what, rate, form));
    if (comma != std::string::npos) {
      const std::string pitch = factors.substr(comma + 1);
      if (!parse_double(pitch, &v.pitch))
        throw Error(fmt::format("{}: pitch '{}' is not a number; {}", what, pitch, form));
    }
  }
  return checked(v, what);
}

std::vector<std::string> voice_names(const std::string& engine) {
  const std::string e = lower(engine);
  if (e == "espeak") return detail::espeak_voice_names();
  if (e == "flite") return detail::flite_voice_names();
  throw Error(fmt::format("synth: unknown engine '{}'; valid engines: espeak, flite", engine));
}

}  // namespace glossa::synth
