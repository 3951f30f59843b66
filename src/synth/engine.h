#pragma once
// Internals shared by the synthesiser back ends (espeak_tts.cpp, flite_tts.cpp) and tts.cpp.
// Keeps the engines' own headers out of everything else.
#include <string>
#include <string_view>
#include <vector>

#include "phones/phone_seq.h"
#include "synth/tts.h"

namespace glossa::synth::detail {

// One phone event of a synthesiser: the phones it stands for (ARPAbet or "SIL"), starting at
// `start` seconds and lasting until the next mark starts (the last one until the audio ends).
// Several phones share the span (the first gets 60%, the rest share 40%); no phones means "this
// span belongs to the previous phone" (or to the next one when there is no previous one).
struct Mark {
  std::vector<std::string> phones;
  double start = 0;
};

// Turns marks into a contiguous phone sequence covering [0, duration]: a leading gap becomes
// SIL, marks are clamped to the audio, zero-length phones are dropped, adjacent SIL merged.
// Throws glossa::Error (prefixed with `what`) when the result is invalid or holds no speech.
phones::PhoneSeq marks_to_phones(const std::vector<Mark>& marks, double duration,
                                 const std::string& what);

// `text` for an error message: quoted, cut after 60 bytes.
std::string quote_text(const std::string& text);

// Clips samples to [-1, 1] (resampling a full-scale 16-bit signal can overshoot slightly).
void clamp_samples(Audio& audio);

// Merges an R that directly follows ER or R into that phone (espeak writes the linking r of
// "censoring" as its own phoneme after the r-coloured vowel; CMU writes ER alone).
void merge_rhotic_r(phones::PhoneSeq& seq);

// eSpeak NG English phoneme mnemonic -> ARPAbet phones ("SIL" for pauses; empty = the span
// belongs to the previous phone). `rhotic`: the voice pronounces post-vocalic r ("car" with
// [ɹ]); `broad_a`: the voice says "bath" with [ɑː].
std::vector<std::string> espeak_to_arpabet(std::string_view mnemonic, bool rhotic, bool broad_a);

// Flite (CMU US phoneset) phone name -> ARPAbet phones; empty when the name is unknown.
std::vector<std::string> flite_to_arpabet(std::string_view name);

Utterance espeak_speak(const std::string& text, const Voice& voice);
Utterance flite_speak(const std::string& text, const Voice& voice);

// Canonical spelling of an espeak voice name ("EN-US+M3" -> "en-us+m3"); throws glossa::Error
// listing the valid names when it is not an English espeak voice.
std::string espeak_canonical_name(const std::string& name);
std::vector<std::string> espeak_voice_names();
std::vector<std::string> flite_voice_names();
// Throws glossa::Error when `pitch` is not 1 and the flite voice cannot change its pitch (rms).
void flite_check_pitch(const std::string& name, double pitch);

}  // namespace glossa::synth::detail
