#include "ema/import.h"

#include <algorithm>
#include <cmath>

#include "audio/decode.h"
#include "core/error.h"
#include "ema/corpus.h"
#include "io/atomic_file.h"
#include "io/npy.h"

namespace glossa::ema {
namespace fs = std::filesystem;
using nlohmann::json;

std::vector<float> frame_energy_db(const Audio& audio, size_t frames) {
  std::vector<float> db(frames, -120.f);
  for (size_t f = 0; f < frames; ++f) {
    const size_t a = f * kSamplesPerFrame;
    const size_t b = std::min(audio.samples.size(), a + kSamplesPerFrame);
    if (a >= b) continue;
    double e = 0;
    for (size_t i = a; i < b; ++i) e += double(audio.samples[i]) * audio.samples[i];
    db[f] = static_cast<float>(10.0 * std::log10(e / double(b - a) + 1e-12));
  }
  return db;
}

RowVec estimate_neutral(const MatrixRM& positions, const std::vector<float>& frame_db,
                        const std::string& method) {
  if (positions.rows() == 0) throw Error("cannot estimate a neutral pose from no frames");
  if (method == "mean") return positions.colwise().mean();
  if (method != "silence")
    throw Error("unknown neutral-pose method '" + method + "' (use mean or silence)");
  std::vector<float> sorted = frame_db;
  std::sort(sorted.begin(), sorted.end());
  const float threshold = sorted[sorted.size() / 10];
  RowVec sum = RowVec::Zero(positions.cols());
  int n = 0;
  for (Eigen::Index f = 0; f < positions.rows(); ++f) {
    if (frame_db[static_cast<size_t>(f)] <= threshold) {
      sum += positions.row(f);
      ++n;
    }
  }
  return sum / static_cast<float>(std::max(n, 1));
}

ImportReport import_corpus(const CorpusSource& source, const ImportOptions& opt) {
  if (opt.out.empty()) throw Error("corpus import: no output folder given");
  if (fs::exists(opt.out) && !fs::is_empty(opt.out) && !fs::exists(opt.out / "manifest.json"))
    throw file_error(opt.out, "output folder exists and is not a glossa corpus; refusing to "
                                "write into it");
  fs::create_directories(opt.out / "audio");
  fs::create_directories(opt.out / "landmarks");

  ImportReport report;
  report.details = json::array();
  const auto ids = source.ids();
  if (ids.empty()) throw Error("corpus import: the source has no utterances");

  std::optional<LandmarkSet> out_set;
  json utts = json::array();
  struct SpeakerAcc {
    std::vector<MatrixRM> poses;
    std::vector<float> db;
  };
  std::map<std::string, SpeakerAcc> acc;

  for (size_t i = 0; i < ids.size(); ++i) {
    const std::string& id = ids[i];
    if (opt.progress) opt.progress(i, ids.size(), id);
    json note = {{"id", id}};
    try {
      RawUtterance raw = source.load(id);
      LandmarkSeq ema = std::move(raw.ema);
      bool has_refs = std::any_of(ema.set.names.begin(), ema.set.names.end(),
                                  [](const std::string& n) { return is_reference_sensor(n); });
      if (has_refs) {
        ema = stabilise_head(ema);
        note["head_stabilised"] = true;
      }
      const GapReport gaps = fill_gaps(ema, opt.max_gap_s);
      if (!gaps.ok) {
        note["skipped"] = fmt::format("sensor {} has a dropout of {:.3f} s (limit {:.3f} s)",
                                      gaps.worst_sensor, gaps.longest_gap_s, opt.max_gap_s);
        report.details.push_back(note);
        ++report.skipped;
        continue;
      }
      if (gaps.filled_runs) note["filled_gaps"] = gaps.filled_runs;
      LandmarkSeq lm = resample(ema, kFrameRate, opt.resampling);
      if (out_set && lm.set != *out_set)
        throw Error("utterance " + id + " has sensors [" + lm.set.joined() +
                    "], unlike the earlier ones [" + out_set->joined() + "]");
      out_set = lm.set;

      Audio audio = audio::load_audio(raw.audio_path);
      const size_t audio_frames =
          (audio.samples.size() + kSamplesPerFrame - 1) / kSamplesPerFrame;
      const double mismatch_s =
          (double(audio_frames) - double(lm.frames())) / kFrameRate;
      if (std::abs(mismatch_s) > opt.max_length_mismatch_s) {
        note["skipped"] = fmt::format("audio is {:.2f} s, EMA {:.2f} s: lengths differ by more "
                                      "than {:.2f} s",
                                      audio.seconds(), lm.seconds(), opt.max_length_mismatch_s);
        report.details.push_back(note);
        ++report.skipped;
        continue;
      }
      const size_t frames = std::min(audio_frames, lm.frames());
      if (frames == 0) throw Error("utterance " + id + " is empty");
      if (audio_frames != lm.frames()) note["length_mismatch_s"] = mismatch_s;
      lm.positions.conservativeResize(static_cast<Eigen::Index>(frames), Eigen::NoChange);
      audio.samples.resize(std::min(audio.samples.size(), frames * kSamplesPerFrame));

      audio::write_wav(opt.out / "audio" / (id + ".wav"), audio);
      io::write_npy(opt.out / "landmarks" / (id + ".npy"), lm.positions.data(),
                    {frames, lm.set.size(), 3});
      auto& a = acc[raw.speaker];
      a.poses.push_back(lm.positions);
      const auto db = frame_energy_db(audio, frames);
      a.db.insert(a.db.end(), db.begin(), db.end());

      json u = {{"id", id},
                {"speaker", raw.speaker},
                {"text", raw.text},
                {"frames", frames},
                {"seconds", frames / kFrameRate}};
      if (!raw.transcript.empty()) u["transcript"] = raw.transcript;
      if (!raw.tags.empty()) u["tags"] = raw.tags;
      utts.push_back(u);
      ++report.imported;
      if (note.size() > 1) report.details.push_back(note);
    } catch (const Error& e) {
      note["skipped"] = e.what();
      report.details.push_back(note);
      ++report.skipped;
    }
  }
  if (opt.progress) opt.progress(ids.size(), ids.size(), "");
  if (report.imported == 0)
    throw Error("corpus import: no utterance could be imported (first problem: " +
                report.details.at(0).value("skipped", std::string("unknown")) + ")");

  json speakers = json::object();
  for (auto& [id, a] : acc) {
    Eigen::Index rows = 0;
    for (const auto& p : a.poses) rows += p.rows();
    MatrixRM all(rows, a.poses.front().cols());
    Eigen::Index at = 0;
    for (const auto& p : a.poses) {
      all.middleRows(at, p.rows()) = p;
      at += p.rows();
    }
    const RowVec neutral = estimate_neutral(all, a.db, opt.neutral);
    speakers[id] = {{"neutral", std::vector<float>(neutral.data(), neutral.data() + neutral.size())},
                    {"neutral_method", opt.neutral},
                    {"utterances", a.poses.size()},
                    {"frames", rows}};
  }
  json manifest = {{"format", "glossa-corpus"},
                   {"version", kCorpusVersion},
                   {"landmark_set", out_set->names},
                   {"frame_rate", kFrameRate},
                   {"sample_rate", kSampleRate},
                   {"units", "mm"},
                   {"axes", "x back->front, y right->left, z bottom->top"},
                   {"source", {{"format", source.format()}, {"description", source.describe()}}},
                   {"import",
                    {{"resampling", opt.resampling == Resampling::kNearest ? "nearest"
                                                                            : "antialiased"},
                     {"max_gap_s", opt.max_gap_s},
                     {"neutral", opt.neutral},
                     {"imported", report.imported},
                     {"skipped", report.skipped},
                     {"notes", report.details}}},
                   {"speakers", speakers},
                   {"utterances", utts}};
  io::write_file_atomic(opt.out / "manifest.json", manifest.dump(1));
  return report;
}

}  // namespace glossa::ema
