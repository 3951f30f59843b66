#pragma once
// Configuration of a decoder: the sliding-window MLP of the papers (Taylor et al. 2017, made
// causal) or a GRU/LSTM stack, uni- or bidirectional.
#include <string>

#include <nlohmann/json.hpp>

namespace glossa::nn {

struct DecoderConfig {
  std::string type = "gru";  // "mlp", "gru" or "lstm"
  int layers = 2;            // RNN layers (1..5) or MLP hidden layers (1..4)
  int hidden = 256;          // units per layer (per direction for RNNs)
  bool bidirectional = false;
  float dropout = 0.25f;
  int window_in = 15;  // MLP: input frames; the window ending at frame t
  int window_out = 5;  // MLP: output frames t-window_out+1..t, averaged where windows overlap
  // RNN inference: run overlapping windows of this many frames, one every `inference_hop`
  // frames, and average them (0 = the whole utterance in one pass). -1 = decided by the
  // trainer: its training window for a bidirectional RNN, 0 for a unidirectional one, and a
  // hop of a fifth of the window. A bidirectional RNN trained on windows generalises better
  // when run on windows of the same length (bench/RESULTS.md).
  int inference_window = -1;
  int inference_hop = -1;

  // Replaces the automatic (-1) inference window and hop by their values for a model trained
  // on `training_window` frames (0 when unknown: the whole utterance).
  void resolve_inference(int training_window);

  // "GRU-2L", "Bi-LSTM-2L", "MLP 15:5".
  std::string label() const;
  // Frames of context the decoder reads before / after the frame it predicts.
  int left_context() const;
  int right_context() const;
  nlohmann::json to_json() const;
  // Missing keys keep their defaults; throws glossa::Error on invalid values.
  static DecoderConfig from_json(const nlohmann::json& j);
  void validate() const;
};

}  // namespace glossa::nn
