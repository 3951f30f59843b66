#include "ema/readers/npy_meta.h"

#include <algorithm>
#include <cctype>

#include "core/error.h"
#include "io/atomic_file.h"
#include "io/npy.h"

namespace glossa::ema {
namespace fs = std::filesystem;
using nlohmann::json;

namespace {

class NpyMetaSource : public CorpusSource {
 public:
  explicit NpyMetaSource(const fs::path& dir) : dir_(dir) {
    const fs::path mpath = dir / "meta.json";
    if (!fs::exists(mpath)) throw file_error(dir, "no meta.json (needed for the npy layout)");
    try {
      meta_ = json::parse(io::read_file(mpath));
      const json& ema = meta_.at("ema");
      rate_ = ema.at("sample_rate_hz").get<double>();
      for (const json& s : ema.at("sensors")) set_.names.push_back(s.at("code").get<std::string>());
    } catch (const json::exception& e) {
      throw file_error(mpath, std::string("malformed meta.json: ") + e.what());
    }
    if (rate_ <= 0) throw file_error(mpath, "ema.sample_rate_hz must be positive");
    if (set_.size() == 0) throw file_error(mpath, "ema.sensors is empty");
    for (const auto& e : fs::directory_iterator(dir)) {
      if (e.path().extension() == ".npy") ids_.push_back(e.path().stem().string());
    }
    std::sort(ids_.begin(), ids_.end());
  }

  std::string format() const override { return "npy"; }
  std::vector<std::string> ids() const override { return ids_; }

  RawUtterance load(const std::string& id) const override {
    RawUtterance u;
    u.id = id;
    parse_id(id, u);
    u.audio_path = dir_ / (id + ".wav");
    if (!fs::exists(u.audio_path)) throw file_error(u.audio_path, "no audio for utterance " + id);
    const fs::path p = dir_ / (id + ".npy");
    io::NpyArray a = io::read_npy(p);
    if (a.shape.size() != 3 || a.shape[1] != set_.size() || a.shape[2] != 3)
      throw file_error(p, fmt::format("expected shape [frames, {}, 3] as meta.json names {} "
                                      "sensors",
                                      set_.size(), set_.size()));
    if (a.shape[0] == 0) throw file_error(p, "no frames");
    u.ema.set = set_;
    u.ema.rate = rate_;
    u.ema.positions = Eigen::Map<MatrixRM>(a.data.data(), static_cast<Eigen::Index>(a.shape[0]),
                                           static_cast<Eigen::Index>(3 * set_.size()));
    return u;
  }

  json describe() const override {
    json d = {{"folder", dir_.string()}};
    for (const char* key : {"name", "language", "axes", "origin_note"}) {
      if (meta_.contains(key)) d[key] = meta_[key];
      if (meta_.contains("ema") && meta_["ema"].contains(key)) d[key] = meta_["ema"][key];
    }
    return d;
  }

 private:
  void parse_id(const std::string& id, RawUtterance& u) const {
    u.speaker = "speaker";
    if (meta_.contains("speakers")) {
      for (const auto& [name, _] : meta_["speakers"].items())
        if (id.rfind(name, 0) == 0 && name.size() > 0) u.speaker = name;
    }
    const size_t n = id.size();
    if (n >= 2 && std::isdigit(static_cast<unsigned char>(id[n - 1])) &&
        std::isdigit(static_cast<unsigned char>(id[n - 2]))) {
      u.text = id.substr(n - 2);
      if (n >= 4 && meta_.contains("emotions") && meta_["emotions"].contains(id.substr(n - 4, 2)))
        u.tags["emotion"] = id.substr(n - 4, 2);
    } else {
      u.text = id;
    }
  }

  fs::path dir_;
  json meta_;
  double rate_ = 0;
  LandmarkSet set_;
  std::vector<std::string> ids_;
};

}  // namespace

std::unique_ptr<CorpusSource> open_npy_meta_source(const fs::path& dir) {
  return std::make_unique<NpyMetaSource>(dir);
}

}  // namespace glossa::ema
