#pragma once
// Runs predictors over a corpus' test utterances and collects one results row per predictor.
#include <string>
#include <vector>

#include "ema/corpus.h"
#include "eval/metrics.h"
#include "eval/predictor.h"

namespace glossa::eval {

struct ResultRow {
  std::string name;
  Metrics metrics;
  int64_t parameters = 0;
  double train_minutes = NAN;
  double infer_ms_per_s = NAN;  // features + decoder, per second of audio
};

struct TestItem {
  std::string id;
  Audio audio;
  MatrixRM truth;    // absolute positions [T, 3L]
  RowVec neutral;    // the speaker's neutral pose
};

std::vector<TestItem> load_test_items(const ema::Corpus& corpus, const std::vector<std::string>& ids);

ResultRow evaluate(const Predictor& p, const std::vector<TestItem>& items, size_t landmarks);

}  // namespace glossa::eval
