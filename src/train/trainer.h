#pragma once
// Training of a landmark model: random windows, MSE on standardised displacements, Adam,
// validation (eq. 1, mm) after every epoch, early stopping on it, checkpoints that survive a
// kill, and one self-describing model file with the best weights at the end.
#include <filesystem>
#include <string>

#include "ema/corpus.h"
#include "train/train_config.h"

namespace glossa::train {

struct TrainOptions {
  std::filesystem::path checkpoint_dir;  // empty: <model>.ckpt
  bool resume = false;                   // continue from the checkpoint if there is one
  std::filesystem::path cache_dir;       // feature cache; empty disables
  bool progress = true;
};

struct TrainResult {
  int epochs_run = 0;
  int best_epoch = 0;
  double best_val_mm = 0;
  double seconds = 0;
  int64_t parameters = 0;
};

TrainResult train_model(const ema::Corpus& corpus, const TrainConfig& cfg,
                        const std::filesystem::path& model_out, const TrainOptions& opt);

}  // namespace glossa::train
