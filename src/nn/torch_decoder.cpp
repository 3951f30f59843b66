#include "nn/torch_decoder.h"

#include "core/error.h"

namespace glossa::nn {

DecoderNetImpl::DecoderNetImpl(const DecoderConfig& cfg, int in_dims, int out_dims)
    : cfg_(cfg), in_dims_(in_dims), out_dims_(out_dims) {
  cfg_.validate();
  const double inter_dropout = cfg.layers > 1 ? cfg.dropout : 0.0;
  if (cfg.type == "gru") {
    gru_ = register_module("gru", torch::nn::GRU(torch::nn::GRUOptions(in_dims, cfg.hidden)
                                                     .num_layers(cfg.layers)
                                                     .batch_first(true)
                                                     .bidirectional(cfg.bidirectional)
                                                     .dropout(inter_dropout)));
  } else if (cfg.type == "lstm") {
    lstm_ = register_module("lstm", torch::nn::LSTM(torch::nn::LSTMOptions(in_dims, cfg.hidden)
                                                        .num_layers(cfg.layers)
                                                        .batch_first(true)
                                                        .bidirectional(cfg.bidirectional)
                                                        .dropout(inter_dropout)));
  } else {
    torch::nn::Sequential seq;
    int width = in_dims * cfg.window_in;
    for (int l = 0; l < cfg.layers; ++l) {
      seq->push_back(torch::nn::Linear(width, cfg.hidden));
      seq->push_back(torch::nn::ReLU());
      seq->push_back(torch::nn::Dropout(cfg.dropout));
      width = cfg.hidden;
    }
    mlp_ = register_module("mlp", seq);
  }
  drop_ = register_module("drop", torch::nn::Dropout(cfg.dropout));
  const int head_in = cfg.type == "mlp" ? cfg.hidden : cfg.hidden * (cfg.bidirectional ? 2 : 1);
  const int head_out = cfg.type == "mlp" ? out_dims * cfg.window_out : out_dims;
  head_ = register_module("head", torch::nn::Linear(head_in, head_out));
}

torch::Tensor DecoderNetImpl::forward(torch::Tensor x) {
  if (cfg_.type == "mlp") return forward_mlp(x);
  torch::Tensor h =
      cfg_.type == "gru" ? std::get<0>(gru_->forward(x)) : std::get<0>(lstm_->forward(x));
  return head_->forward(drop_->forward(h));
}

// Window ending at frame t (frames t-W+1..t, replicate-padded at the start) predicts frames
// t-K+1..t; each frame's estimate is the mean of the windows that cover it.
torch::Tensor DecoderNetImpl::forward_mlp(torch::Tensor x) {
  const int64_t B = x.size(0), T = x.size(1), D = x.size(2);
  const int W = cfg_.window_in, K = cfg_.window_out;
  // Pad W-1 frames before and K-1 after (the last windows predict past the end; dropped).
  torch::Tensor first = x.index({torch::indexing::Slice(), torch::indexing::Slice(0, 1)});
  torch::Tensor last = x.index({torch::indexing::Slice(), torch::indexing::Slice(T - 1, T)});
  torch::Tensor padded =
      torch::cat({first.expand({B, W - 1, D}), x, last.expand({B, K - 1, D})}, 1);
  // Windows ending at t = 0 .. T+K-2: [B, T+K-1, W*D]
  torch::Tensor win = padded.unfold(1, W, 1).transpose(2, 3).reshape({B, T + K - 1, W * D});
  torch::Tensor y = head_->forward(mlp_->forward(win)).view({B, T + K - 1, K, out_dims_});
  // Output k of the window ending at t is frame t-K+1+k. Accumulate by shifting.
  torch::Tensor acc = torch::zeros({B, T, out_dims_}, x.options());
  for (int k = 0; k < K; ++k) {
    // frames f = t-K+1+k for t in [0, T+K-2] -> t = f+K-1-k; f in [0, T-1]
    acc = acc +
          y.index({torch::indexing::Slice(), torch::indexing::Slice(K - 1 - k, K - 1 - k + T), k});
  }
  return acc / static_cast<double>(K);
}

int64_t DecoderNetImpl::parameter_count() const {
  int64_t n = 0;
  for (const auto& p : parameters()) n += p.numel();
  return n;
}

void export_tensors(DecoderNet& net, std::map<std::string, NamedTensor>& out) {
  torch::NoGradGuard ng;
  for (const auto& item : net->named_parameters()) {
    torch::Tensor t = item.value().detach().to(torch::kFloat32).contiguous().cpu();
    NamedTensor nt;
    nt.shape.assign(t.sizes().begin(), t.sizes().end());
    nt.data.assign(t.data_ptr<float>(), t.data_ptr<float>() + t.numel());
    out["decoder." + item.key()] = std::move(nt);
  }
}

void import_tensors(DecoderNet& net, const std::map<std::string, NamedTensor>& in,
                    const std::string& file_name) {
  torch::NoGradGuard ng;
  for (auto& item : net->named_parameters()) {
    const std::string key = "decoder." + item.key();
    auto it = in.find(key);
    if (it == in.end()) throw file_error(file_name, "model file lacks tensor " + key);
    const std::vector<int64_t> want(item.value().sizes().begin(), item.value().sizes().end());
    if (it->second.shape != want)
      throw file_error(file_name, "tensor " + key + " has the wrong shape for this decoder");
    item.value().copy_(
        torch::from_blob(const_cast<float*>(it->second.data.data()), want, torch::kFloat32));
  }
}

}  // namespace glossa::nn
