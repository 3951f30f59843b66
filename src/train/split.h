#pragma once
// Train / validation / test splits of a corpus, by rule:
//   "text:13,14,15,16"   test = utterances of these texts (no test sentence heard in training)
//   "speaker:DPM"        test = this speaker's utterances (train on the others)
//   "tag:split"          test = utterances whose tag `split` is "test" (a corpus' own lists)
//   "random:0.2"         test = a random 20 % of utterances
//   "none"               no test set
// Validation is drawn from what remains: whole texts for text splits (so early stopping never
// sees a training sentence), random utterances otherwise.
#include <cstdint>
#include <string>
#include <vector>

#include "ema/corpus.h"

namespace glossa::train {

struct Split {
  std::string rule;
  std::vector<std::string> train, val, test;
};

Split make_split(const ema::Corpus& corpus, const std::string& rule, double val_fraction,
                 uint64_t seed);

}  // namespace glossa::train
