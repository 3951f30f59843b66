#include <cmath>
#include <filesystem>
#include <memory>

#include "cli/commands.h"
#include "core/error.h"
#include "ema/corpus.h"
#include "ema/import.h"
#include "ema/readers/ag501_pos.h"
#include "ema/readers/est_track.h"
#include "ema/readers/imt22.h"
#include "ema/readers/npy_meta.h"
#include "ema/stats.h"
#include "ema/synthetic.h"
#include "train/progress.h"

namespace glossa::cli {
namespace fs = std::filesystem;

namespace {

struct ImportArgs {
  std::string src, out, format = "auto", channels, preset = "mocha", speaker;
  std::string resampling = "nearest", neutral = "mean";
  double max_gap = 0.1, max_mismatch = 1.0;
};

std::string detect_format(const fs::path& src) {
  if (fs::exists(src / "meta.json")) return "npy";
  for (const auto& e : fs::recursive_directory_iterator(src)) {
    const auto ext = e.path().extension();
    if (ext == ".pos") return "ag501";
    if (ext == ".ema") return "est";
  }
  return "imt22";
}

std::unique_ptr<ema::CorpusSource> open_source(const ImportArgs& a) {
  const fs::path src = a.src;
  if (!fs::is_directory(src)) throw file_error(src, "not a folder");
  const std::string fmt = a.format == "auto" ? detect_format(src) : a.format;
  if (fmt == "npy") return ema::open_npy_meta_source(src);
  if (fmt == "imt22") return ema::open_imt22_source(src, a.speaker.empty() ? "IMT22" : a.speaker);
  if (fmt == "ag501") {
    if (a.channels.empty())
      throw Error("--format ag501 needs --channels, e.g. \"1=TD,2=TB,...,9=REF-UI\"");
    ema::Ag501Options o;
    o.channels = ema::parse_channel_map(a.channels);
    o.speaker = a.speaker;
    return ema::open_ag501_source(src, o);
  }
  if (fmt == "est") {
    ema::EstOptions o;
    if (a.preset == "mocha") o = ema::EstOptions::mocha();
    else if (a.preset == "mngu0") o = ema::EstOptions::mngu0();
    else throw Error("--preset must be mocha or mngu0");
    o.speaker = a.speaker;
    return ema::open_est_source(src, o);
  }
  throw Error("unknown --format '" + fmt + "' (auto, npy, imt22, ag501, est)");
}

}  // namespace

void add_corpus_commands(CLI::App& app, std::vector<std::pair<CLI::App*, Run>>& runs) {
  CLI::App* corpus = app.add_subcommand("corpus", "Import, inspect and generate EMA corpora");
  corpus->require_subcommand(1);

  auto a = std::make_shared<ImportArgs>();
  CLI::App* imp = corpus->add_subcommand(
      "import", "Convert a corpus in its own layout into a normalised glossa corpus");
  imp->add_option("source", a->src, "Folder of the corpus to import")->required();
  imp->add_option("-o,--out", a->out, "Output folder (new, or an earlier glossa corpus)")
      ->required();
  imp->add_option("--format", a->format,
                  "auto | npy (npy + meta.json, e.g. STEM-E2VA) | imt22 | ag501 (.pos) | est "
                  "(.ema tracks: MOCHA-TIMIT, mngu0)")
      ->capture_default_str();
  imp->add_option("--channels", a->channels,
                  "AG501 channel map, e.g. \"1=TD,2=TB,3=BR,...,11=REF-UI,12=REF-LM,13=REF-RM\"");
  imp->add_option("--preset", a->preset, "EST channel naming: mocha | mngu0")
      ->capture_default_str();
  imp->add_option("--speaker", a->speaker, "Speaker name when the layout has none");
  imp->add_option("--resample", a->resampling,
                  "nearest (as the papers) | antialiased (soxr low-pass)")
      ->capture_default_str();
  imp->add_option("--max-gap", a->max_gap,
                  "Longest sensor dropout (s) to interpolate; longer ones skip the utterance")
      ->capture_default_str();
  imp->add_option("--max-length-mismatch", a->max_mismatch,
                  "Largest audio/EMA length difference (s) to reconcile by trimming")
      ->capture_default_str();
  imp->add_option("--neutral", a->neutral,
                  "Neutral pose per speaker: mean (mean pose) | silence (mean of the quietest "
                  "10% of frames)")
      ->capture_default_str();
  runs.emplace_back(imp, [a] {
    auto source = open_source(*a);
    ema::ImportOptions o;
    o.out = a->out;
    o.resampling = ema::parse_resampling(a->resampling);
    o.max_gap_s = a->max_gap;
    o.max_length_mismatch_s = a->max_mismatch;
    o.neutral = a->neutral;
    auto bar = std::make_shared<train::ProgressBar>("import", source->ids().size());
    o.progress = [bar](size_t done, size_t, const std::string&) { bar->update(done); };
    const auto report = ema::import_corpus(*source, o);
    bar->finish();
    for (const auto& d : report.details) {
      if (d.contains("skipped"))
        fmt::print(stderr, "skipped {}: {}\n", d["id"].get<std::string>(),
                   d["skipped"].get<std::string>());
    }
    size_t mismatched = 0;
    double worst = 0;
    for (const auto& d : report.details)
      if (d.contains("length_mismatch_s")) {
        ++mismatched;
        worst = std::max(worst, std::abs(d["length_mismatch_s"].get<double>()));
      }
    fmt::print("imported {} utterances, skipped {}; {} had audio/EMA length differences "
               "(largest {:.3f} s), reconciled by trimming; corpus written to {}\n",
               report.imported, report.skipped, mismatched, worst, a->out);
    return 0;
  });

  auto stats_dir = std::make_shared<std::string>();
  auto stats_json = std::make_shared<bool>(false);
  CLI::App* st = corpus->add_subcommand(
      "stats", "Per-sensor ranges, speeds and durations of a glossa corpus");
  st->add_option("corpus", *stats_dir, "Corpus folder")->required();
  st->add_flag("--json", *stats_json, "Print JSON instead of tables");
  runs.emplace_back(st, [stats_dir, stats_json] {
    const auto c = ema::Corpus::load(*stats_dir);
    const auto s = ema::compute_stats(c);
    fmt::print("{}", *stats_json ? ema::stats_json(s).dump(1) + "\n" : ema::stats_text(s));
    return 0;
  });

  auto demo_dir = std::make_shared<std::string>();
  auto demo = std::make_shared<ema::SyntheticOptions>();
  CLI::App* dm = corpus->add_subcommand(
      "demo", "Generate a small synthetic EMA corpus (npy layout) whose audio depends on its "
              "articulation; import it with `glossa corpus import`");
  dm->add_option("out", *demo_dir, "Output folder")->required();
  dm->add_option("--speakers", demo->speakers)->capture_default_str();
  dm->add_option("--texts", demo->texts)->capture_default_str();
  dm->add_option("--takes", demo->takes, "Repetitions of each text per speaker")
      ->capture_default_str();
  dm->add_option("--seconds", demo->seconds)->capture_default_str();
  dm->add_option("--seed", demo->seed)->capture_default_str();
  runs.emplace_back(dm, [demo_dir, demo] {
    ema::write_synthetic_source(*demo_dir, *demo);
    fmt::print("wrote {} synthetic utterances to {}\n",
               demo->speakers * demo->texts * demo->takes, *demo_dir);
    return 0;
  });
}

}  // namespace glossa::cli
