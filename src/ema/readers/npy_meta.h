#pragma once
// Raw EMA positions as `<id>.npy` [frames, sensors, 3] (mm, any rate) beside `<id>.wav`, with a
// `meta.json` that names the sensors and the rate: the layout of STEM-E2VA as kept in
// ../shared/data/stem-e2va. The meta keys read are ema.sample_rate_hz, ema.sensors[].code,
// and optionally speakers{} and emotions{}: an id that starts with a speaker key belongs to
// that speaker, its last two digits are the text number, and the two letters before them are
// the emotion when they are an emotions key (e.g. CXYFNE01: speaker CXY, emotion NE, text 01).
#include <filesystem>
#include <memory>

#include "ema/source.h"

namespace glossa::ema {

std::unique_ptr<CorpusSource> open_npy_meta_source(const std::filesystem::path& dir);

}  // namespace glossa::ema
