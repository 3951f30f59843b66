#include <filesystem>

#include "cli/commands.h"
#include "core/error.h"
#include "ema/corpus.h"
#include "features/cache.h"
#include "io/atomic_file.h"
#include "train/progress.h"
#include "train/trainer.h"

namespace glossa::cli {
namespace fs = std::filesystem;

namespace {

struct TrainArgs {
  std::string corpus, out, config, checkpoint, cache;
  bool resume = false, no_cache = false, quiet = false;
  nlohmann::json overrides = nlohmann::json::object();
};

// Adds `flag`, which sets config key `key` (under "decoder" when `decoder`) when given.
template <typename T>
void override_option(CLI::App* t, nlohmann::json& o, const std::string& flag,
                     const std::string& key, const std::string& help, bool decoder = false) {
  t->add_option_function<T>(
      flag, [&o, key, decoder](const T& v) { (decoder ? o["decoder"][key] : o[key]) = v; }, help);
}

}  // namespace

void add_train_command(CLI::App& app, std::vector<std::pair<CLI::App*, Run>>& runs) {
  auto a = std::make_shared<TrainArgs>();
  CLI::App* t = app.add_subcommand(
      "train", "Train a speech-to-landmarks model on a glossa corpus (config file and/or flags)");
  t->add_option("-c,--corpus", a->corpus, "Corpus folder (from `glossa corpus import`)")
      ->required();
  t->add_option("-o,--out", a->out, "Model file to write")->required();
  t->add_option("--config", a->config,
                "JSON training config; flags given on the command line override it");
  t->add_option("--checkpoint", a->checkpoint, "Checkpoint folder (default: <out>.ckpt)");
  t->add_flag("--resume", a->resume, "Continue from the checkpoint after an interruption");
  t->add_option("--cache", a->cache, "Feature cache folder (default: ~/.cache/glossa)");
  t->add_flag("--no-cache", a->no_cache, "Do not cache features");
  t->add_flag("-q,--quiet", a->quiet, "No progress output");

  // Flags that override config keys. Each writes into `overrides` only when given.
  auto& o = a->overrides;
  auto str = [t, &o](auto... args) { override_option<std::string>(t, o, args...); };
  auto integer = [t, &o](auto... args) { override_option<long long>(t, o, args...); };
  auto real = [t, &o](auto... args) { override_option<double>(t, o, args...); };
  str("--encoder", "encoder", "Features: mfcc (default, the papers' 27-D) | logmel");
  str("--decoder", "type", "Decoder: gru (default) | lstm | mlp", true);
  integer("--layers", "layers", "RNN layers 1-5 (default 2) or MLP hidden layers 1-4", true);
  integer("--hidden", "hidden", "Units per layer (per direction for RNNs; default 256)", true);
  real("--dropout", "dropout", "Dropout (default 0.25)", true);
  integer("--window-in", "window_in", "MLP input frames (default 15)", true);
  integer("--window-out", "window_out", "MLP output frames (default 5)", true);
  integer("--inference-window", "inference_window",
          "RNN inference on overlapping windows of N frames, averaged (0 = whole utterance; "
          "default: the training window for bidirectional RNNs, 0 otherwise)",
          true);
  integer("--inference-hop", "inference_hop",
          "Frames between inference windows (default: a fifth of the window)", true);
  t->add_flag_function(
      "--bidirectional", [&o](int64_t) { o["decoder"]["bidirectional"] = true; },
      "Bidirectional RNN");
  str("--split", "split",
      "Test split: text:13,14 | speaker:DPM | tag:split | random:0.2 | none (default)");
  real("--val-fraction", "val_fraction", "Share of training texts/utterances for validation (0.1)");
  integer("--window", "window", "Frames per training window (default 15 = 300 ms)");
  integer("--batch", "batch", "Batch size (default 32)");
  real("--lr", "lr", "Adam learning rate (default 1e-3)");
  integer("--epochs", "max_epochs", "Maximum epochs (default 40)");
  integer("--patience", "patience", "Early-stopping patience in epochs (default 8)");
  integer("--windows-per-epoch", "windows_per_epoch", "Windows per epoch (default frames/window)");
  real("--checkpoint-seconds", "checkpoint_seconds", "Seconds between checkpoints (default 60)");
  integer("--seed", "seed", "Random seed (default 1)");
  integer("--threads", "threads", "CPU threads (default: all cores)");

  runs.emplace_back(t, [a] {
    nlohmann::json j = nlohmann::json::object();
    if (!a->config.empty()) {
      try {
        j = nlohmann::json::parse(io::read_file(a->config));
      } catch (const nlohmann::json::exception& e) {
        throw file_error(a->config, std::string("not valid JSON: ") + e.what());
      }
    }
    // Numbers given as strings by the option callbacks stay numbers; merge decoder keys.
    for (auto& [k, v] : a->overrides.items()) {
      if (k == "decoder") {
        for (auto& [dk, dv] : v.items()) j["decoder"][dk] = dv;
      } else {
        j[k] = v;
      }
    }
    const auto cfg = train::TrainConfig::from_json(j);
    const auto corpus = ema::Corpus::load(a->corpus);
    train::TrainOptions opt;
    opt.checkpoint_dir = a->checkpoint;
    opt.resume = a->resume;
    opt.progress = !a->quiet;
    if (!a->no_cache)
      opt.cache_dir = a->cache.empty() ? features::FeatureCache::default_dir() : fs::path(a->cache);
    const auto r = train::train_model(corpus, cfg, a->out, opt);
    fmt::print(
        "trained {} ({} parameters) for {} epochs in {}; best validation error {:.3f} mm "
        "at epoch {}; model written to {}\n",
        cfg.decoder.label(), r.parameters, r.epochs_run, train::format_duration(r.seconds),
        r.best_val_mm, r.best_epoch, a->out);
    return 0;
  });
}

}  // namespace glossa::cli
