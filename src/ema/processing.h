#pragma once
// Signal processing on landmark sequences: head stabilisation, dropout repair and resampling.
#include <string>
#include <vector>

#include "ema/landmarks.h"

namespace glossa::ema {

// Per frame, fits the rigid transform (Kabsch: rotation + translation, no scale) that maps the
// reference sensors onto a fixed template and applies it to every sensor. With the three
// references REF-UI, REF-LM and REF-RM the template is the head frame of DESIGN.md: origin at
// the upper incisor, y from the right to the left mastoid, x forward, z up. With other
// references it is their configuration in the first complete frame. Reference sensors are
// removed from the result. Frames where fewer than 3 references are finite become NaN.
// Throws glossa::Error when the set has fewer than 3 reference sensors.
LandmarkSeq stabilise_head(const LandmarkSeq& seq);

struct GapReport {
  int filled_runs = 0;        // NaN runs interpolated
  double longest_gap_s = 0;   // longest NaN run seen, seconds
  std::string worst_sensor;   // sensor with the longest run
  bool ok = true;             // false when a run exceeds the limit (nothing was changed then)
};

// Linearly interpolates NaN runs no longer than `max_gap_s` per sensor coordinate (runs at the
// start or end take the nearest valid value). When any run is longer, or a sensor has no valid
// sample at all, leaves `seq` unchanged and returns ok = false.
GapReport fill_gaps(LandmarkSeq& seq, double max_gap_s);

enum class Resampling { kNearest, kAntialiased };

// Resamples to `out_rate`. kNearest picks the sample nearest each output time, as the papers do
// (250 -> 50 Hz keeps every 5th sample). kAntialiased low-passes and resamples with soxr.
// The output has floor((n - 1) * out_rate / in_rate) + 1 frames.
LandmarkSeq resample(const LandmarkSeq& seq, double out_rate, Resampling method);

Resampling parse_resampling(const std::string& name);

}  // namespace glossa::ema
