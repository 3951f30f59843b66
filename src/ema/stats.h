#pragma once
// Descriptive statistics of a corpus: per-sensor ranges and speeds, durations per speaker.
// Speeds are frame-to-frame 3D distances times 50 fps (mm/s).
#include <map>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "ema/corpus.h"

namespace glossa::ema {

struct SensorStats {
  std::string name;
  double min[3], max[3];       // absolute, mm
  double std_displacement[3];  // std of displacement from the speaker's neutral, mm
  double mean_speed = 0, p95_speed = 0, max_speed = 0;  // mm/s
};

struct CorpusStats {
  std::vector<SensorStats> sensors;
  std::map<std::string, std::pair<size_t, double>> speakers;  // utterances, seconds
  size_t utterances = 0;
  double seconds = 0, shortest = 0, longest = 0;
};

CorpusStats compute_stats(const Corpus& corpus);
std::string stats_text(const CorpusStats& s);
nlohmann::json stats_json(const CorpusStats& s);

}  // namespace glossa::ema
