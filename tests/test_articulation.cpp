// The procedural articulation model: phonetic constraints that must hold on its trajectories.
#include <gtest/gtest.h>

#include "articulation/phone_targets.h"
#include "articulation/procedural.h"
#include "core/error.h"

namespace glossa::articulation {
namespace {

using phones::PhoneSeq;

PhoneSeq sequence(const std::vector<std::pair<std::string, double>>& spec) {
  PhoneSeq s;
  double t = 0;
  for (const auto& [p, d] : spec) {
    s.push_back({p, t, t + d});
    t += d;
  }
  return s;
}

// The pose at the middle of phone i.
RowVec mid(const Articulation& a, const PhoneSeq& s, size_t i) {
  const double t = 0.5 * (s[i].start + s[i].end);
  return a.landmarks.positions.row(static_cast<Eigen::Index>(std::lround(t * 50)));
}

double coord(const RowVec& pose, const char* sensor, int axis) {
  return pose(3 * VocalTract::landmark_set().index_of(sensor) + axis);
}

bool is_vowel(const std::string& p) { return phones::is_vowel(p); }

size_t frames_of(const PhoneSeq& s) { return static_cast<size_t>(s.back().end * 50) + 1; }

TEST(Articulation, ClosuresAreReached) {
  const auto s = sequence({{"SIL", 0.2},
                           {"AA", 0.14},
                           {"P", 0.08},
                           {"IY", 0.14},
                           {"B", 0.07},
                           {"AE", 0.14},
                           {"M", 0.07},
                           {"AA", 0.14},
                           {"T", 0.07},
                           {"AA", 0.14},
                           {"D", 0.06},
                           {"IY", 0.14},
                           {"K", 0.08},
                           {"AA", 0.14},
                           {"N", 0.07},
                           {"UW", 0.14},
                           {"G", 0.07},
                           {"AA", 0.14},
                           {"SIL", 0.2}});
  const auto a = articulate(s, frames_of(s));
  for (size_t i = 0; i < s.size(); ++i) {
    const RowVec p = mid(a, s, i);
    const std::string& ph = s[i].phone;
    if (ph == "P" || ph == "B" || ph == "M") EXPECT_EQ(VocalTract::lip_aperture(p), 0.0) << i;
    if (ph == "T" || ph == "D" || ph == "N") EXPECT_LT(VocalTract::tip_clearance(p), 0.2) << i;
    if (ph == "K" || ph == "G") EXPECT_LT(VocalTract::dorsum_clearance(p), 0.2) << i;
    if (is_vowel(ph)) EXPECT_GT(VocalTract::lip_aperture(p), 1.5) << ph << " " << i;
    if (ph == "AA") EXPECT_GT(VocalTract::tip_clearance(p), 5.0) << i;
  }
}

TEST(Articulation, VowelsFollowHeightBacknessAndRounding) {
  const auto s = sequence({{"SIL", 0.2},
                           {"IY", 0.25},
                           {"SIL", 0.3},
                           {"AA", 0.25},
                           {"SIL", 0.3},
                           {"UW", 0.25},
                           {"SIL", 0.2}});
  const auto a = articulate(s, frames_of(s));
  const RowVec iy = mid(a, s, 1), aa = mid(a, s, 3), uw = mid(a, s, 5);
  const RowVec rest = VocalTract().neutral();
  // The jaw opens most for the low vowel; the dorsum is higher for /i/ and /u/ than /a/.
  EXPECT_LT(coord(aa, "LI", 2), coord(iy, "LI", 2) - 4);
  EXPECT_GT(coord(iy, "TD", 2), coord(aa, "TD", 2) + 6);
  EXPECT_GT(coord(uw, "TD", 2), coord(aa, "TD", 2) + 6);
  // /i/ is front, /u/ back; /u/ protrudes the lips and draws the corners in, /i/ spreads them.
  EXPECT_GT(coord(iy, "TB", 0), coord(uw, "TB", 0) + 6);
  EXPECT_GT(coord(uw, "UL", 0), coord(rest, "UL", 0) + 3);
  EXPECT_GT(coord(uw, "LC", 1), coord(rest, "LC", 1) + 3);  // LC is right (y < 0): inwards
  EXPECT_LT(coord(iy, "LC", 1), coord(rest, "LC", 1) - 1.5);
}

TEST(Articulation, LateralLowersTheTongueEdges) {
  const auto s = sequence({{"AA", 0.15}, {"L", 0.1}, {"AA", 0.15}, {"T", 0.1}, {"AA", 0.15}});
  const auto a = articulate(s, frames_of(s));
  const RowVec l = mid(a, s, 1), t = mid(a, s, 3);
  const double l_drop = coord(l, "TB", 2) - 0.5 * (coord(l, "BL", 2) + coord(l, "BR", 2));
  const double t_drop = coord(t, "TB", 2) - 0.5 * (coord(t, "BL", 2) + coord(t, "BR", 2));
  EXPECT_GT(l_drop, t_drop + 3);
}

TEST(Articulation, SmoothBoundedAndRestingInSilence) {
  PhoneSeq s;
  double t = 0.3;
  const std::vector<std::string> ph = {"DH", "AH", "K",  "AE", "T", "S",  "AE", "T",
                                       "AA", "N",  "DH", "AH", "M", "AE", "T"};
  for (const auto& p : ph) {
    s.push_back({p, t, t + 0.06});  // fast speech
    t += 0.06;
  }
  const size_t frames = static_cast<size_t>((t + 0.6) * 50);
  const auto a = articulate(s, frames);
  const auto& P = a.landmarks.positions;
  ASSERT_EQ(P.rows(), static_cast<Eigen::Index>(frames));
  ASSERT_EQ(P.cols(), 30);
  ASSERT_TRUE(P.allFinite());
  const double max_speed =
      ((P.bottomRows(P.rows() - 1) - P.topRows(P.rows() - 1)) * 50.0).cwiseAbs().maxCoeff();
  EXPECT_LT(max_speed, 700.0);  // mm/s per axis; EMA peaks are ~500 (bench/RESULTS.md)
  EXPECT_GT(max_speed, 50.0);
  // Long silence at both ends: back at the neutral pose.
  const RowVec rest = VocalTract().neutral();
  EXPECT_LT((P.row(0) - rest).cwiseAbs().maxCoeff(), 1.0);
  EXPECT_LT((P.row(P.rows() - 1) - rest).cwiseAbs().maxCoeff(), 1.0);
}

TEST(Articulation, EveryArpabetPhoneHasTargets) {
  for (const auto& p : phones::arpabet()) EXPECT_FALSE(phone_targets(p).empty()) << p;
  EXPECT_THROW(phone_targets("QX"), Error);
}

TEST(Articulation, RefusesBadPhoneSequences) {
  EXPECT_THROW(articulate({{"QX", 0, 0.1}}, 10), Error);
  EXPECT_THROW(articulate({{"AA", 0, 0.2}, {"T", 0.1, 0.3}}, 20), Error);  // overlap
  EXPECT_THROW(articulate({{"AA", 0.2, 0.1}}, 20), Error);                 // backwards
  EXPECT_EQ(articulate({}, 5).landmarks.positions.rows(), 5);              // all silence
}

}  // namespace
}  // namespace glossa::articulation
