#include "features/cache.h"

#include <xxhash.h>

#include <cstdlib>

#include "core/error.h"
#include "io/npy.h"

namespace glossa::features {
namespace fs = std::filesystem;

fs::path FeatureCache::default_dir() {
  if (const char* g = std::getenv("GLOSSA_CACHE"); g && *g) return g;
  if (const char* x = std::getenv("XDG_CACHE_HOME"); x && *x) return fs::path(x) / "glossa";
  if (const char* h = std::getenv("HOME"); h && *h) return fs::path(h) / ".cache" / "glossa";
  return fs::temp_directory_path() / "glossa-cache";
}

fs::path FeatureCache::entry_path(const Encoder& encoder, const Audio& audio) const {
  XXH3_state_t* st = XXH3_createState();
  XXH3_64bits_reset(st);
  XXH3_64bits_update(st, audio.samples.data(), audio.samples.size() * sizeof(float));
  XXH3_64bits_update(st, &audio.sample_rate, sizeof(audio.sample_rate));
  const std::string cfg = encoder.config().dump();
  XXH3_64bits_update(st, cfg.data(), cfg.size());
  const XXH64_hash_t h = XXH3_64bits_digest(st);
  XXH3_freeState(st);
  return dir_ / "features" / encoder.name() / fmt::format("{:016x}.npy", h);
}

MatrixRM FeatureCache::get(const Encoder& encoder, const Audio& audio) const {
  if (dir_.empty()) return encoder.encode(audio);
  const fs::path p = entry_path(encoder, audio);
  const auto expect_rows = static_cast<size_t>(frame_count(audio.samples.size()));
  if (fs::exists(p)) {
    try {
      io::NpyArray a = io::read_npy(p);
      if (a.shape.size() == 2 && a.shape[0] == expect_rows &&
          a.shape[1] == static_cast<size_t>(encoder.dims()))
        return Eigen::Map<MatrixRM>(a.data.data(), static_cast<Eigen::Index>(a.shape[0]),
                                    static_cast<Eigen::Index>(a.shape[1]));
    } catch (const Error&) {
      // A damaged entry is recomputed and overwritten below.
    }
  }
  MatrixRM f = encoder.encode(audio);
  try {
    io::write_npy(p, f.data(), {static_cast<size_t>(f.rows()), static_cast<size_t>(f.cols())});
  } catch (const Error&) {
    // An unwritable cache only costs time.
  }
  return f;
}

}  // namespace glossa::features
