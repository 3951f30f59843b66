#include "nn/decoder_config.h"

#include <algorithm>

#include "core/error.h"

namespace glossa::nn {

std::string DecoderConfig::label() const {
  if (type == "mlp") return fmt::format("MLP {}:{}", window_in, window_out);
  std::string t = type;
  std::transform(t.begin(), t.end(), t.begin(), ::toupper);
  return fmt::format("{}{}-{}L", bidirectional ? "Bi-" : "", t, layers);
}

void DecoderConfig::resolve_inference(int training_window) {
  if (inference_window < 0) inference_window = type != "mlp" && bidirectional ? training_window : 0;
  if (inference_hop < 0) inference_hop = std::max(1, inference_window / 5);
}

int DecoderConfig::left_context() const {
  return type == "mlp" ? (window_in - 1) + (window_out - 1) : 0;
}

int DecoderConfig::right_context() const { return type == "mlp" ? window_out - 1 : 0; }

nlohmann::json DecoderConfig::to_json() const {
  nlohmann::json j = {{"type", type}, {"layers", layers}, {"hidden", hidden}, {"dropout", dropout}};
  if (type == "mlp") {
    j["window_in"] = window_in;
    j["window_out"] = window_out;
  } else {
    j["bidirectional"] = bidirectional;
    j["inference_window"] = inference_window;
    j["inference_hop"] = inference_hop;
  }
  return j;
}

DecoderConfig DecoderConfig::from_json(const nlohmann::json& j) {
  DecoderConfig c;
  try {
    c.type = j.value("type", c.type);
    c.layers = j.value("layers", c.layers);
    c.hidden = j.value("hidden", c.hidden);
    c.bidirectional = j.value("bidirectional", c.bidirectional);
    c.dropout = j.value("dropout", c.dropout);
    c.window_in = j.value("window_in", c.window_in);
    c.window_out = j.value("window_out", c.window_out);
    c.inference_window = j.value("inference_window", c.inference_window);
    c.inference_hop = j.value("inference_hop", c.inference_hop);
  } catch (const nlohmann::json::exception& e) {
    throw Error(std::string("decoder config: ") + e.what());
  }
  c.validate();
  return c;
}

void DecoderConfig::validate() const {
  if (type != "mlp" && type != "gru" && type != "lstm")
    throw Error("decoder type must be mlp, gru or lstm (got '" + type + "')");
  if (type == "mlp") {
    if (layers < 1 || layers > 4) throw Error("MLP decoder: layers must be 1..4");
    if (window_in < 1 || window_out < 1 || window_out > window_in)
      throw Error("MLP decoder: need 1 <= window_out <= window_in");
    if (bidirectional) throw Error("MLP decoder: --bidirectional applies to RNNs only");
  } else if (layers < 1 || layers > 5) {
    throw Error("RNN decoder: layers must be 1..5");
  }
  if (inference_window < -1 || inference_window > 100000)
    throw Error("decoder: inference_window must be -1 (auto), 0 (whole utterance) or frames");
  if (inference_hop == 0 || inference_hop < -1 ||
      (inference_window > 0 && inference_hop > inference_window))
    throw Error("decoder: inference_hop must be -1 (auto) or 1..inference_window");
  if (hidden < 1 || hidden > 4096) throw Error("decoder: hidden must be 1..4096");
  if (dropout < 0 || dropout >= 1) throw Error("decoder: dropout must be in [0, 1)");
}

}  // namespace glossa::nn
