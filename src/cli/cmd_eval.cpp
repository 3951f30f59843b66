#include <filesystem>
#include <set>

#include "cli/commands.h"
#include "core/error.h"
#include "ema/corpus.h"
#include "eval/evaluate.h"
#include "eval/report.h"
#include "features/cache.h"
#include "io/atomic_file.h"
#include "nn/model.h"
#include "train/dataset.h"
#include "train/split.h"

namespace glossa::cli {
namespace fs = std::filesystem;

namespace {

struct EvalArgs {
  std::string corpus, split, md, csv;
  std::vector<std::string> models, names;
  std::vector<std::string> ridge_features{"mfcc"};
  bool no_baselines = false;
  int ridge_context = 5, threads = 0;
  double val_fraction = 0.1;
  uint64_t seed = 1;
};

}  // namespace

void add_eval_command(CLI::App& app, std::vector<std::pair<CLI::App*, Run>>& runs) {
  auto a = std::make_shared<EvalArgs>();
  CLI::App* e = app.add_subcommand(
      "eval", "Evaluate models and the two baselines (mean pose, ridge) on a corpus' test split");
  e->add_option("-c,--corpus", a->corpus, "Corpus folder")->required();
  e->add_option("-m,--model", a->models, "Model file(s); one table row each");
  e->add_option("--name", a->names, "Row names for the models, in order (default: decoder label)");
  e->add_option("--split", a->split,
                "Split rule (default: the first model's own split; see `glossa train --help`)");
  e->add_flag("--no-baselines", a->no_baselines, "Leave out the mean-pose and ridge rows");
  e->add_option("--ridge-features", a->ridge_features, "Encoders for ridge rows (mfcc, logmel)")
      ->capture_default_str();
  e->add_option("--ridge-context", a->ridge_context, "Ridge stacks frames t-c..t+c")
      ->capture_default_str();
  e->add_option("--val-fraction", a->val_fraction, "Validation share used to pick ridge's weight")
      ->capture_default_str();
  e->add_option("--seed", a->seed, "Seed of the split")->capture_default_str();
  e->add_option("--threads", a->threads,
                "CPU threads for inference (default: all; 1 for timing "
                "on one core)");
  e->add_option("--md", a->md, "Write the table as Markdown to this file");
  e->add_option("--csv", a->csv, "Write the table as CSV to this file");

  runs.emplace_back(e, [a] {
    if (a->threads > 0) {
      nn::set_threads(a->threads);
    }
    const auto corpus = ema::Corpus::load(a->corpus);
    std::vector<std::shared_ptr<nn::Model>> models;
    for (const auto& m : a->models) {
      models.push_back(std::make_shared<nn::Model>(nn::Model::load(m)));
      if (models.back()->landmark_set() != corpus.landmark_set())
        throw file_error(m, "model predicts [" + models.back()->landmark_set().joined() +
                                "] but the corpus has [" + corpus.landmark_set().joined() + "]");
    }
    if (a->no_baselines && models.empty())
      throw Error("eval: nothing to evaluate (--no-baselines and no -m model)");
    std::string rule = a->split;
    if (rule.empty() && !models.empty())
      rule = models.front()->header().at("training").value("split", "none");
    if (rule.empty() || rule == "none")
      throw Error("eval: give --split (no model with a recorded test split)");
    train::Split split = train::make_split(corpus, rule, a->val_fraction, a->seed);
    // A random split depends on the seed: test exactly what the first model held out.
    if (a->split.empty() && !models.empty()) {
      const auto& ids = models.front()->header().at("training").value("test_ids", nlohmann::json());
      if (ids.is_array() && !ids.empty()) split.test = ids.get<std::vector<std::string>>();
    }
    if (split.test.empty()) throw Error("eval: split '" + rule + "' has no test utterances");
    const auto items = eval::load_test_items(corpus, split.test);
    const size_t L = corpus.landmark_set().size();

    std::vector<eval::ResultRow> rows;
    if (!a->no_baselines) {
      rows.push_back(eval::evaluate(eval::MeanPosePredictor(L), items, L));
      const features::FeatureCache cache(features::FeatureCache::default_dir());
      for (const auto& f : a->ridge_features) {
        const auto enc = features::make_encoder(f);
        const auto tr = train::load_sequences(corpus, split.train, *enc, cache);
        const auto va = train::load_sequences(corpus, split.val, *enc, cache);
        const auto ridge = eval::RidgePredictor::fit(enc->config(), tr, va, a->ridge_context);
        rows.push_back(eval::evaluate(*ridge, items, L));
      }
    }
    for (size_t i = 0; i < models.size(); ++i) {
      const std::string name = i < a->names.size()
                                   ? a->names[i]
                                   : models[i]->label() + " " + models[i]->encoder().name();
      rows.push_back(eval::evaluate(eval::ModelPredictor(models[i], name), items, L));
    }
    const std::string md = eval::markdown_table(rows, corpus.landmark_set());
    fmt::print("split {}: {} test utterances, {} frames\n\n{}", rule, items.size(),
               rows.front().metrics.frames, md);
    if (!a->md.empty()) io::write_file_atomic(a->md, md);
    if (!a->csv.empty())
      io::write_file_atomic(a->csv, eval::csv_table(rows, corpus.landmark_set()));
    return 0;
  });
}

}  // namespace glossa::cli
