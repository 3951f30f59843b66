#pragma once
// Turns any CorpusSource into a normalised glossa corpus (see corpus.h): head stabilisation
// when reference sensors exist, dropout repair, resampling to 50 fps, audio to 16 kHz mono,
// audio/landmark length reconciliation, and a neutral pose per speaker.
#include <filesystem>
#include <functional>
#include <string>

#include <nlohmann/json.hpp>

#include "audio/audio.h"
#include "ema/processing.h"
#include "ema/source.h"

namespace glossa::ema {

struct ImportOptions {
  std::filesystem::path out;
  Resampling resampling = Resampling::kNearest;
  double max_gap_s = 0.1;          // longer NaN runs make the utterance skipped
  std::string neutral = "mean";    // "mean": mean pose; "silence": mean pose in quiet frames
  double max_length_mismatch_s = 1.0;  // larger audio/EMA length differences skip the utterance
  std::function<void(size_t done, size_t total, const std::string& id)> progress;
};

struct ImportReport {
  size_t imported = 0;
  size_t skipped = 0;
  nlohmann::json details;  // per-utterance notes: skips, filled gaps, length mismatches
};

ImportReport import_corpus(const CorpusSource& source, const ImportOptions& opt);

// Neutral pose estimate from absolute positions [frames, 3L] and per-frame audio energy (dB).
// "mean" ignores the energies; "silence" averages the frames in the quietest 10%.
RowVec estimate_neutral(const MatrixRM& positions, const std::vector<float>& frame_db,
                        const std::string& method);

// Per-frame RMS energy in dB of 16 kHz audio, one value per 20 ms frame (`frames` values).
std::vector<float> frame_energy_db(const Audio& audio, size_t frames);

}  // namespace glossa::ema
