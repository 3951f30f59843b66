#pragma once
// A small articulatory model of an average adult vocal tract, in the head frame of DESIGN.md
// (mm; x back->front, y right->left, z bottom->top; origin at the upper incisal edge). A handful
// of articulatory parameters (jaw, lips, tongue body, tongue tip, tongue edges) place the
// papers' ten EMA sensors, TD TB BR BL TT UL LC LL LI LJ. The jaw rotates about the condyle and
// carries the lower lip and, in part, the tongue; the tongue and lower lip cannot pass through
// the palate and the upper lip, so a target beyond a contact ends in contact (a closure).
#include <array>

#include "core/matrix.h"
#include "ema/landmarks.h"

namespace glossa::articulation {

// Articulatory parameters; 0 is the neutral (rest) posture. Lengths in mm.
enum Param : int {
  kJawOpen,       // lower-incisor drop by rotation about the condyle (+ opens)
  kJawForward,    // jaw protrusion (+ forward)
  kLipProtrude,   // both lips and the corners forward (+), as in rounding
  kLipSpread,     // corners outward (+) or drawn together (-, rounding)
  kUpperLipUp,    // upper lip raise (+ up)
  kLowerLipUp,    // lower lip raise relative to the jaw (+ up, towards closure)
  kLowerLipBack,  // lower lip drawn back under the upper incisors (+), labiodentals
  kBodyFront,     // tongue body forward (+) / back (-) relative to the jaw
  kBodyUp,        // tongue body up (+) / down (-) relative to the jaw
  kTipFront,      // tongue tip forward (+) relative to where the body puts it
  kTipUp,         // tongue tip up (+)
  kEdgesDown,     // tongue lateral edges lowered (+, /l/) or raised into a groove (-, /s/)
  kParamCount
};

using Params = std::array<double, kParamCount>;

const char* param_name(int p);

// Where the tongue and the lips touch: the midsagittal palate height, and contact thresholds.
struct Contacts {
  // Height of the palate surface (z, mm) above head-frame point x; incisors, alveolar ridge,
  // hard palate and velum, smoothly joined.
  static double palate_z(double x);
  static constexpr double kTongueSensorDepth = 1.5;  // sensor below the tongue surface at contact
  static constexpr double kLipsClosedGap = 9.0;      // UL.z - LL.z when the lips just touch
};

class VocalTract {
 public:
  VocalTract();
  static const LandmarkSet& landmark_set();  // LandmarkSet::imt22()

  // The neutral pose: 30 values (10 sensors x xyz), mm.
  const RowVec& neutral() const { return neutral_; }
  // Sensor positions for the parameters, contacts applied. Row of 30 values.
  RowVec pose(const Params& p) const;
  // Vertical gap between the lips beyond touching (mm, >= 0; 0 = closed) for a pose.
  static double lip_aperture(const RowVec& pose);
  // Tongue-tip distance below the palate (mm, >= 0; 0 = contact) for a pose.
  static double tip_clearance(const RowVec& pose);
  static double dorsum_clearance(const RowVec& pose);

 private:
  RowVec neutral_;
};

}  // namespace glossa::articulation
