// The torch-free inference decoder must compute what the libtorch modules compute.
#include <gtest/gtest.h>

#include "core/error.h"
#include "nn/cpu_decoder.h"
#include "nn/torch_decoder.h"

namespace glossa::nn {
namespace {

constexpr int kIn = 7, kOut = 6;

MatrixRM random_input(Eigen::Index T, unsigned seed) {
  std::srand(seed);
  return MatrixRM::Random(T, kIn);
}

MatrixRM torch_forward(DecoderNet& net, const MatrixRM& x) {
  torch::NoGradGuard ng;
  net->eval();
  torch::Tensor in =
      torch::from_blob(const_cast<float*>(x.data()), {1, x.rows(), x.cols()}, torch::kFloat32);
  torch::Tensor out = net->forward(in).contiguous();
  return Eigen::Map<MatrixRM>(out.data_ptr<float>(), x.rows(), out.size(2));
}

CpuDecoder cpu_copy(DecoderNet& net) {
  std::map<std::string, NamedTensor> t;
  export_tensors(net, t);
  return CpuDecoder(net->config(), kIn, kOut, t, "test");
}

struct Case {
  std::string type;
  int layers;
  bool bidirectional;
};

class MatchesTorch : public ::testing::TestWithParam<Case> {};

TEST_P(MatchesTorch, WholeUtterance) {
  const Case c = GetParam();
  torch::manual_seed(3);
  DecoderConfig cfg;
  cfg.type = c.type;
  cfg.layers = c.layers;
  cfg.bidirectional = c.bidirectional;
  cfg.hidden = 16;
  cfg.inference_window = 0;
  DecoderNet net(cfg, kIn, kOut);
  const CpuDecoder cpu = cpu_copy(net);
  EXPECT_EQ(cpu.parameter_count(), net->parameter_count());
  for (Eigen::Index T : {1, 4, 37}) {
    const MatrixRM x = random_input(T, static_cast<unsigned>(T));
    const MatrixRM want = torch_forward(net, x);
    const MatrixRM got = cpu.forward(x);
    ASSERT_EQ(got.rows(), T);
    ASSERT_EQ(got.cols(), kOut);
    EXPECT_LT((got - want).cwiseAbs().maxCoeff(), 1e-4f) << cfg.label() << " T=" << T;
  }
}

INSTANTIATE_TEST_SUITE_P(Decoders, MatchesTorch,
                         ::testing::Values(Case{"gru", 1, false}, Case{"gru", 2, true},
                                           Case{"lstm", 2, false}, Case{"lstm", 1, true},
                                           Case{"mlp", 2, false}));

// Windowed inference = the mean, per frame, of torch's outputs on every window covering it.
TEST(CpuDecoder, WindowedInferenceAveragesOverlappingWindows) {
  torch::manual_seed(5);
  DecoderConfig cfg;
  cfg.type = "gru";
  cfg.layers = 2;
  cfg.bidirectional = true;
  cfg.hidden = 12;
  cfg.inference_window = 6;
  cfg.inference_hop = 4;
  DecoderNet net(cfg, kIn, kOut);
  const CpuDecoder cpu = cpu_copy(net);
  const Eigen::Index T = 19, W = 6;
  const MatrixRM x = random_input(T, 9);
  MatrixRM sum = MatrixRM::Zero(T, kOut);
  Eigen::VectorXf n = Eigen::VectorXf::Zero(T);
  for (Eigen::Index s : {0, 4, 8, 12, 13}) {  // every 4 frames, plus one ending at the end
    const MatrixRM y = torch_forward(net, x.middleRows(s, W));
    sum.middleRows(s, W) += y;
    n.segment(s, W).array() += 1;
  }
  const MatrixRM want = sum.array().colwise() / n.array();
  EXPECT_LT((cpu.forward(x) - want).cwiseAbs().maxCoeff(), 1e-4f);
  // Shorter than one window: one pass over what there is.
  const MatrixRM short_x = x.topRows(4);
  EXPECT_LT((cpu.forward(short_x) - torch_forward(net, short_x)).cwiseAbs().maxCoeff(), 1e-4f);
}

TEST(CpuDecoder, RefusesMissingOrMisshapenTensors) {
  DecoderConfig cfg;
  cfg.hidden = 8;
  DecoderNet net(cfg, kIn, kOut);
  std::map<std::string, NamedTensor> t;
  export_tensors(net, t);
  auto bad = t;
  bad.erase("decoder.head.bias");
  try {
    CpuDecoder(cfg, kIn, kOut, bad, "m.glossa");
    FAIL() << "accepted a missing tensor";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("m.glossa"), std::string::npos);
    EXPECT_NE(std::string(e.what()).find("head.bias"), std::string::npos);
  }
  bad = t;
  bad["decoder.gru.weight_hh_l1"].shape = {24, 9};
  EXPECT_THROW(CpuDecoder(cfg, kIn, kOut, bad, "m.glossa"), Error);
  const CpuDecoder ok(cfg, kIn, kOut, t, "m.glossa");
  EXPECT_THROW(ok.forward(MatrixRM::Zero(3, kIn + 1)), Error);
  EXPECT_EQ(ok.forward(MatrixRM::Zero(0, kIn)).rows(), 0);
}

}  // namespace
}  // namespace glossa::nn
