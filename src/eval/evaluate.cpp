#include "eval/evaluate.h"

#include <chrono>

#include "core/error.h"

namespace glossa::eval {

std::vector<TestItem> load_test_items(const ema::Corpus& corpus,
                                      const std::vector<std::string>& ids) {
  std::vector<TestItem> out;
  for (const auto& id : ids) {
    const ema::Utterance& u = corpus.utterance(id);
    TestItem t;
    t.id = id;
    t.audio = corpus.load_audio(u);
    t.truth = corpus.load_landmarks(u).positions;
    t.neutral = corpus.speaker(u.speaker).neutral;
    out.push_back(std::move(t));
  }
  return out;
}

ResultRow evaluate(const Predictor& p, const std::vector<TestItem>& items, size_t landmarks) {
  if (items.empty()) throw Error("evaluation: no test utterances");
  ResultRow row;
  row.name = p.name();
  row.parameters = p.parameters();
  row.train_minutes = p.train_minutes();
  MetricAccumulator acc(landmarks);
  double compute_s = 0, audio_s = 0;
  for (const auto& t : items) {
    const auto start = std::chrono::steady_clock::now();
    MatrixRM disp = p.predict(t.audio);
    compute_s += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    audio_s += t.audio.seconds();
    const Eigen::Index n = std::min(disp.rows(), t.truth.rows());
    MatrixRM pred = disp.topRows(n);
    pred.rowwise() += t.neutral;
    acc.add(pred, t.truth.topRows(n));
  }
  row.metrics = acc.result();
  row.infer_ms_per_s = 1000.0 * compute_s / audio_s;
  return row;
}

}  // namespace glossa::eval
