#include "nn/cpu_decoder.h"

#include <algorithm>

#include "core/error.h"

namespace glossa::nn {
namespace {

using Index = Eigen::Index;

// Windows of one batch are capped so that a long recording does not need gigabytes at once.
constexpr Index kMaxWindowsPerBatch = 256;

const NamedTensor& find(const std::map<std::string, NamedTensor>& t, const std::string& key,
                        std::vector<int64_t> shape, const std::string& file_name) {
  auto it = t.find("decoder." + key);
  if (it == t.end()) throw file_error(file_name, "model file lacks tensor decoder." + key);
  if (it->second.shape != shape)
    throw file_error(file_name, "tensor decoder." + key + " has the wrong shape for this decoder");
  return it->second;
}

// torch stores a Linear weight as [out, in]; we keep its transpose [in, out].
MatrixRM transposed(const NamedTensor& t) {
  const auto rows = static_cast<Index>(t.shape[0]), cols = static_cast<Index>(t.shape[1]);
  return Eigen::Map<const MatrixRM>(t.data.data(), rows, cols).transpose();
}

RowVec vec(const NamedTensor& t) {
  return Eigen::Map<const RowVec>(t.data.data(), static_cast<Index>(t.data.size()));
}

}  // namespace

MatrixRM CpuDecoder::Linear::apply(const MatrixRM& x) const {
  MatrixRM y(x.rows(), w.cols());
  y.noalias() = x * w;
  y.rowwise() += b;
  return y;
}

CpuDecoder::CpuDecoder(const DecoderConfig& cfg, int in_dims, int out_dims,
                       const std::map<std::string, NamedTensor>& t, const std::string& file_name)
    : cfg_(cfg), in_dims_(in_dims), out_dims_(out_dims) {
  cfg_.validate();
  const int64_t H = cfg.hidden;
  auto linear = [&](const std::string& name, int64_t in, int64_t out) {
    Linear l;
    l.w = transposed(find(t, name + ".weight", {out, in}, file_name));
    l.b = vec(find(t, name + ".bias", {out}, file_name));
    parameters_ += (in + 1) * out;
    return l;
  };
  if (cfg.type == "mlp") {
    int64_t width = int64_t(in_dims) * cfg.window_in;
    // torch::nn::Sequential numbers Linear, ReLU, Dropout as 0, 1, 2, then 3, 4, 5, ...
    for (int l = 0; l < cfg.layers; ++l) {
      mlp_.push_back(linear("mlp." + std::to_string(3 * l), width, H));
      width = H;
    }
    head_ = linear("head", H, int64_t(out_dims) * cfg.window_out);
    return;
  }
  const int64_t gates = (cfg.type == "gru" ? 3 : 4) * H;
  const int dirs = cfg.bidirectional ? 2 : 1;
  int64_t width = in_dims;
  for (int l = 0; l < cfg.layers; ++l) {
    std::vector<Direction> layer;
    for (int d = 0; d < dirs; ++d) {
      const std::string sfx = "_l" + std::to_string(l) + (d ? "_reverse" : "");
      const std::string p = cfg.type + ".";
      Direction dir;
      dir.input.w = transposed(find(t, p + "weight_ih" + sfx, {gates, width}, file_name));
      dir.input.b = vec(find(t, p + "bias_ih" + sfx, {gates}, file_name));
      dir.w_rec = transposed(find(t, p + "weight_hh" + sfx, {gates, H}, file_name));
      dir.b_rec = vec(find(t, p + "bias_hh" + sfx, {gates}, file_name));
      parameters_ += gates * (width + H + 2);
      layer.push_back(std::move(dir));
    }
    rnn_.push_back(std::move(layer));
    width = H * dirs;
  }
  head_ = linear("head", width, out_dims);
}

MatrixRM CpuDecoder::forward(const MatrixRM& x) const {
  if (x.cols() != in_dims_)
    throw Error("decoder: input has " + std::to_string(x.cols()) + " dimensions, expected " +
                std::to_string(in_dims_));
  if (x.rows() == 0) return MatrixRM(0, out_dims_);
  return cfg_.type == "mlp" ? forward_mlp(x) : forward_rnn(x);
}

// The window ending at frame t (frames t-W+1..t, the first frame repeated before the start)
// predicts frames t-K+1..t; each frame is the mean of the K windows that cover it.
MatrixRM CpuDecoder::forward_mlp(const MatrixRM& x) const {
  const Index T = x.rows(), D = x.cols(), W = cfg_.window_in, K = cfg_.window_out;
  const Index N = T + K - 1;  // windows ending at t = 0 .. T+K-2
  MatrixRM win(N, W * D);
  for (Index t = 0; t < N; ++t)
    for (Index w = 0; w < W; ++w) {
      const Index f = std::clamp<Index>(t - W + 1 + w, 0, T - 1);
      win.block(t, w * D, 1, D) = x.row(f);
    }
  MatrixRM h = win;
  for (const Linear& l : mlp_) h = l.apply(h).cwiseMax(0.0f);
  const MatrixRM y = head_.apply(h);  // [N, K*out]
  MatrixRM acc = MatrixRM::Zero(T, out_dims_);
  for (Index k = 0; k < K; ++k)
    acc += y.block(K - 1 - k, k * out_dims_, T, out_dims_);  // frame f = t-K+1+k
  return acc / static_cast<float>(K);
}

MatrixRM CpuDecoder::forward_rnn(const MatrixRM& x) const {
  const Index T = x.rows(), W = cfg_.inference_window;
  if (W <= 0 || T <= W) return run_rnn_batch(x, T, 1);
  // Overlapping windows starting every `hop` frames, the last one ending at the last frame.
  std::vector<Index> starts;
  const Index hop = std::max(1, cfg_.inference_hop);
  for (Index s = 0; s + W < T; s += hop) starts.push_back(s);
  starts.push_back(T - W);
  MatrixRM acc = MatrixRM::Zero(T, out_dims_);
  Eigen::VectorXf count = Eigen::VectorXf::Zero(T);
  for (size_t first = 0; first < starts.size(); first += kMaxWindowsPerBatch) {
    const Index B = std::min<Index>(kMaxWindowsPerBatch, Index(starts.size() - first));
    MatrixRM xb(W * B, x.cols());
    for (Index s = 0; s < W; ++s)
      for (Index b = 0; b < B; ++b) xb.row(s * B + b) = x.row(starts[first + b] + s);
    const MatrixRM yb = run_rnn_batch(xb, W, B);
    for (Index s = 0; s < W; ++s)
      for (Index b = 0; b < B; ++b) {
        acc.row(starts[first + b] + s) += yb.row(s * B + b);
        count(starts[first + b] + s) += 1;
      }
  }
  return acc.array().colwise() / count.array();
}

MatrixRM CpuDecoder::run_rnn_batch(const MatrixRM& x, Index steps, Index batch) const {
  MatrixRM h = x;
  const Index H = cfg_.hidden;
  for (const auto& layer : rnn_) {
    MatrixRM out(steps * batch, H * Index(layer.size()));
    for (size_t d = 0; d < layer.size(); ++d)
      run_direction(layer[d], layer[d].input.apply(h), steps, batch, d == 1, out, Index(d) * H);
    h = std::move(out);
  }
  return head_.apply(h);
}

void CpuDecoder::run_direction(const Direction& d, const MatrixRM& gates_in, Index steps,
                               Index batch, bool reverse, MatrixRM& out, Index col) const {
  const Index H = cfg_.hidden;
  const bool gru = cfg_.type == "gru";
  MatrixRM h = MatrixRM::Zero(batch, H), c = MatrixRM::Zero(batch, H);
  MatrixRM rec(batch, d.w_rec.cols());
  for (Index i = 0; i < steps; ++i) {
    const Index s = reverse ? steps - 1 - i : i;
    rec.noalias() = h * d.w_rec;
    rec.rowwise() += d.b_rec;
    const auto g = gates_in.middleRows(s * batch, batch);
    if (gru) {
      const auto r = (g.leftCols(H) + rec.leftCols(H)).array().logistic().eval();
      const auto z = (g.middleCols(H, H) + rec.middleCols(H, H)).array().logistic().eval();
      const auto n =
          (g.middleCols(2 * H, H).array() + r * rec.middleCols(2 * H, H).array()).tanh().eval();
      h.array() = (1.0f - z) * n + z * h.array();
    } else {
      const auto gi = (g.leftCols(H) + rec.leftCols(H)).array().logistic().eval();
      const auto gf = (g.middleCols(H, H) + rec.middleCols(H, H)).array().logistic().eval();
      const auto gg = (g.middleCols(2 * H, H) + rec.middleCols(2 * H, H)).array().tanh().eval();
      const auto go = (g.middleCols(3 * H, H) + rec.middleCols(3 * H, H)).array().logistic().eval();
      c.array() = gf * c.array() + gi * gg;
      h.array() = go * c.array().tanh();
    }
    out.block(s * batch, col, batch, H) = h;
  }
}

}  // namespace glossa::nn
