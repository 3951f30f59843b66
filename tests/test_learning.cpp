// The learning path end to end on generated data whose articulation truly depends on the audio:
// a small model's held-out error must fall below half the mean-pose error; training must be
// reproducible and resumable.
#include <gtest/gtest.h>

#include "core/error.h"
#include "ema/corpus.h"
#include "ema/import.h"
#include "ema/readers/npy_meta.h"
#include "ema/synthetic.h"
#include "eval/evaluate.h"
#include "nn/model.h"
#include "nn/model_file.h"
#include "support/fixtures.h"
#include "train/split.h"
#include "train/trainer.h"

namespace glossa {
namespace {

class Learning : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = new testing::TempDir();
    ema::SyntheticOptions o;
    o.speakers = 2;
    o.texts = 6;
    o.takes = 3;
    o.seconds = 2.0;
    ema::write_synthetic_source(*dir_ / "src", o);
    auto source = ema::open_npy_meta_source(*dir_ / "src");
    ema::ImportOptions io;
    io.out = *dir_ / "corpus";
    ema::import_corpus(*source, io);
  }
  static void TearDownTestSuite() { delete dir_; }

  static train::TrainConfig small_config() {
    train::TrainConfig c;
    c.decoder.type = "gru";
    c.decoder.layers = 1;
    c.decoder.hidden = 64;
    c.decoder.dropout = 0.1f;
    c.split = "text:05,06";
    c.max_epochs = 40;
    c.patience = 10;
    c.windows_per_epoch = 640;
    c.lr = 3e-3;
    c.threads = 1;
    return c;
  }

  static testing::TempDir* dir_;
};
testing::TempDir* Learning::dir_ = nullptr;

TEST_F(Learning, HeldOutErrorBelowHalfOfMeanPose) {
  const auto corpus = ema::Corpus::load(*dir_ / "corpus");
  train::TrainOptions opt;
  opt.progress = false;
  const auto cfg = small_config();
  train::train_model(corpus, cfg, *dir_ / "m.glossa", opt);

  const auto split = train::make_split(corpus, cfg.split, cfg.val_fraction, cfg.seed);
  ASSERT_FALSE(split.test.empty());
  const auto items = eval::load_test_items(corpus, split.test);
  const size_t L = corpus.landmark_set().size();
  auto model = std::make_shared<nn::Model>(nn::Model::load(*dir_ / "m.glossa"));
  const auto mean_pose = eval::evaluate(eval::MeanPosePredictor(L), items, L);
  const auto learned = eval::evaluate(eval::ModelPredictor(model, "gru"), items, L);
  EXPECT_LT(learned.metrics.mean_error_mm, 0.5 * mean_pose.metrics.mean_error_mm)
      << "model " << learned.metrics.mean_error_mm << " mm vs mean pose "
      << mean_pose.metrics.mean_error_mm << " mm";
  EXPECT_GT(learned.metrics.pearson, 0.5);
  // The model file records its test split so that `glossa eval` finds it again.
  EXPECT_EQ(model->header()["training"]["test_ids"].size(), split.test.size());
}

TEST_F(Learning, ResumedRunMatchesUninterruptedRun) {
  const auto corpus = ema::Corpus::load(*dir_ / "corpus");
  train::TrainOptions opt;
  opt.progress = false;
  auto cfg = small_config();
  cfg.max_epochs = 4;
  train::train_model(corpus, cfg, *dir_ / "full.glossa", opt);

  // "Kill" after 2 epochs: a run limited to 2 epochs leaves its checkpoint behind.
  auto first = cfg;
  first.max_epochs = 2;
  opt.checkpoint_dir = *dir_ / "ckpt";
  train::train_model(corpus, first, *dir_ / "part.glossa", opt);
  opt.resume = true;
  train::train_model(corpus, cfg, *dir_ / "resumed.glossa", opt);

  const auto a = nn::ModelFile::read(*dir_ / "full.glossa");
  const auto b = nn::ModelFile::read(*dir_ / "resumed.glossa");
  ASSERT_EQ(a.header["training"]["epochs_run"], 4);
  ASSERT_EQ(b.header["training"]["epochs_run"], 4);
  const auto& ha = a.header["training"]["history"];
  const auto& hb = b.header["training"]["history"];
  ASSERT_EQ(ha.size(), hb.size());
  for (size_t i = 0; i < ha.size(); ++i)
    EXPECT_NEAR(ha[i]["val_mm"].get<double>(), hb[i]["val_mm"].get<double>(), 1e-4) << i;
  for (const auto& [name, t] : a.tensors) {
    const auto& u = b.tensors.at(name);
    ASSERT_EQ(t.data.size(), u.data.size());
    for (size_t i = 0; i < t.data.size(); ++i) ASSERT_NEAR(t.data[i], u.data[i], 1e-4) << name;
  }
}

TEST_F(Learning, ResumeRefusesADifferentConfiguration) {
  const auto corpus = ema::Corpus::load(*dir_ / "corpus");
  train::TrainOptions opt;
  opt.progress = false;
  opt.checkpoint_dir = *dir_ / "ckpt2";
  auto cfg = small_config();
  cfg.max_epochs = 1;
  train::train_model(corpus, cfg, *dir_ / "x.glossa", opt);
  cfg.decoder.hidden = 32;
  cfg.max_epochs = 2;
  opt.resume = true;
  EXPECT_THROW(train::train_model(corpus, cfg, *dir_ / "x.glossa", opt), Error);
}

}  // namespace
}  // namespace glossa
