#pragma once
// Landmark sets (the named sensors of a corpus, in order) and landmark sequences, the value
// type the landmarks stage hands on: positions in mm in the head frame (x back->front,
// y right->left, z bottom->top), one row per frame, columns l*3 + axis.
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "core/matrix.h"

namespace glossa {

struct LandmarkSet {
  std::vector<std::string> names;

  size_t size() const { return names.size(); }
  // Index of `name`, or -1.
  int index_of(std::string_view name) const;
  std::string joined(std::string_view sep = " ") const;
  bool operator==(const LandmarkSet&) const = default;

  // The papers' IMT'22 set: TD TB BR BL TT UL LC LL LI LJ.
  static LandmarkSet imt22();
  // The 7 sensors of STEM-E2VA: UL LL LLC RLC TR TM TT.
  static LandmarkSet stem7();
  // Parses "A B C" or "A,B,C".
  static LandmarkSet parse(std::string_view text);
};

struct LandmarkSeq {
  LandmarkSet set;
  double rate = 50.0;  // frames per second
  MatrixRM positions;  // frames x (3 * set.size()), mm

  size_t frames() const { return static_cast<size_t>(positions.rows()); }
  size_t dims() const { return static_cast<size_t>(positions.cols()); }
  double seconds() const { return rate > 0 ? frames() / rate : 0.0; }
};

// Short human names of the sensors the papers and the corpora use ("TT" -> "tongue tip").
std::optional<std::string> describe_sensor(std::string_view code);

}  // namespace glossa
