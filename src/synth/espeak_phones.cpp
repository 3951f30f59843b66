// eSpeak NG English phoneme mnemonics -> ARPAbet.
//
// eSpeak names its English phonemes by lexical set rather than by sound ("A@" is the vowel of
// START whatever the accent makes of it), so the table has a rhotic and a non-rhotic column: a
// rhotic voice (en-us: "car" = [kɑːɹ]) gets the r-coloured vowels as vowel + R like the CMU
// dictionary, a non-rhotic one (en-gb-x-rp: [kɑː]) gets the bare vowel. Which column a voice
// uses is decided by asking eSpeak for the IPA of "car" (see espeak_tts.cpp).
//
// Known approximations (the ARPAbet set has no closer symbol):
//   t# (flap [ɾ]) -> T, ? (glottal stop) -> T, x ([x] of "loch") -> K, t[ / d[ (dental stops
//   of en-029 "th") -> TH / DH, O2 ([ɔ] of en-us "on") -> AO where CMU often has AA,
//   3: ([ɜː]) -> ER also for non-rhotic voices, "aa" (BATH) -> AE unless the voice says "bath"
//   with [ɑː] (then AA), i ("happy") -> IY, I# ([ᵻ]) -> IH, a# ([ɐ]) -> AH.
// Syllabic consonants and the centring diphthongs become two phones sharing the span, as in CMU
// spelling: @L -> AH L, n- -> AH N, i@ -> IY AH, aI@ -> AY AH, A@ -> AA R (rhotic) ...
// ";" (eSpeak's palatal linking glide between a front vowel and the next vowel) has no phone of
// its own: its time goes to the previous phone. Pauses ("_", "_:", "_!", ...) are SIL.
// An unknown mnemonic is looked up by its longest known prefix ("oU#" -> "oU"); failing that a
// vowel-looking one becomes AH and anything else gives its time to the previous phone, so no
// span of speech is ever dropped.
#include <sstream>
#include <string>
#include <string_view>
#include <unordered_map>
#include <vector>

#include "synth/engine.h"

namespace glossa::synth::detail {
namespace {

struct Entry {
  std::string_view rhotic;      // ARPAbet phones separated by spaces
  std::string_view non_rhotic;  // empty: same as `rhotic`
};

const std::unordered_map<std::string_view, Entry>& table() {
  static const std::unordered_map<std::string_view, Entry> t = {
      // Consonants.
      {"p", {"P", ""}},
      {"b", {"B", ""}},
      {"t", {"T", ""}},
      {"d", {"D", ""}},
      {"k", {"K", ""}},
      {"g", {"G", ""}},
      {"f", {"F", ""}},
      {"v", {"V", ""}},
      {"T", {"TH", ""}},
      {"D", {"DH", ""}},
      {"s", {"S", ""}},
      {"z", {"Z", ""}},
      {"S", {"SH", ""}},
      {"Z", {"ZH", ""}},
      {"h", {"HH", ""}},
      {"m", {"M", ""}},
      {"n", {"N", ""}},
      {"N", {"NG", ""}},
      {"l", {"L", ""}},
      {"r", {"R", ""}},
      {"w", {"W", ""}},
      {"j", {"Y", ""}},
      {"tS", {"CH", ""}},
      {"dZ", {"JH", ""}},
      {"t#", {"T", ""}},     // flap [ɾ] ("water")
      {"d#", {"D", ""}},     // voiced flap
      {"t2", {"T", ""}},     // t after s ("abbotstown")
      {"d2", {"D", ""}},     //
      {"t[", {"TH", ""}},    // dental stop for "th" (en-029)
      {"d[", {"DH", ""}},    //
      {"?", {"T", ""}},      // glottal stop ("cotton" [kɑʔn̩])
      {"x", {"K", ""}},      // velar fricative ("loch", "Bach")
      {"C", {"HH", ""}},     // palatal fricative
      {"r-", {"R", ""}},     // linking r
      {"l/", {"L", ""}},     // dark l
      {"w#", {"W", ""}},     // voiceless w [ʍ] (Scottish "wh")
      {"n-", {"AH N", ""}},  // syllabic n
      {"m-", {"AH M", ""}},  // syllabic m
      {"@L", {"AH L", ""}},  // syllabic l ("able")
      {"l-", {"AH L", ""}},  //
      // Vowels.
      {"a", {"AE", ""}},
      {"aa", {"AE", ""}},  // BATH; AA for broad-a voices (handled below)
      {"a#", {"AH", ""}},  // [ɐ]
      {"A:", {"AA", ""}},
      {"A", {"AA", ""}},
      {"A@", {"AA R", "AA"}},  // START
      {"0", {"AA", ""}},       // LOT
      {"O:", {"AO", ""}},
      {"O", {"AO", ""}},
      {"O2", {"AO", ""}},
      {"O@", {"AO R", "AO"}},  // NORTH
      {"o@", {"AO R", "AO"}},  // FORCE
      {"oU", {"OW", ""}},
      {"o:", {"OW", ""}},
      {"o", {"OW", ""}},
      {"V", {"AH", ""}},
      {"@", {"AH", ""}},
      {"@2", {"AH", ""}},
      {"@5", {"AH", ""}},
      {"@-", {"AH", ""}},
      {"3", {"ER", "AH"}},  // lettER: [ɚ] or [ə]
      {"3:", {"ER", ""}},   // NURSE
      {"E", {"EH", ""}},
      {"e", {"EH", ""}},
      {"e@", {"EH R", "EH"}},  // SQUARE
      {"eI", {"EY", ""}},
      {"I", {"IH", ""}},
      {"I2", {"IH", ""}},
      {"I#", {"IH", ""}},  // [ᵻ] ("-ed", "-es")
      {"i", {"IY", ""}},   // happY
      {"i:", {"IY", ""}},
      {"i@", {"IY AH", ""}},       // [iə] ("idea", "-ian")
      {"i@3", {"IH R", "IH AH"}},  // NEAR
      {"U", {"UH", ""}},
      {"U@", {"UH R", "UH AH"}},  // CURE
      {"u:", {"UW", ""}},
      {"u", {"UW", ""}},
      {"aI", {"AY", ""}},
      {"aI2", {"AY", ""}},
      {"aI@", {"AY AH", ""}},       // [aɪə] ("diet")
      {"aI3", {"AY ER", "AY AH"}},  // "fire"
      {"aU", {"AW", ""}},
      {"aU@", {"AW ER", "AW AH"}},  // "hour"
      {"OI", {"OY", ""}},
      {"IR", {"ER", ""}},  // Scottish [əɹ] ("bird")
      {"VR", {"ER", ""}},  // Scottish [ʌɹ] ("word")
      // No phone of its own: the span goes to the previous phone.
      {";", {"", ""}},
  };
  return t;
}

std::vector<std::string> split(std::string_view s) {
  std::vector<std::string> out;
  std::istringstream in{std::string(s)};
  for (std::string w; in >> w;) out.push_back(w);
  return out;
}

bool looks_like_vowel(char c) {
  return std::string_view("aeiouyAEIOUVY@03").find(c) != std::string_view::npos;
}

}  // namespace

std::vector<std::string> espeak_to_arpabet(std::string_view mnemonic, bool rhotic, bool broad_a) {
  if (mnemonic.empty()) return {};
  if (mnemonic.front() == '_') return {"SIL"};
  if (mnemonic == "aa" && broad_a) return {"AA"};
  const auto& t = table();
  for (std::string_view m = mnemonic; !m.empty(); m.remove_suffix(1)) {
    const auto it = t.find(m);
    if (it == t.end()) continue;
    const Entry& e = it->second;
    return split(!rhotic && !e.non_rhotic.empty() ? e.non_rhotic : e.rhotic);
  }
  if (looks_like_vowel(mnemonic.front())) return {"AH"};
  return {};
}

}  // namespace glossa::synth::detail
