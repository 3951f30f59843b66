#pragma once
// Inference of a decoder without libtorch: the maths of DecoderNet (nn/torch_decoder.h) in
// Eigen, on the weights of the model file's tensor table. Model::predict and the trainer's
// validation run this, so what is validated is exactly what ships. A recurrent time step costs
// one matrix-vector product per layer and direction, with no framework overhead per step.
#include <map>
#include <string>
#include <vector>

#include "core/matrix.h"
#include "nn/decoder_config.h"
#include "nn/model_file.h"

namespace glossa::nn {

class CpuDecoder {
 public:
  CpuDecoder() = default;
  // Throws glossa::Error naming `file_name` when a tensor is missing or has the wrong shape.
  CpuDecoder(const DecoderConfig& cfg, int in_dims, int out_dims,
             const std::map<std::string, NamedTensor>& tensors, const std::string& file_name);

  // Normalised features [T, in] -> normalised displacements [T, out]. For an RNN with an
  // inference window, overlapping windows are run as one batch and their outputs averaged.
  MatrixRM forward(const MatrixRM& x) const;

  const DecoderConfig& config() const { return cfg_; }
  int64_t parameter_count() const { return parameters_; }

 private:
  // Linear map y = x W + b, W stored transposed from torch's [out, in] to [in, out].
  struct Linear {
    MatrixRM w;
    RowVec b;
    MatrixRM apply(const MatrixRM& x) const;
  };
  // One direction of one recurrent layer; gates stacked as torch does (GRU r,z,n; LSTM i,f,g,o).
  struct Direction {
    Linear input;    // x -> gates
    MatrixRM w_rec;  // [H, G*H]
    RowVec b_rec;    // [G*H]
  };

  MatrixRM forward_mlp(const MatrixRM& x) const;
  MatrixRM forward_rnn(const MatrixRM& x) const;
  // Runs B sequences of S steps stored time-major (row s*B + b) through the RNN stack and head.
  MatrixRM run_rnn_batch(const MatrixRM& x, Eigen::Index steps, Eigen::Index batch) const;
  void run_direction(const Direction& d, const MatrixRM& gates_in, Eigen::Index steps,
                     Eigen::Index batch, bool reverse, MatrixRM& out, Eigen::Index col) const;

  DecoderConfig cfg_;
  int in_dims_ = 0, out_dims_ = 0;
  std::vector<std::vector<Direction>> rnn_;  // [layer][direction]
  std::vector<Linear> mlp_;
  Linear head_;
  int64_t parameters_ = 0;
};

}  // namespace glossa::nn
