#pragma once
// A small generated EMA corpus whose articulation truly determines its audio: smooth
// articulatory controls (tongue height and backness, lip aperture and rounding, voicing)
// drive the 10 sensors of the papers' set and a source-filter voice (glottal pulses through
// formant resonators whose frequencies follow the tongue and lips). Used by the example job
// and the learning test. Written in the npy + meta.json layout (ema/readers/npy_meta.h) at
// 250 Hz, so it goes through `glossa corpus import` like a real corpus.
#include <cstdint>
#include <filesystem>

namespace glossa::ema {

struct SyntheticOptions {
  int speakers = 2;           // each with its own coordinate origin and voice pitch
  int texts = 8;              // distinct "sentences" (target sequences)
  int takes = 3;              // repetitions of each text per speaker
  double seconds = 2.5;       // approximate length of an utterance
  uint64_t seed = 1;
};

void write_synthetic_source(const std::filesystem::path& dir, const SyntheticOptions& opt);

}  // namespace glossa::ema
