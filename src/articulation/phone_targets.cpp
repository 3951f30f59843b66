#include "articulation/phone_targets.h"

#include <map>
#include <string>

#include "core/error.h"
#include "phones/phone_seq.h"

namespace glossa::articulation {
namespace {

// Builds a Target; every parameter starts free at its neutral value.
struct T {
  Target t;
  T() { t.dominance.fill(kFree); }
  T& p(Param k, double v, double d) {
    t.value[k] = v;
    t.dominance[k] = d;
    return *this;
  }
  T& jaw(double open, double d) { return p(kJawOpen, open, d).p(kJawForward, 0, kFree); }
  T& lips(double protrude, double spread, double d) {
    return p(kLipProtrude, protrude, d).p(kLipSpread, spread, d);
  }
  T& lower_lip(double up, double back, double d) {
    return p(kLowerLipUp, up, d).p(kLowerLipBack, back, d);
  }
  T& upper_lip(double up, double d) { return p(kUpperLipUp, up, d); }
  T& body(double front, double up, double d) { return p(kBodyFront, front, d).p(kBodyUp, up, d); }
  T& tip_at(double x, double z, double d) {
    t.tip_at = {x, z};
    t.dominance[kTipFront] = t.dominance[kTipUp] = d;
    return *this;
  }
  T& edges(double down, double d) { return p(kEdgesDown, down, d); }
  T& round() {
    t.rounded = true;
    return *this;
  }
  operator Target() const { return t; }
};

constexpr double X = kClosure, C = kCritical, A = kActive;

// Vowels: the jaw follows height (high 2-4 mm, mid 5-7, low 9-11); the body's front/up offsets
// place the dorsum in the vowel quadrilateral; rounding protrudes and narrows the lips. The
// tongue edges rest raised against the upper molars in most vowels.
Target vowel(double jaw, double front, double up, double protrude, double spread,
             double dominance = C) {
  T v;
  v.jaw(jaw, dominance).body(front, up, dominance).edges(-1.5, A);
  v.lower_lip(0, 0, C).upper_lip(0, A);  // a vowel needs its lips apart
  // The tip rests low behind the lower incisors, lowest in front vowels.
  v.p(kTipFront, 0, A).p(kTipUp, front > 2 ? -4 : -1.5, A);
  v.lips(protrude, spread, protrude > 0 ? dominance : A);
  if (protrude > 0) v.round();
  return v;
}

std::map<std::string, std::vector<Target>> make_table() {
  std::map<std::string, std::vector<Target>> m;
  // Monophthongs.
  m["IY"] = {vowel(2.5, 7, 9, 0, 3)};
  m["IH"] = {vowel(4, 5, 6, 0, 2)};
  m["EH"] = {vowel(6, 4, 2, 0, 1.5)};
  m["AE"] = {vowel(10, 3, -3, 0, 2.5)};
  m["AA"] = {vowel(11, -6, -6, 0, 0)};
  m["AO"] = {vowel(9, -8, -3, 2.5, -2.5)};
  m["AH"] = {vowel(7, -1, -2, 0, 0, A)};  // schwa / wedge: reduced, yields to neighbours
  m["UH"] = {vowel(4, -5, 4, 3, -3)};
  m["UW"] = {vowel(3, -7, 7, 5, -5)};
  // ER: bunched/retroflex r-colouring: tip raised and drawn back, some lip rounding.
  Target er = T().jaw(5, C).body(-3, 4, C).tip_at(-17, 8, A).lips(2.5, -2, A).round();
  m["ER"] = {er};
  // Diphthongs: onset then offset target.
  m["EY"] = {vowel(5, 5, 4, 0, 2), vowel(3, 6, 8, 0, 3)};
  m["AY"] = {vowel(11, -5, -5, 0, 0), vowel(4, 6, 7, 0, 2)};
  m["AW"] = {vowel(11, -4, -5, 0, 0), vowel(4, -7, 5, 4, -4)};
  m["OW"] = {vowel(7, -7, -1, 3, -3), vowel(4, -7, 5, 4.5, -4.5)};
  m["OY"] = {vowel(8, -8, -2, 3, -3), vowel(4, 6, 7, 0, 1)};

  // Bilabials: the lower lip rises past contact (the lips press), the jaw helps.
  for (const char* s : {"P", "B", "M"})
    m[s] = {T().lower_lip(12, 0, X).upper_lip(-1, C).jaw(2, 0.6)};
  // Labiodentals: lower lip up and back under the upper incisors.
  for (const char* s : {"F", "V"}) m[s] = {T().lower_lip(6, 6, X).upper_lip(1, A).jaw(2, 0.6)};
  // Dentals: tip between or just behind the incisal edges.
  for (const char* s : {"TH", "DH"}) m[s] = {T().tip_at(1.0, -1.5, X).jaw(3, A)};
  // Alveolar stops and nasal: the tip aims past the alveolar ridge (closure), edges sealed.
  for (const char* s : {"T", "D", "N"}) m[s] = {T().tip_at(-9.5, 12, X).jaw(2.5, X).edges(-1.5, A)};
  // Alveolar fricatives: close approach (a ~1.5 mm channel), high jaw, grooved tongue.
  for (const char* s : {"S", "Z"})
    m[s] = {T().tip_at(-8, 6, X).jaw(1, X).edges(-3.5, C).lips(0, 1, A)};
  // Post-alveolar fricatives: blade towards the post-alveolar region, lips rounded/protruded.
  for (const char* s : {"SH", "ZH"})
    m[s] = {T().tip_at(-14, 9.5, X)
                .body(0, 3, A)
                .lips(3.5, -2.5, C)
                .jaw(1.5, C)
                .edges(-2.5, A)
                .round()};
  // Affricates: post-alveolar closure released into the fricative; one target at the closure.
  for (const char* s : {"CH", "JH"})
    m[s] = {T().tip_at(-12, 14, X).body(0, 3, A).lips(3, -2, C).jaw(1.5, C).edges(-2, A).round()};
  // Lateral: apical alveolar contact with the sides lowered; dark /l/ backs the body.
  m["L"] = {T().tip_at(-9, 12, X).edges(5, C).body(-3, -1, A).jaw(4, A)};
  // /r/: tip raised and retracted (retroflex/bunched), body raised, lips rounded.
  m["R"] = {T().tip_at(-17, 8, X).body(-3, 3, A).lips(3, -2.5, A).jaw(3, A).round()};
  // Velars: the dorsum rises past the velum (closure).
  for (const char* s : {"K", "G", "NG"}) m[s] = {T().body(-4, 16, X).jaw(3, A)};
  // Glides: /w/ a rounded, labial-velar /u/; /j/ a palatal /i/.
  m["W"] = {T().lips(5, -5, X).lower_lip(3, 0, A).body(-7, 6, A).jaw(2, A).round()};
  m["Y"] = {T().body(7, 10, X).jaw(2, A).lips(0, 2, A)};
  // /h/: the glottis only; the mouth takes its neighbours' shape.
  m["HH"] = {T().jaw(4, kFree)};
  // Silence: the rest posture, weakly held, so that neighbours spread into short pauses.
  {
    T sil;
    sil.t.dominance.fill(0.3);
    m["SIL"] = {sil};
  }
  return m;
}

}  // namespace

std::vector<Target> phone_targets(std::string_view phone) {
  static const auto table = make_table();
  auto it = table.find(std::string(phone));
  if (it == table.end())
    throw Error("articulation: '" + std::string(phone) + "' is not an ARPAbet phone");
  return it->second;
}

}  // namespace glossa::articulation
