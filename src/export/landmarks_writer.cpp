#include "export/landmarks_writer.h"

#include <fmt/format.h>

#include "io/atomic_file.h"
#include "io/npy.h"

namespace glossa::exporter {

void write_landmarks_csv(const std::filesystem::path& path, const LandmarkSeq& seq) {
  std::string out = "time_s";
  for (const auto& n : seq.set.names)
    for (const char* ax : {"_x", "_y", "_z"}) out += "," + n + ax;
  out += "\n";
  for (size_t f = 0; f < seq.frames(); ++f) {
    out += fmt::format("{:.3f}", double(f) / seq.rate);
    for (size_t c = 0; c < seq.dims(); ++c)
      out += fmt::format(",{:.4f}", seq.positions(static_cast<Eigen::Index>(f), static_cast<Eigen::Index>(c)));
    out += "\n";
  }
  io::write_file_atomic(path, out);
}

void write_landmarks_npy(const std::filesystem::path& path, const LandmarkSeq& seq) {
  io::write_npy(path, seq.positions.data(), {seq.frames(), seq.set.size(), 3});
}

}  // namespace glossa::exporter
