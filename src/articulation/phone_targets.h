#pragma once
// Articulatory targets of every ARPAbet phone and of silence, from articulatory phonetics:
// place and manner for consonants, height / backness / rounding for vowels, with the jaw
// coupled to vowel height. Each target says how strongly the phone needs each parameter
// (its dominance, after Cohen & Massaro 1993): a bilabial needs its lips and leaves the
// tongue to its neighbours; a vowel needs its tongue body and jaw.
#include <optional>
#include <string_view>
#include <vector>

#include "articulation/vocal_tract.h"

namespace glossa::articulation {

// Dominance levels.
inline constexpr double kClosure = 5.0;   // a consonant's constriction: it must be reached
inline constexpr double kCritical = 1.0;  // the phone is defined by this articulator
inline constexpr double kActive = 0.35;   // the phone shapes it but tolerates coarticulation
inline constexpr double kFree = 0.04;     // the phone leaves it to its neighbours

struct Target {
  Params value{};
  std::array<double, kParamCount> dominance{};
  // Where the tongue tip must be (head-frame x, z; mm), when the phone places it absolutely
  // (alveolar, dental, post-alveolar, retroflex). It overrides value[kTipFront/kTipUp].
  std::optional<std::pair<double, double>> tip_at;
  // Lip targets of rounded phones reach further ahead (anticipatory rounding).
  bool rounded = false;
};

// The targets of a phone: one, or two for a diphthong (start, end). Throws glossa::Error for a
// symbol that is not ARPAbet.
std::vector<Target> phone_targets(std::string_view phone);

}  // namespace glossa::articulation
