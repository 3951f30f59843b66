#pragma once
// libtorch modules behind the decoders. Private to nn/ and train/ (it pulls in torch).
#include <torch/torch.h>

#include "nn/decoder_config.h"
#include "nn/model_file.h"

namespace glossa::nn {

// Maps normalised features [B, T, in] to normalised displacements [B, T, out].
class DecoderNetImpl : public torch::nn::Module {
 public:
  DecoderNetImpl(const DecoderConfig& cfg, int in_dims, int out_dims);
  torch::Tensor forward(torch::Tensor x);
  const DecoderConfig& config() const { return cfg_; }
  int64_t parameter_count() const;

 private:
  torch::Tensor forward_mlp(torch::Tensor x);

  DecoderConfig cfg_;
  int in_dims_, out_dims_;
  torch::nn::GRU gru_{nullptr};
  torch::nn::LSTM lstm_{nullptr};
  torch::nn::Sequential mlp_{nullptr};
  torch::nn::Dropout drop_{nullptr};
  torch::nn::Linear head_{nullptr};
};
TORCH_MODULE(DecoderNet);

// Copies parameters and buffers to / from the model file's tensor table.
void export_tensors(DecoderNet& net, std::map<std::string, NamedTensor>& out);
void import_tensors(DecoderNet& net, const std::map<std::string, NamedTensor>& in,
                    const std::string& file_name);

}  // namespace glossa::nn
