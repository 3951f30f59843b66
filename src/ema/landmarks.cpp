#include "ema/landmarks.h"

#include <map>

namespace glossa {

int LandmarkSet::index_of(std::string_view name) const {
  for (size_t i = 0; i < names.size(); ++i)
    if (names[i] == name) return static_cast<int>(i);
  return -1;
}

std::string LandmarkSet::joined(std::string_view sep) const {
  std::string out;
  for (size_t i = 0; i < names.size(); ++i) {
    if (i) out += sep;
    out += names[i];
  }
  return out;
}

LandmarkSet LandmarkSet::imt22() { return {{"TD", "TB", "BR", "BL", "TT", "UL", "LC", "LL", "LI", "LJ"}}; }

LandmarkSet LandmarkSet::stem7() { return {{"UL", "LL", "LLC", "RLC", "TR", "TM", "TT"}}; }

LandmarkSet LandmarkSet::parse(std::string_view text) {
  LandmarkSet set;
  std::string cur;
  for (char c : text) {
    if (c == ',' || c == ' ' || c == '\t') {
      if (!cur.empty()) set.names.push_back(cur);
      cur.clear();
    } else {
      cur += c;
    }
  }
  if (!cur.empty()) set.names.push_back(cur);
  return set;
}

std::optional<std::string> describe_sensor(std::string_view code) {
  static const std::map<std::string, std::string, std::less<>> names = {
      {"TD", "tongue dorsum"},      {"TB", "tongue blade"},
      {"BR", "tongue blade right"}, {"BL", "tongue blade left"},
      {"TT", "tongue tip"},         {"UL", "upper lip"},
      {"LC", "lip corner"},         {"LL", "lower lip"},
      {"LI", "lower incisors (jaw)"}, {"LJ", "jaw, canine/premolar"},
      {"LLC", "left lip corner"},   {"RLC", "right lip corner"},
      {"TR", "tongue root/back"},   {"TM", "tongue middle"},
      {"REF-UI", "upper incisor reference"}, {"REF-LM", "left mastoid reference"},
      {"REF-RM", "right mastoid reference"},
  };
  auto it = names.find(code);
  if (it == names.end()) return std::nullopt;
  return it->second;
}

}  // namespace glossa
