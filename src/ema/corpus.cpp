#include "ema/corpus.h"

#include <cmath>

#include "audio/decode.h"
#include "core/error.h"
#include "io/atomic_file.h"
#include "io/npy.h"

namespace glossa::ema {
namespace fs = std::filesystem;
using nlohmann::json;

Corpus Corpus::load(const fs::path& root) {
  const fs::path mpath = root / "manifest.json";
  if (!fs::exists(mpath))
    throw file_error(root, "not a glossa corpus (no manifest.json; create one with "
                           "`glossa corpus import`)");
  Corpus c;
  c.root_ = root;
  try {
    c.manifest_ = json::parse(io::read_file(mpath));
    const json& m = c.manifest_;
    if (m.value("format", "") != "glossa-corpus")
      throw file_error(mpath, "not a glossa corpus manifest (format field missing)");
    const int version = m.at("version").get<int>();
    if (version > kCorpusVersion)
      throw file_error(mpath, "corpus version " + std::to_string(version) +
                                  " is newer than this glossa understands");
    c.set_.names = m.at("landmark_set").get<std::vector<std::string>>();
    if (c.set_.size() == 0) throw file_error(mpath, "empty landmark set");
    for (const auto& [id, s] : m.at("speakers").items()) {
      Speaker sp;
      sp.id = id;
      const auto neutral = s.at("neutral").get<std::vector<float>>();
      if (neutral.size() != 3 * c.set_.size())
        throw file_error(mpath, "speaker " + id + ": neutral pose has " +
                                    std::to_string(neutral.size()) + " values, expected " +
                                    std::to_string(3 * c.set_.size()));
      sp.neutral = Eigen::Map<const RowVec>(neutral.data(), 1, neutral.size());
      sp.neutral_method = s.value("neutral_method", "mean");
      c.speakers_[id] = sp;
    }
    for (const json& u : m.at("utterances")) {
      Utterance utt;
      utt.id = u.at("id").get<std::string>();
      utt.speaker = u.at("speaker").get<std::string>();
      utt.text = u.value("text", "");
      utt.transcript = u.value("transcript", "");
      utt.frames = u.at("frames").get<size_t>();
      utt.seconds = u.value("seconds", utt.frames / kFrameRate);
      if (u.contains("tags")) utt.tags = u["tags"].get<std::map<std::string, std::string>>();
      if (!c.speakers_.count(utt.speaker))
        throw file_error(mpath, "utterance " + utt.id + " names unknown speaker " + utt.speaker);
      c.utts_.push_back(std::move(utt));
    }
  } catch (const json::exception& e) {
    throw file_error(mpath, std::string("malformed manifest: ") + e.what());
  }
  return c;
}

const Speaker& Corpus::speaker(const std::string& id) const {
  auto it = speakers_.find(id);
  if (it == speakers_.end()) throw file_error(root_, "no speaker '" + id + "' in this corpus");
  return it->second;
}

const Utterance& Corpus::utterance(const std::string& id) const {
  for (const auto& u : utts_)
    if (u.id == id) return u;
  throw file_error(root_, "no utterance '" + id + "' in this corpus");
}

fs::path Corpus::audio_path(const Utterance& u) const { return root_ / "audio" / (u.id + ".wav"); }

fs::path Corpus::landmarks_path(const Utterance& u) const {
  return root_ / "landmarks" / (u.id + ".npy");
}

Audio Corpus::load_audio(const Utterance& u) const { return audio::load_audio(audio_path(u)); }

LandmarkSeq Corpus::load_landmarks(const Utterance& u) const {
  const fs::path p = landmarks_path(u);
  io::NpyArray a = io::read_npy(p);
  const size_t L = set_.size();
  if (a.shape.size() != 3 || a.shape[1] != L || a.shape[2] != 3)
    throw file_error(p, "expected landmarks of shape [frames, " + std::to_string(L) + ", 3]");
  LandmarkSeq seq;
  seq.set = set_;
  seq.rate = kFrameRate;
  seq.positions = Eigen::Map<MatrixRM>(a.data.data(), static_cast<Eigen::Index>(a.shape[0]),
                                       static_cast<Eigen::Index>(3 * L));
  if (!seq.positions.allFinite()) throw file_error(p, "landmarks contain NaN or infinity");
  return seq;
}

}  // namespace glossa::ema
