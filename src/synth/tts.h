#pragma once
// Text-to-speech front end for building a bootstrap training corpus: speaks English text with
// eSpeak NG or Flite and returns the audio (16 kHz mono) together with the ARPAbet phones the
// synthesiser itself produced, timed by the synthesiser (not by a recogniser or aligner).
//
// Both engines keep global state, so every call is serialised by a per-engine mutex; calls from
// several threads are safe but do not run in parallel.
#include <string>
#include <vector>

#include "audio/audio.h"
#include "phones/phone_seq.h"

namespace glossa::synth {

// Rate and pitch factors outside these ranges are refused (glossa::Error).
inline constexpr double kMinRate = 0.5;
inline constexpr double kMaxRate = 2.5;
inline constexpr double kMinPitch = 0.25;
inline constexpr double kMaxPitch = 2.0;

struct Voice {
  std::string engine;  // "espeak" | "flite"
  // espeak: an English voice, optionally with a variant, e.g. "en-us", "en-us+m3", "en+f2",
  // "en-gb-x-rp". flite: "slt", "kal16", "rms" or "awb".
  std::string name;
  double rate = 1.0;   // speaking-rate factor (1 = the engine's default; 2 = twice as fast)
  double pitch = 1.0;  // pitch factor (espeak: pitch parameter 50 * pitch, clamped to 0..100;
                       // flite: scales the voice's int_f0_target_mean; flite "rms" ignores
                       // that feature, so it only takes pitch 1)

  bool operator==(const Voice&) const = default;
};

struct Utterance {
  Audio audio;              // 16 kHz mono float in [-1, 1]
  phones::PhoneSeq phones;  // ARPAbet + SIL, contiguous, covering [0, audio.seconds()]
};

// Speaks `text` (UTF-8). Throws glossa::Error for empty text, an unknown engine or voice (the
// message lists the valid names), a rate or pitch out of range, a synthesiser failure, or text
// that produces no speech at all.
Utterance speak(const std::string& text, const Voice& voice);

// A default list of distinct English voices of both engines, all at rate 1 and pitch 1.
std::vector<Voice> standard_voices();

// Human-readable form, e.g. "espeak:en-us+m3 rate 1.10 pitch 0.90".
std::string describe(const Voice& voice);

// Compact form "engine:name[@rate[,pitch]]", e.g. "flite:slt", "espeak:en-us+f2@1.2,0.9".
// Rate and pitch are written only when they differ from 1, with enough digits to round-trip.
std::string format_voice(const Voice& voice);

// Inverse of format_voice. Checks the engine, the voice name (against the engine's voices) and
// the rate and pitch ranges; throws glossa::Error naming the problem when the spec is invalid.
Voice parse_voice(const std::string& spec);

// The voice names an engine accepts ("espeak": English base voices and "+variant" names;
// "flite": the linked voices). Throws glossa::Error for an unknown engine.
std::vector<std::string> voice_names(const std::string& engine);

}  // namespace glossa::synth
