#include "articulation/procedural.h"

#include <algorithm>
#include <cmath>

#include "articulation/phone_targets.h"
#include "core/error.h"

namespace glossa::articulation {
namespace {

// Natural frequencies (rad/s) of each parameter's articulator. A critically damped system
// covers 90% of a step in about 3.9 / omega: ~140 ms for the jaw, ~80 ms for the tongue tip.
double omega(int p) {
  switch (p) {
    case kJawOpen:
    case kJawForward:
      return 28;
    case kLipProtrude:
    case kLipSpread:
      return 30;
    case kUpperLipUp:
    case kLowerLipUp:
    case kLowerLipBack:
      return 65;
    case kBodyFront:
    case kBodyUp:
      return 36;
    case kTipFront:
    case kTipUp:
      return 60;
    default:
      return 40;  // tongue edges
  }
}

bool is_lip_param(int p) { return p >= kLipProtrude && p <= kLowerLipBack; }

// One target in time: a phone (or half of a diphthong) from `start` to `end`.
struct Event {
  double start, end;
  Target target;
};

// `tip_rest`: the tongue tip's neutral (x, z), about which absolute tip places are scaled.
std::vector<Event> make_events(const phones::PhoneSeq& seq, double amplitude,
                               const Eigen::Vector2d& tip_rest) {
  std::vector<Event> ev;
  for (const auto& ph : seq) {
    const auto targets = phone_targets(ph.phone);
    const double span = (ph.end - ph.start) / static_cast<double>(targets.size());
    for (size_t i = 0; i < targets.size(); ++i) {
      Event e{ph.start + span * i, ph.start + span * (i + 1), targets[i]};
      for (double& v : e.target.value) v *= amplitude;
      if (e.target.tip_at) {  // scale the tip's place about the rest position too
        const double rx = tip_rest(0), rz = tip_rest(1);
        e.target.tip_at = std::pair{rx + amplitude * (e.target.tip_at->first - rx),
                                    rz + amplitude * (e.target.tip_at->second - rz)};
      }
      ev.push_back(std::move(e));
    }
  }
  return ev;
}

}  // namespace

Articulation articulate(const phones::PhoneSeq& phones, size_t frames,
                        const ProceduralOptions& opt) {
  phones::validate(phones, "phone sequence");
  if (!(opt.rate > 0) || !(opt.speed > 0) || !(opt.reach > 0) || !(opt.rounding_reach > 0) ||
      !(opt.lead >= 0) || !std::isfinite(opt.amplitude))
    throw Error("articulation: rate, speed and reach must be positive");
  const VocalTract tract;
  // Time that no phone covers is silence, held like a SIL phone.
  phones::PhoneSeq covered;
  double at = 0;
  const double span_end =
      std::max(static_cast<double>(frames) / opt.rate, phones.empty() ? 0.0 : phones.back().end);
  for (const auto& ph : phones) {
    if (ph.start > at) covered.push_back({"SIL", at, ph.start});
    covered.push_back(ph);
    at = ph.end;
  }
  if (span_end > at) covered.push_back({"SIL", at, span_end});
  const int tt = 3 * VocalTract::landmark_set().index_of("TT");
  const Eigen::Vector2d tip_rest(tract.neutral()(tt), tract.neutral()(tt + 2));
  const auto events = make_events(covered, opt.amplitude, tip_rest);

  Articulation out;
  out.landmarks.set = VocalTract::landmark_set();
  out.landmarks.rate = opt.rate;
  out.landmarks.positions.resize(static_cast<Eigen::Index>(frames), 30);
  out.params.resize(static_cast<Eigen::Index>(frames), kParamCount);
  if (frames == 0) return out;

  constexpr double dt = 0.001;  // integration step, s
  const double t_end = static_cast<double>(frames - 1) / opt.rate;
  // Blended target at time t; the rest posture holds weakly where no phone reaches.
  // The tongue tip is blended in head-frame position, because places of articulation are
  // absolute (the alveolar ridge does not move with the jaw): a relative tip target becomes a
  // position given where the jaw and body are now (`tip_base`, TT with a zero tip offset).
  auto target_at = [&](double t, const Eigen::Vector2d& tip_base, Params& target) {
    std::array<double, kParamCount> num{}, den{};
    den.fill(1e-3);
    for (const auto& e : events) {
      const double outside = std::max({0.0, e.start - t, t - e.end});
      if (outside > 10 * opt.rounding_reach) continue;
      for (int p = 0; p < kParamCount; ++p) {
        // Constrictions are sharp in time: high dominance, short reach (a /p/ closes the lips
        // for its own duration and releases them); rounding spreads far ahead.
        double reach = is_lip_param(p) && e.target.rounded ? opt.rounding_reach : opt.reach;
        if (e.target.dominance[p] >= kClosure) reach *= 0.25;
        const double d = e.target.dominance[p] * std::exp(-outside / reach);
        double value = e.target.value[p];
        if (p == kTipFront || p == kTipUp) {
          const int axis = p == kTipFront ? 0 : 1;
          value = e.target.tip_at ? (axis ? e.target.tip_at->second : e.target.tip_at->first)
                                  : tip_base(axis) + value;
        }
        num[p] += d * value;
        den[p] += d;
      }
    }
    for (int p = 0; p < kParamCount; ++p) target[p] = num[p] / den[p];
    // Rest (where nothing reaches) is a zero tip offset; then back to an offset.
    target[kTipFront] = (num[kTipFront] + 1e-3 * tip_base(0)) / den[kTipFront] - tip_base(0);
    target[kTipUp] = (num[kTipUp] + 1e-3 * tip_base(1)) / den[kTipUp] - tip_base(1);
  };
  auto tip_base_of = [&](const Params& x) {
    Params untipped = x;
    untipped[kTipFront] = untipped[kTipUp] = 0;
    const RowVec pose = tract.pose(untipped);
    return Eigen::Vector2d(pose(tt), pose(tt + 2));
  };

  Params x{}, v{}, target{};
  target_at(opt.lead, tip_base_of(x), x);  // start on the first target
  x[kTipFront] = x[kTipUp] = 0;
  target_at(opt.lead, tip_base_of(x), x);
  size_t f = 0;
  const auto steps = static_cast<long>(std::ceil(t_end / dt));
  for (long i = 0; i <= steps && f < frames; ++i) {
    const double t = i * dt;
    while (f < frames && static_cast<double>(f) / opt.rate <= t + 1e-9) {
      const RowVec pose = tract.pose(x);
      out.landmarks.positions.row(static_cast<Eigen::Index>(f)) = pose;
      for (int p = 0; p < kParamCount; ++p)
        out.params(static_cast<Eigen::Index>(f), p) = static_cast<float>(x[p]);
      ++f;
    }
    target_at(t + opt.lead, tip_base_of(x), target);
    for (int p = 0; p < kParamCount; ++p) {  // semi-implicit Euler, critically damped
      const double w = omega(p) * opt.speed;
      v[p] += dt * (w * w * (target[p] - x[p]) - 2 * w * v[p]);
      x[p] += dt * v[p];
    }
  }
  return out;
}

}  // namespace glossa::articulation
