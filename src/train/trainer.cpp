#include "train/trainer.h"

#include <chrono>
#include <ctime>
#include <random>

#include "core/error.h"
#include "eval/metrics.h"
#include "features/normalizer.h"
#include "io/atomic_file.h"
#include "nn/cpu_decoder.h"
#include "nn/model_file.h"
#include "nn/torch_decoder.h"
#include "train/dataset.h"
#include "train/progress.h"
#include "train/split.h"

namespace glossa::train {
namespace fs = std::filesystem;
using nlohmann::json;

namespace {

struct State {
  int epoch = 0;  // epochs completed
  int step = 0;   // steps done within the current epoch
  int best_epoch = 0;
  double best_val = std::numeric_limits<double>::infinity();
  int bad_epochs = 0;
  double seconds = 0;  // training time accumulated over all sessions
  json history = json::array();
};

json state_json(const State& s, const TrainConfig& cfg) {
  return {{"epoch", s.epoch},           {"step", s.step},
          {"best_epoch", s.best_epoch}, {"best_val_mm", s.best_val},
          {"bad_epochs", s.bad_epochs}, {"seconds", s.seconds},
          {"history", s.history},       {"config", cfg.to_json()}};
}

// The checkpoint is a folder written whole under a temporary name and swapped in.
void save_checkpoint(const fs::path& dir, const State& s, const TrainConfig& cfg,
                     nn::DecoderNet& net, nn::DecoderNet& best, torch::optim::Adam& opt) {
  const fs::path tmp = dir.string() + ".tmp";
  const fs::path old = dir.string() + ".old";
  fs::remove_all(tmp);
  fs::create_directories(tmp);
  torch::save(net, (tmp / "net.pt").string());
  torch::save(best, (tmp / "best.pt").string());
  torch::save(opt, (tmp / "optim.pt").string());
  io::write_file_atomic(tmp / "state.json", state_json(s, cfg).dump(1));
  fs::remove_all(old);
  if (fs::exists(dir)) fs::rename(dir, old);
  fs::rename(tmp, dir);
  fs::remove_all(old);
}

bool load_checkpoint(const fs::path& dir_in, State& s, const TrainConfig& cfg, nn::DecoderNet& net,
                     nn::DecoderNet& best, torch::optim::Adam& opt) {
  fs::path dir = dir_in;
  if (!fs::exists(dir / "state.json")) {
    const fs::path old = dir.string() + ".old";  // killed between the two renames
    if (!fs::exists(old / "state.json")) return false;
    dir = old;
  }
  json j;
  try {
    j = json::parse(io::read_file(dir / "state.json"));
  } catch (const json::exception& e) {
    throw file_error(dir / "state.json", std::string("damaged checkpoint: ") + e.what());
  }
  json saved = j.at("config"), now = cfg.to_json();
  for (const char* k : {"max_epochs", "patience", "checkpoint_seconds", "threads"}) {
    saved.erase(k);
    now.erase(k);
  }
  if (saved != now)
    throw file_error(dir,
                     "checkpoint was made with a different configuration; remove it or "
                     "train without --resume");
  s.epoch = j.at("epoch");
  s.step = j.at("step");
  s.best_epoch = j.at("best_epoch");
  s.best_val = j.at("best_val_mm").is_number() ? j.at("best_val_mm").get<double>()
                                               : std::numeric_limits<double>::infinity();
  s.bad_epochs = j.at("bad_epochs");
  s.seconds = j.at("seconds");
  s.history = j.at("history");
  try {
    torch::load(net, (dir / "net.pt").string());
    torch::load(best, (dir / "best.pt").string());
    torch::load(opt, (dir / "optim.pt").string());
  } catch (const c10::Error& e) {
    throw file_error(dir, "damaged checkpoint: cannot load the saved tensors");
  }
  return true;
}

torch::Tensor to_tensor(const MatrixRM& m) {
  return torch::from_blob(const_cast<float*>(m.data()), {m.rows(), m.cols()}, torch::kFloat32)
      .clone();
}

struct Prepared {
  std::vector<torch::Tensor> x, y;  // normalised, [T, D] and [T, 3L]
};

Prepared prepare(const std::vector<Sequence>& seqs, const features::Normalizer& fn,
                 const features::Normalizer& tn) {
  Prepared p;
  for (const auto& s : seqs) {
    p.x.push_back(to_tensor(fn.apply(s.features)));
    p.y.push_back(to_tensor(tn.apply(s.targets)));
  }
  return p;
}

// Validates with the torch-free decoder that Model::predict runs, so early stopping judges
// exactly what the model file will do.
double validate(nn::DecoderNet& net, const std::vector<Sequence>& seqs,
                const features::Normalizer& fn, const features::Normalizer& tn, size_t L) {
  std::map<std::string, nn::NamedTensor> tensors;
  nn::export_tensors(net, tensors);
  const nn::CpuDecoder dec(net->config(), static_cast<int>(fn.mean.size()), static_cast<int>(3 * L),
                           tensors, "validation");
  eval::MetricAccumulator acc(L);
  for (const auto& s : seqs) acc.add(tn.invert(dec.forward(fn.apply(s.features))), s.targets);
  return acc.result().mean_error_mm;
}

void copy_params(nn::DecoderNet& from, nn::DecoderNet& to) {
  torch::NoGradGuard ng;
  auto src = from->named_parameters();
  for (auto& item : to->named_parameters()) item.value().copy_(src[item.key()]);
}

std::string today() {
  const std::time_t t = std::time(nullptr);
  char buf[32];
  std::strftime(buf, sizeof buf, "%Y-%m-%d", std::gmtime(&t));
  return buf;
}

}  // namespace

TrainResult train_model(const ema::Corpus& corpus, const TrainConfig& config,
                        const fs::path& model_out, const TrainOptions& opt) {
  config.validate();
  TrainConfig cfg = config;
  cfg.decoder.resolve_inference(cfg.window);
  const auto wall_start = std::chrono::steady_clock::now();
  if (cfg.threads > 0) torch::set_num_threads(cfg.threads);
  torch::manual_seed(cfg.seed);
  const auto encoder = features::make_encoder(cfg.encoder);
  const Split split = make_split(corpus, cfg.split, cfg.val_fraction, cfg.seed);
  if (split.val.empty())
    throw Error("training needs a validation set for early stopping (val_fraction > 0)");
  const features::FeatureCache cache(opt.cache_dir);

  ProgressBar load_bar("features", split.train.size() + split.val.size(), opt.progress);
  auto train_seqs = load_sequences(corpus, split.train, *encoder, cache,
                                   [&](size_t d, size_t) { load_bar.update(d); });
  auto val_seqs = load_sequences(corpus, split.val, *encoder, cache, [&](size_t d, size_t) {
    load_bar.update(split.train.size() + d);
  });
  load_bar.finish();

  std::vector<const MatrixRM*> fx, ty;
  size_t train_frames = 0;
  for (const auto& s : train_seqs) {
    fx.push_back(&s.features);
    ty.push_back(&s.targets);
    train_frames += static_cast<size_t>(s.features.rows());
  }
  const auto fnorm = features::Normalizer::fit(fx);
  const auto tnorm = features::Normalizer::fit(ty, 0.05f);
  const Prepared tr = prepare(train_seqs, fnorm, tnorm);

  const size_t L = corpus.landmark_set().size();
  const int lc = cfg.decoder.left_context(), rc = cfg.decoder.right_context();
  const int64_t need = cfg.window + lc + rc;
  // Sample start positions uniformly over all valid (utterance, start) pairs.
  std::vector<int64_t> cum;
  std::vector<size_t> usable;
  int64_t total_starts = 0;
  for (size_t i = 0; i < tr.x.size(); ++i) {
    const int64_t starts = tr.x[i].size(0) - need + 1;
    if (starts <= 0) continue;
    usable.push_back(i);
    total_starts += starts;
    cum.push_back(total_starts);
  }
  if (usable.empty())
    throw Error(fmt::format("no training utterance is long enough for windows of {} frames", need));

  nn::DecoderNet net(cfg.decoder, encoder->dims(), static_cast<int>(3 * L));
  nn::DecoderNet best(cfg.decoder, encoder->dims(), static_cast<int>(3 * L));
  torch::optim::Adam adam(net->parameters(), torch::optim::AdamOptions(cfg.lr)
                                                 .betas({cfg.beta1, cfg.beta2})
                                                 .weight_decay(cfg.weight_decay));
  const fs::path ckpt =
      opt.checkpoint_dir.empty() ? fs::path(model_out.string() + ".ckpt") : opt.checkpoint_dir;
  State st;
  if (opt.resume && load_checkpoint(ckpt, st, cfg, net, best, adam)) {
    if (opt.progress)
      fmt::print(stderr, "resuming from {} at epoch {} step {}\n", ckpt.string(), st.epoch + 1,
                 st.step);
  } else {
    copy_params(net, best);
  }

  const int steps_per_epoch =
      std::max<int>(1, (cfg.windows_per_epoch > 0 ? cfg.windows_per_epoch
                                                  : static_cast<int>(train_frames / cfg.window)) /
                           cfg.batch);
  auto last_ckpt = std::chrono::steady_clock::now();
  auto session_start = last_ckpt;
  const double seconds_before = st.seconds;
  auto elapsed = [&] {
    return seconds_before +
           std::chrono::duration<double>(std::chrono::steady_clock::now() - session_start).count();
  };
  net->train();
  const int64_t D = encoder->dims(), O = static_cast<int64_t>(3 * L);

  while (st.epoch < cfg.max_epochs && st.bad_epochs < cfg.patience) {
    ProgressBar bar(fmt::format("epoch {}/{}", st.epoch + 1, cfg.max_epochs), steps_per_epoch,
                    opt.progress);
    double loss_sum = 0;
    int loss_n = 0;
    for (; st.step < steps_per_epoch; ++st.step) {
      // Each step draws from its own seed, so a resumed run samples what the original would.
      const uint64_t step_seed = cfg.seed * 1000003ULL + uint64_t(st.epoch) * 100003ULL + st.step;
      std::mt19937_64 rng(step_seed);
      torch::manual_seed(step_seed);
      std::uniform_int_distribution<int64_t> pick(0, total_starts - 1);
      torch::Tensor xb = torch::empty({cfg.batch, need, D});
      torch::Tensor yb = torch::empty({cfg.batch, need, O});
      for (int b = 0; b < cfg.batch; ++b) {
        const int64_t r = pick(rng);
        const size_t k = std::upper_bound(cum.begin(), cum.end(), r) - cum.begin();
        const int64_t start = r - (k ? cum[k - 1] : 0);
        const size_t u = usable[k];
        xb[b] = tr.x[u].narrow(0, start, need);
        yb[b] = tr.y[u].narrow(0, start, need);
      }
      torch::Tensor pred = net->forward(xb).narrow(1, lc, cfg.window);
      torch::Tensor loss = torch::mse_loss(pred, yb.narrow(1, lc, cfg.window));
      adam.zero_grad();
      loss.backward();
      if (cfg.grad_clip > 0) torch::nn::utils::clip_grad_norm_(net->parameters(), cfg.grad_clip);
      adam.step();
      loss_sum += loss.item<double>();
      ++loss_n;
      bar.update(st.step + 1, fmt::format("loss {:.4f}", loss_sum / loss_n));
      if (std::chrono::steady_clock::now() - last_ckpt >
          std::chrono::duration<double>(cfg.checkpoint_seconds)) {
        State mid = st;
        mid.step = st.step + 1;
        mid.seconds = elapsed();
        save_checkpoint(ckpt, mid, cfg, net, best, adam);
        last_ckpt = std::chrono::steady_clock::now();
      }
    }
    const double val = validate(net, val_seqs, fnorm, tnorm, L);
    ++st.epoch;
    st.step = 0;
    const bool improved = val < st.best_val - 1e-6;
    if (improved) {
      st.best_val = val;
      st.best_epoch = st.epoch;
      st.bad_epochs = 0;
      copy_params(net, best);
    } else {
      ++st.bad_epochs;
    }
    st.seconds = elapsed();
    st.history.push_back(
        {{"epoch", st.epoch}, {"train_loss", loss_n ? loss_sum / loss_n : 0.0}, {"val_mm", val}});
    bar.finish(fmt::format("loss {:.4f} val {:.3f} mm{}", loss_n ? loss_sum / loss_n : 0.0, val,
                           improved ? " *" : ""));
    save_checkpoint(ckpt, st, cfg, net, best, adam);
    last_ckpt = std::chrono::steady_clock::now();
  }

  // The model file: best weights plus everything needed to use them.
  nn::ModelFile mf;
  nn::export_tensors(best, mf.tensors);
  json neutral_speakers = json::object();
  RowVec mean_neutral = RowVec::Zero(static_cast<Eigen::Index>(3 * L));
  std::set<std::string> train_speakers;
  for (const auto& s : train_seqs) train_speakers.insert(s.speaker);
  for (const auto& sp : train_speakers) {
    const RowVec& n = corpus.speaker(sp).neutral;
    neutral_speakers[sp] = std::vector<float>(n.data(), n.data() + n.size());
    mean_neutral += n;
  }
  mean_neutral /= static_cast<float>(train_speakers.size());
  double train_seconds = 0;
  for (const auto& s : train_seqs) train_seconds += s.seconds;
  mf.header = {
      {"kind", "glossa-landmark-model"},
      {"glossa_version", GLOSSA_VERSION},
      {"created", today()},
      {"landmark_set", corpus.landmark_set().names},
      {"units", "mm, head frame (x back->front, y right->left, z bottom->top), 50 fps"},
      {"output", "displacement from the speaker's neutral pose"},
      {"encoder", encoder->config()},
      {"feature_norm", fnorm.to_json()},
      {"target_norm", tnorm.to_json()},
      {"decoder", cfg.decoder.to_json()},
      {"neutral",
       {{"default",
         std::vector<float>(mean_neutral.data(), mean_neutral.data() + mean_neutral.size())},
        {"speakers", neutral_speakers}}},
      {"training",
       {{"corpus", fs::absolute(corpus.root()).string()},
        {"corpus_source", corpus.manifest().value("source", json::object()).value("format", "")},
        {"split", split.rule},
        {"train_utterances", split.train.size()},
        {"val_utterances", split.val.size()},
        {"test_ids", split.test},
        {"train_seconds_of_audio", train_seconds},
        {"epochs_run", st.epoch},
        {"best_epoch", st.best_epoch},
        {"best_val_mm", st.best_val},
        {"training_seconds", st.seconds},
        {"parameters", net->parameter_count()},
        {"config", cfg.to_json()},
        {"history", st.history}}}};
  mf.write(model_out);

  TrainResult r;
  r.epochs_run = st.epoch;
  r.best_epoch = st.best_epoch;
  r.best_val_mm = st.best_val;
  r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count();
  r.parameters = net->parameter_count();
  return r;
}

}  // namespace glossa::train
