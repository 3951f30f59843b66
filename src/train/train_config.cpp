#include "train/train_config.h"

#include "core/error.h"

namespace glossa::train {

nlohmann::json TrainConfig::to_json() const {
  return {{"encoder", encoder},         {"decoder", decoder.to_json()},
          {"split", split},             {"val_fraction", val_fraction},
          {"window", window},           {"batch", batch},
          {"lr", lr},                   {"betas", {beta1, beta2}},
          {"weight_decay", weight_decay}, {"grad_clip", grad_clip},
          {"max_epochs", max_epochs},   {"patience", patience},
          {"windows_per_epoch", windows_per_epoch},
          {"checkpoint_seconds", checkpoint_seconds},
          {"seed", seed},               {"threads", threads}};
}

TrainConfig TrainConfig::from_json(const nlohmann::json& j, TrainConfig c) {
  try {
    if (j.contains("encoder")) {
      if (j["encoder"].is_string()) c.encoder = {{"type", j["encoder"]}};
      else c.encoder = j["encoder"];
    }
    if (j.contains("decoder")) {
      nlohmann::json d = c.decoder.to_json();
      d.update(j["decoder"]);
      c.decoder = nn::DecoderConfig::from_json(d);
    }
    c.split = j.value("split", c.split);
    c.val_fraction = j.value("val_fraction", c.val_fraction);
    c.window = j.value("window", c.window);
    c.batch = j.value("batch", c.batch);
    c.lr = j.value("lr", c.lr);
    if (j.contains("betas")) {
      c.beta1 = j["betas"].at(0).get<double>();
      c.beta2 = j["betas"].at(1).get<double>();
    }
    c.weight_decay = j.value("weight_decay", c.weight_decay);
    c.grad_clip = j.value("grad_clip", c.grad_clip);
    c.max_epochs = j.value("max_epochs", c.max_epochs);
    c.patience = j.value("patience", c.patience);
    c.windows_per_epoch = j.value("windows_per_epoch", c.windows_per_epoch);
    c.checkpoint_seconds = j.value("checkpoint_seconds", c.checkpoint_seconds);
    c.seed = j.value("seed", c.seed);
    c.threads = j.value("threads", c.threads);
  } catch (const nlohmann::json::exception& e) {
    throw Error(std::string("training config: ") + e.what());
  }
  c.validate();
  return c;
}

void TrainConfig::validate() const {
  decoder.validate();
  if (window < 1 || window > 10000) throw Error("training config: window must be 1..10000 frames");
  if (batch < 1 || batch > 4096) throw Error("training config: batch must be 1..4096");
  if (!(lr > 0 && lr < 1)) throw Error("training config: lr must be in (0, 1)");
  if (max_epochs < 1) throw Error("training config: max_epochs must be at least 1");
  if (patience < 1) throw Error("training config: patience must be at least 1");
  if (val_fraction < 0 || val_fraction >= 1)
    throw Error("training config: val_fraction must be in [0, 1)");
  if (threads < 0) throw Error("training config: threads must be >= 0");
}

}  // namespace glossa::train
