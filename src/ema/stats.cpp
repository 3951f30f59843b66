#include "ema/stats.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <fmt/format.h>

namespace glossa::ema {

CorpusStats compute_stats(const Corpus& corpus) {
  const size_t L = corpus.landmark_set().size();
  CorpusStats s;
  s.sensors.resize(L);
  std::vector<std::vector<float>> speeds(L);
  std::vector<std::array<double, 3>> sum(L, {0, 0, 0}), sq(L, {0, 0, 0});
  size_t frames = 0;
  s.shortest = std::numeric_limits<double>::infinity();
  for (size_t l = 0; l < L; ++l) {
    s.sensors[l].name = corpus.landmark_set().names[l];
    for (int k = 0; k < 3; ++k) {
      s.sensors[l].min[k] = std::numeric_limits<double>::infinity();
      s.sensors[l].max[k] = -std::numeric_limits<double>::infinity();
    }
  }
  for (const auto& u : corpus.utterances()) {
    const LandmarkSeq seq = corpus.load_landmarks(u);
    const RowVec& neutral = corpus.speaker(u.speaker).neutral;
    const auto& P = seq.positions;
    for (Eigen::Index f = 0; f < P.rows(); ++f) {
      for (size_t l = 0; l < L; ++l) {
        for (int k = 0; k < 3; ++k) {
          const double v = P(f, 3 * l + k);
          s.sensors[l].min[k] = std::min(s.sensors[l].min[k], v);
          s.sensors[l].max[k] = std::max(s.sensors[l].max[k], v);
          const double d = v - neutral(3 * l + k);
          sum[l][k] += d;
          sq[l][k] += d * d;
        }
        if (f > 0)
          speeds[l].push_back(static_cast<float>(
              (P.block(f, 3 * l, 1, 3) - P.block(f - 1, 3 * l, 1, 3)).norm() * kFrameRate));
      }
    }
    frames += static_cast<size_t>(P.rows());
    auto& sp = s.speakers[u.speaker];
    sp.first += 1;
    sp.second += u.seconds;
    s.seconds += u.seconds;
    s.shortest = std::min(s.shortest, u.seconds);
    s.longest = std::max(s.longest, u.seconds);
    ++s.utterances;
  }
  for (size_t l = 0; l < L; ++l) {
    auto& v = speeds[l];
    auto& ss = s.sensors[l];
    for (int k = 0; k < 3; ++k) {
      const double m = sum[l][k] / double(std::max<size_t>(frames, 1));
      ss.std_displacement[k] = std::sqrt(std::max(0.0, sq[l][k] / double(std::max<size_t>(frames, 1)) - m * m));
    }
    if (v.empty()) continue;
    double total = 0;
    for (float x : v) total += x;
    ss.mean_speed = total / double(v.size());
    std::sort(v.begin(), v.end());
    ss.p95_speed = v[static_cast<size_t>(0.95 * double(v.size() - 1))];
    ss.max_speed = v.back();
  }
  return s;
}

std::string stats_text(const CorpusStats& s) {
  std::string out = fmt::format("{} utterances, {:.1f} s of speech ({:.2f} to {:.2f} s each)\n",
                                s.utterances, s.seconds, s.shortest, s.longest);
  for (const auto& [id, v] : s.speakers)
    out += fmt::format("  speaker {}: {} utterances, {:.1f} s\n", id, v.first, v.second);
  out += "\nsensor  range x [mm]        range y [mm]        range z [mm]       "
         " sd(disp) x/y/z [mm]  speed mean/p95/max [mm/s]\n";
  for (const auto& x : s.sensors) {
    out += fmt::format("{:<6}", x.name);
    for (int k = 0; k < 3; ++k) out += fmt::format("  {:8.2f}..{:<8.2f}", x.min[k], x.max[k]);
    out += fmt::format("  {:5.2f}/{:5.2f}/{:5.2f}    {:6.1f}/{:6.1f}/{:6.1f}\n",
                       x.std_displacement[0], x.std_displacement[1], x.std_displacement[2],
                       x.mean_speed, x.p95_speed, x.max_speed);
  }
  return out;
}

nlohmann::json stats_json(const CorpusStats& s) {
  nlohmann::json j = {{"utterances", s.utterances}, {"seconds", s.seconds},
                      {"shortest_s", s.shortest},   {"longest_s", s.longest}};
  for (const auto& [id, v] : s.speakers) j["speakers"][id] = {{"utterances", v.first}, {"seconds", v.second}};
  for (const auto& x : s.sensors)
    j["sensors"].push_back({{"name", x.name},
                            {"min_mm", {x.min[0], x.min[1], x.min[2]}},
                            {"max_mm", {x.max[0], x.max[1], x.max[2]}},
                            {"std_displacement_mm",
                             {x.std_displacement[0], x.std_displacement[1], x.std_displacement[2]}},
                            {"speed_mm_s",
                             {{"mean", x.mean_speed}, {"p95", x.p95_speed}, {"max", x.max_speed}}}});
  return j;
}

}  // namespace glossa::ema
