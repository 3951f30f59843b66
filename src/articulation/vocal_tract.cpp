#include "articulation/vocal_tract.h"

#include <algorithm>
#include <cmath>

#include <Eigen/Geometry>

namespace glossa::articulation {
namespace {

using Vec3 = Eigen::Vector3d;

// Sensor order of LandmarkSet::imt22().
enum Sensor { TD, TB, BR, BL, TT, UL, LC, LL, LI, LJ, kSensors };

// Rest positions of an average adult male (mm, head frame). Anatomical sources: the upper
// incisal edge is the origin; lips ~12 mm in front of it; the lower incisors just behind and
// below it with the teeth ~2 mm apart; EMA tongue coils ~10 (TT), ~27 (TB) and ~43 mm (TD)
// behind the tongue tip; blade-edge coils 13 mm either side of the midline; LC on the right
// (y < 0) and LJ on the left (y > 0) as in the papers' corpus.
const std::array<Vec3, kSensors> kRest = {{
    {-44.0, 0.0, -1.0},    // TD
    {-28.0, 0.0, 0.0},     // TB
    {-25.0, -13.0, -4.0},  // BR
    {-25.0, 13.0, -4.0},   // BL
    {-11.0, 0.0, -6.0},    // TT
    {12.0, 0.0, 4.0},      // UL
    {2.0, -24.0, -6.0},    // LC
    {11.0, 0.0, -6.0},     // LL
    {-3.0, 0.0, -11.0},    // LI
    {-14.0, 20.0, -15.0},  // LJ
}};

// The mandibular condyle, about which the jaw rotates when it opens.
const Vec3 kCondyle{-88.0, 0.0, 22.0};

// Share of the jaw's motion each tongue sensor follows, and of the body and tip parameters.
struct TongueWeights {
  double jaw, body, tip;
};
const std::array<TongueWeights, kSensors> kTongue = {{
    {0.45, 1.0, 0.0},   // TD
    {0.55, 1.0, 0.3},   // TB
    {0.55, 0.9, 0.25},  // BR
    {0.55, 0.9, 0.25},  // BL
    {0.7, 0.6, 1.0},    // TT
}};

// Palate profile (x, z): front of the incisors, incisal edge, back of the incisors, alveolar
// ridge, post-alveolar, hard-palate dome, velum.
const std::array<std::pair<double, double>, 8> kPalate = {{{8.0, -1.0},
                                                           {0.0, 0.0},
                                                           {-4.0, 5.0},
                                                           {-9.0, 9.0},
                                                           {-16.0, 13.0},
                                                           {-28.0, 16.0},
                                                           {-42.0, 14.0},
                                                           {-56.0, 9.0}}};

Vec3 get(const RowVec& r, int s) { return {r(3 * s), r(3 * s + 1), r(3 * s + 2)}; }
void set(RowVec& r, int s, const Vec3& v) {
  for (int a = 0; a < 3; ++a) r(3 * s + a) = static_cast<float>(v(a));
}

}  // namespace

const char* param_name(int p) {
  static const char* names[kParamCount] = {
      "jaw_open",       "jaw_forward", "lip_protrude", "lip_spread", "upper_lip_up", "lower_lip_up",
      "lower_lip_back", "body_front",  "body_up",      "tip_front",  "tip_up",       "edges_down"};
  return p >= 0 && p < kParamCount ? names[p] : "?";
}

double Contacts::palate_z(double x) {
  if (x >= kPalate.front().first) return kPalate.front().second;
  if (x <= kPalate.back().first) return kPalate.back().second;
  for (size_t i = 1; i < kPalate.size(); ++i) {
    const auto [x1, z1] = kPalate[i];
    const auto [x0, z0] = kPalate[i - 1];
    if (x >= x1) {
      const double u = (x0 - x) / (x0 - x1);
      const double s = u * u * (3 - 2 * u);  // smoothstep: no kinks at the joints
      return z0 + (z1 - z0) * s;
    }
  }
  return kPalate.back().second;
}

const LandmarkSet& VocalTract::landmark_set() {
  static const LandmarkSet s = LandmarkSet::imt22();
  return s;
}

VocalTract::VocalTract() { neutral_ = pose(Params{}); }

RowVec VocalTract::pose(const Params& p) const {
  RowVec out(3 * kSensors);
  // Jaw: rotation about the condyle (y axis) that drops the lower incisor by jaw_open mm.
  const Vec3 li_arm = kRest[LI] - kCondyle;
  const double theta = p[kJawOpen] / li_arm.norm();  // small-angle arc length
  const Eigen::Matrix3d rot = Eigen::AngleAxisd(theta, Vec3::UnitY()).toRotationMatrix();
  const Vec3 protrude{p[kJawForward], 0, 0};
  auto jaw = [&](const Vec3& rest) { return Vec3(kCondyle + rot * (rest - kCondyle) + protrude); };

  set(out, LI, jaw(kRest[LI]));
  set(out, LJ, jaw(kRest[LJ]));

  // Lips. Rounding draws the corners forward and together; spreading pulls them out and back.
  const double protr = p[kLipProtrude];
  Vec3 ul = kRest[UL] + Vec3(protr, 0, p[kUpperLipUp]);
  Vec3 ll = jaw(kRest[LL]) + Vec3(protr - p[kLowerLipBack], 0, p[kLowerLipUp]);
  // The lower lip cannot rise through the upper one: beyond touching, the lips press together
  // (a little compression) and the lower lip stops.
  const double overlap = ll.z() - (ul.z() - Contacts::kLipsClosedGap);
  if (overlap > 0) ll.z() -= 0.85 * overlap;
  // A lower lip drawn back tucks under the upper incisors (labiodental): not behind them.
  ll.x() = std::max(ll.x(), 1.5);
  set(out, UL, ul);
  set(out, LL, ll);
  const Vec3 lc_jaw = jaw(kRest[LC]);
  const double spread = p[kLipSpread];
  Vec3 lc = kRest[LC] + 0.5 * (lc_jaw - kRest[LC]);  // corners follow half the jaw drop
  lc += Vec3(0.6 * protr - 0.25 * std::max(spread, 0.0), -spread, 0.3 * p[kUpperLipUp]);
  set(out, LC, lc);

  // Tongue: carried in part by the jaw, moved by body and tip, kept below the palate.
  const Vec3 body{p[kBodyFront], 0, p[kBodyUp]};
  const Vec3 tip{p[kTipFront], 0, p[kTipUp]};
  for (int s : {TD, TB, BR, BL, TT}) {
    const auto& w = kTongue[s];
    Vec3 v = kRest[s] + w.jaw * (jaw(kRest[s]) - kRest[s]) + w.body * body + w.tip * tip;
    if (s == BR || s == BL) {
      v.z() -= p[kEdgesDown];
      v.y() *= 1.0 - 0.03 * std::max(p[kEdgesDown], 0.0);  // a lateral /l/ narrows the blade
    }
    const double lateral = (s == BR || s == BL) ? 3.0 : 0.0;  // the palate is lower at the sides
    const double roof = Contacts::palate_z(v.x()) - lateral - Contacts::kTongueSensorDepth;
    if (v.z() > roof) v.z() = roof;
    set(out, s, v);
  }
  return out;
}

double VocalTract::lip_aperture(const RowVec& pose) {
  return std::max(0.0, double(pose(3 * UL + 2) - pose(3 * LL + 2)) - Contacts::kLipsClosedGap);
}

double VocalTract::tip_clearance(const RowVec& pose) {
  const Vec3 t = get(pose, TT);
  return std::max(0.0, Contacts::palate_z(t.x()) - Contacts::kTongueSensorDepth - t.z());
}

double VocalTract::dorsum_clearance(const RowVec& pose) {
  const Vec3 t = get(pose, TD);
  return std::max(0.0, Contacts::palate_z(t.x()) - Contacts::kTongueSensorDepth - t.z());
}

}  // namespace glossa::articulation
