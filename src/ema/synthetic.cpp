#include "ema/synthetic.h"

#include <cmath>
#include <random>

#include <nlohmann/json.hpp>

#include "audio/decode.h"
#include "core/error.h"
#include "ema/landmarks.h"
#include "io/atomic_file.h"
#include "io/npy.h"

namespace glossa::ema {
namespace fs = std::filesystem;

namespace {

constexpr double kEmaRate = 250.0;
constexpr int kAudioRate = 16000;

struct Controls {  // all in [0, 1]
  double height, backness, aperture, rounding, voicing;
};

// One text: a sequence of articulatory targets with durations.
struct Target {
  Controls c;
  double seconds;
};

std::vector<Target> make_text(std::mt19937_64& rng, double seconds) {
  std::uniform_real_distribution<double> u(0, 1), dur(0.09, 0.22);
  std::vector<Target> t;
  t.push_back({{0.5, 0.5, 0.0, 0.2, 0.0}, 0.25});  // leading silence, lips closed
  double total = 0.25;
  while (total < seconds - 0.3) {
    Controls c{u(rng), u(rng), 0.15 + 0.85 * u(rng), u(rng) < 0.3 ? 0.8 : 0.1 * u(rng), 1.0};
    if (u(rng) < 0.15) c = {0.4, 0.5, 0.0, 0.2, 0.0};  // a closure (like /p b m/)
    const double d = dur(rng);
    t.push_back({c, d});
    total += d;
  }
  t.push_back({{0.5, 0.5, 0.0, 0.2, 0.0}, 0.3});
  return t;
}

// Second-order smoothing of the piecewise-constant targets at 250 Hz (critically damped,
// ~40 ms time constant), like articulators approaching targets.
std::vector<Controls> trajectory(const std::vector<Target>& text, double tempo) {
  std::vector<Controls> raw;
  for (const auto& t : text) {
    const int n = std::max(1, static_cast<int>(std::round(t.seconds * tempo * kEmaRate)));
    for (int i = 0; i < n; ++i) raw.push_back(t.c);
  }
  std::vector<Controls> out(raw.size());
  const double a = std::exp(-1.0 / (0.04 * kEmaRate));
  Controls s1 = raw.front(), s2 = raw.front();
  for (size_t i = 0; i < raw.size(); ++i) {
    auto step = [&](double Controls::*f) {
      s1.*f = a * (s1.*f) + (1 - a) * (raw[i].*f);
      s2.*f = a * (s2.*f) + (1 - a) * (s1.*f);
    };
    for (auto f : {&Controls::height, &Controls::backness, &Controls::aperture,
                   &Controls::rounding, &Controls::voicing})
      step(f);
    out[i] = s2;
  }
  return out;
}

// Sensor positions (mm, head frame) of the 10-sensor set for given controls.
void pose(const Controls& c, const Eigen::Vector3f& origin, float* out) {
  const float jaw = static_cast<float>(0.6 * c.aperture + 0.4 * (1 - c.height));  // 0 closed
  const float h = static_cast<float>(c.height), b = static_cast<float>(c.backness);
  const float r = static_cast<float>(c.rounding);
  const float tongue_drop = 6.f * jaw;
  const float pts[10][3] = {
      {-35.f - 6.f * b, 0, -12.f + 10.f * h - tongue_drop},            // TD
      {-22.f - 5.f * b, 0, -10.f + 8.f * h - tongue_drop},             // TB
      {-22.f - 5.f * b, -8.f + 2.f * h, -13.f + 6.f * h - tongue_drop},  // BR
      {-22.f - 5.f * b, 8.f - 2.f * h, -13.f + 6.f * h - tongue_drop},   // BL
      {-8.f - 6.f * b, 0, -12.f + 7.f * h * (1 - b) - tongue_drop},    // TT
      {12.f + 4.f * r, 0, 8.f + 1.5f * jaw},                            // UL
      {8.f - 3.f * r, -24.f + 6.f * r, -6.f - 3.f * jaw},               // LC
      {11.f + 4.f * r - 2.f * jaw, 0, -14.f - 12.f * jaw},              // LL
      {2.f - 3.f * jaw, 0, -16.f - 11.f * jaw},                         // LI
      {-18.f - 2.f * jaw, 20.f, -20.f - 8.f * jaw},                     // LJ
  };
  for (int l = 0; l < 10; ++l)
    for (int k = 0; k < 3; ++k) out[3 * l + k] = pts[l][k] + origin[k];
}

// Two-pole resonator with time-varying centre frequency and bandwidth.
struct Resonator {
  double y1 = 0, y2 = 0;
  double step(double x, double f, double bw) {
    const double r = std::exp(-M_PI * bw / kAudioRate);
    const double a1 = 2 * r * std::cos(2 * M_PI * f / kAudioRate), a2 = -r * r;
    const double y = (1 - r) * x + a1 * y1 + a2 * y2;
    y2 = y1;
    y1 = y;
    return y;
  }
};

std::vector<float> voice(const std::vector<Controls>& traj, double f0, std::mt19937_64& rng) {
  const size_t n = static_cast<size_t>(traj.size() * kAudioRate / kEmaRate);
  std::vector<float> out(n);
  std::normal_distribution<double> noise(0, 1);
  Resonator r1, r2, r3;
  double phase = 0;
  for (size_t i = 0; i < n; ++i) {
    const double pos = i * kEmaRate / kAudioRate;
    const size_t k = std::min(traj.size() - 1, static_cast<size_t>(pos));
    const size_t k2 = std::min(traj.size() - 1, k + 1);
    const double w = pos - k;
    auto lerp = [&](double Controls::*f) { return (1 - w) * (traj[k].*f) + w * (traj[k2].*f); };
    const double h = lerp(&Controls::height), b = lerp(&Controls::backness);
    const double ap = lerp(&Controls::aperture), ro = lerp(&Controls::rounding);
    const double vo = lerp(&Controls::voicing);
    const double F1 = 250 + 550 * (1 - h) * (0.4 + 0.6 * ap);
    const double F2 = 850 + 1400 * (1 - b) - 350 * ro;
    const double F3 = 2300 + 500 * (1 - ro) + 200 * h;
    phase += f0 * (1 + 0.05 * std::sin(2 * M_PI * 3 * i / kAudioRate)) / kAudioRate;
    double src = 0;
    if (phase >= 1) {
      phase -= 1;
      src = 1;
    }
    const double excitation = vo * src * 40 + 0.02 * noise(rng) * (0.3 + ap);
    double y = r1.step(excitation, F1, 80) + 0.6 * r2.step(excitation, F2, 120) +
               0.3 * r3.step(excitation, F3, 180);
    out[i] = static_cast<float>(0.5 * y * (0.15 + 0.85 * ap) + 0.0005 * noise(rng));
  }
  return out;
}

}  // namespace

void write_synthetic_source(const fs::path& dir, const SyntheticOptions& opt) {
  if (opt.speakers < 1 || opt.texts < 1 || opt.takes < 1 || opt.seconds < 0.5)
    throw Error("synthetic corpus: need at least 1 speaker, text and take, and 0.5 s");
  fs::create_directories(dir);
  std::mt19937_64 rng(opt.seed);
  std::vector<std::vector<Target>> texts;
  for (int t = 0; t < opt.texts; ++t) texts.push_back(make_text(rng, opt.seconds));
  const LandmarkSet set = LandmarkSet::imt22();
  nlohmann::json meta = {
      {"name", "glossa synthetic demo corpus"},
      {"ema",
       {{"sample_rate_hz", kEmaRate},
        {"units", "mm"},
        {"axes", "x back->front, y right->left, z bottom->top"}}},
      {"speakers", nlohmann::json::object()}};
  for (const auto& n : set.names) meta["ema"]["sensors"].push_back({{"code", n}});
  std::uniform_real_distribution<double> u(0, 1);
  for (int s = 0; s < opt.speakers; ++s) {
    const std::string spk = fmt::format("S{:02}", s + 1);
    meta["speakers"][spk] = {{"synthetic", true}};
    // Speakers differ in origin (tens of mm), pitch and speaking rate.
    const Eigen::Vector3f origin(static_cast<float>(40 * s + 10 * u(rng)),
                                 static_cast<float>(5 * u(rng)),
                                 static_cast<float>(-30 * s - 10 * u(rng)));
    const double f0 = 100 + 90 * s + 20 * u(rng);
    for (int t = 0; t < opt.texts; ++t) {
      for (int k = 0; k < opt.takes; ++k) {
        const double tempo = 0.85 + 0.3 * u(rng);
        const auto traj = trajectory(texts[t], tempo);
        const std::string id = fmt::format("{}T{}{:02}", spk, k + 1, t + 1);
        std::vector<float> ema(traj.size() * 30);
        for (size_t i = 0; i < traj.size(); ++i) pose(traj[i], origin, &ema[i * 30]);
        io::write_npy(dir / (id + ".npy"), ema.data(), {traj.size(), 10, 3});
        Audio a;
        a.sample_rate = kAudioRate;
        a.samples = voice(traj, f0, rng);
        audio::write_wav(dir / (id + ".wav"), a);
      }
    }
  }
  io::write_file_atomic(dir / "meta.json", meta.dump(1));
}

}  // namespace glossa::ema
