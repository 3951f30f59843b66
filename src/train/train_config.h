#pragma once
// Everything a training run depends on. Read from a JSON config file and/or CLI flags; stored
// in the model file and the checkpoint so that a run can be resumed and reproduced.
#include <cstdint>
#include <string>

#include <nlohmann/json.hpp>

#include "nn/decoder_config.h"

namespace glossa::train {

struct TrainConfig {
  nlohmann::json encoder = {{"type", "mfcc"}};
  nn::DecoderConfig decoder;
  std::string split = "none";  // see split.h
  double val_fraction = 0.1;
  int window = 15;             // frames per training sample (the papers' 300 ms)
  int batch = 32;
  double lr = 1e-3;
  double beta1 = 0.9, beta2 = 0.99;
  double weight_decay = 0;
  double grad_clip = 5.0;      // max gradient norm; 0 disables
  int max_epochs = 40;
  int patience = 8;            // epochs without validation improvement before stopping
  int windows_per_epoch = 0;   // 0: training frames / window
  double checkpoint_seconds = 60;  // also checkpoints at every epoch end
  uint64_t seed = 1;
  int threads = 0;             // 0: all cores

  nlohmann::json to_json() const;
  // Overlays the keys present in `j` onto `base`; throws glossa::Error on bad values.
  static TrainConfig from_json(const nlohmann::json& j, TrainConfig base);
  static TrainConfig from_json(const nlohmann::json& j) { return from_json(j, TrainConfig()); }
  void validate() const;
};

}  // namespace glossa::train
