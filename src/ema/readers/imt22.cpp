#include "ema/readers/imt22.h"

#include <algorithm>
#include <fstream>
#include <map>
#include <sstream>

#include "core/error.h"
#include "io/npy.h"

namespace glossa::ema {
namespace fs = std::filesystem;

namespace {

std::string lower(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return std::tolower(c); });
  return s;
}

std::string trim(const std::string& s) {
  const auto a = s.find_first_not_of(" \t\r\n");
  if (a == std::string::npos) return "";
  const auto b = s.find_last_not_of(" \t\r\n");
  return s.substr(a, b - a + 1);
}

class Imt22Source : public CorpusSource {
 public:
  Imt22Source(const fs::path& dir, std::string speaker) : dir_(dir), speaker_(std::move(speaker)) {
    if (!fs::is_directory(dir)) throw file_error(dir, "not a folder");
    std::vector<fs::path> lists, transcript_files;
    for (const auto& e : fs::recursive_directory_iterator(dir)) {
      if (!e.is_regular_file()) continue;
      const fs::path& p = e.path();
      const std::string ext = lower(p.extension().string());
      const std::string name = lower(p.filename().string());
      if (ext == ".wav") wav_[p.stem().string()] = p;
      else if (ext == ".npy") npy_[p.stem().string()] = p;
      else if (ext == ".txt" || ext == ".lab" || ext == ".lst" || ext == ".list") {
        if (name.find("train") != std::string::npos || name.find("test") != std::string::npos)
          lists.push_back(p);
        else if (name.rfind("transcript", 0) == 0 || name.rfind("text", 0) == 0)
          transcript_files.push_back(p);
        else
          per_utt_text_[p.stem().string()] = p;
      }
    }
    for (const auto& [id, _] : npy_)
      if (wav_.count(id)) ids_.push_back(id);
    if (ids_.empty())
      throw file_error(dir, "no utterance with both <id>.wav and <id>.npy found in the folder tree");
    for (const auto& p : lists) {
      const std::string split = lower(p.filename().string()).find("train") != std::string::npos
                                    ? "train"
                                    : "test";
      std::ifstream in(p);
      std::string line;
      while (std::getline(in, line)) {
        std::istringstream ss(line);
        std::string tok;
        if (ss >> tok) split_[fs::path(tok).stem().string()] = split;
      }
    }
    for (const auto& p : transcript_files) {
      std::ifstream in(p);
      std::string line;
      while (std::getline(in, line)) {
        std::istringstream ss(line);
        std::string tok;
        if (!(ss >> tok)) continue;
        std::string rest;
        std::getline(ss, rest);
        transcripts_[fs::path(tok).stem().string()] = trim(rest);
      }
    }
  }

  std::string format() const override { return "imt22"; }
  std::vector<std::string> ids() const override { return ids_; }

  RawUtterance load(const std::string& id) const override {
    RawUtterance u;
    u.id = id;
    u.speaker = speaker_;
    u.audio_path = wav_.at(id);
    const fs::path& p = npy_.at(id);
    io::NpyArray a = io::read_npy(p);
    const LandmarkSet set = LandmarkSet::imt22();
    if (a.shape.size() == 3 && a.shape[1] == 10 && a.shape[2] == 3) a.shape = {a.shape[0], 30};
    if (a.shape.size() != 2 || a.shape[1] != 30)
      throw file_error(p, "expected IMT'22 landmarks of shape [frames, 30] (10 sensors x xyz)");
    if (a.shape[0] == 0) throw file_error(p, "no frames");
    u.ema.set = set;
    u.ema.rate = 50.0;
    u.ema.positions =
        Eigen::Map<MatrixRM>(a.data.data(), static_cast<Eigen::Index>(a.shape[0]), 30);
    if (auto it = transcripts_.find(id); it != transcripts_.end()) u.transcript = it->second;
    if (auto it = per_utt_text_.find(id); it != per_utt_text_.end()) {
      std::ifstream in(it->second);
      std::stringstream ss;
      ss << in.rdbuf();
      u.transcript = trim(ss.str());
    }
    u.text = u.transcript.empty() ? id : lower(u.transcript);
    if (auto it = split_.find(id); it != split_.end()) u.tags["split"] = it->second;
    return u;
  }

  nlohmann::json describe() const override {
    return {{"folder", dir_.string()},
            {"layout", "IMT'22 release: 16 kHz wav, [frames, 30] npy at 50 fps"},
            {"axes", "as released (stabilised EMA pose space)"}};
  }

 private:
  fs::path dir_;
  std::string speaker_;
  std::map<std::string, fs::path> wav_, npy_, per_utt_text_;
  std::map<std::string, std::string> split_, transcripts_;
  std::vector<std::string> ids_;
};

}  // namespace

std::unique_ptr<CorpusSource> open_imt22_source(const fs::path& dir, const std::string& speaker) {
  return std::make_unique<Imt22Source>(dir, speaker);
}

}  // namespace glossa::ema
