#pragma once
// Landmark trajectories as files other tools open: CSV (time + one column per sensor axis,
// "TT_x" ...) and .npy float32 [frames, L, 3] for numpy.
#include <filesystem>

#include "ema/landmarks.h"

namespace glossa::exporter {

void write_landmarks_csv(const std::filesystem::path& path, const LandmarkSeq& seq);
void write_landmarks_npy(const std::filesystem::path& path, const LandmarkSeq& seq);

}  // namespace glossa::exporter
