#pragma once
// The value type of the phones stage: ARPAbet phones with their times. Produced by speech
// recognition, forced alignment or a synthesiser; consumed by the procedural articulation
// model (articulation/).
#include <string>
#include <string_view>
#include <vector>

namespace glossa::phones {

// One phone: an ARPAbet symbol without stress digits ("AA" .. "ZH") or "SIL" for silence and
// non-speech, from `start` to `end` seconds.
struct TimedPhone {
  std::string phone;
  double start = 0;
  double end = 0;
};

using PhoneSeq = std::vector<TimedPhone>;

// The 39 ARPAbet phones of the CMU dictionary, then "SIL".
const std::vector<std::string>& arpabet();
bool is_arpabet(std::string_view phone);  // one of arpabet(), SIL included
bool is_vowel(std::string_view phone);
// Upper-cases, strips stress digits ("ah0" -> "AH") and maps pocketsphinx's noise and silence
// units (SIL, +NSN+, +SPN+, ...) to "SIL". Returns "" for a symbol that is not ARPAbet.
std::string normalize_phone(std::string_view symbol);

// Throws glossa::Error when times are not finite, go backwards, overlap or a phone is unknown.
// `what` names the source in the message.
void validate(const PhoneSeq& seq, const std::string& what);

// Reads/writes the plain-text form: one "start end PHONE" line per phone (seconds). Writing is
// atomic; reading names the file and line of any error.
PhoneSeq read_phone_file(const std::string& path);
void write_phone_file(const std::string& path, const PhoneSeq& seq);

}  // namespace glossa::phones
