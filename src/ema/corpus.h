#pragma once
// A normalised glossa corpus on disk:
//   manifest.json          landmark set, speakers with their neutral poses, utterances, report
//   audio/<id>.wav         16 kHz mono 16-bit PCM
//   landmarks/<id>.npy     float32 [frames, L, 3], mm, head frame, 50 fps
// Articulation is represented as each speaker's neutral pose plus displacements: speakers do
// not share a coordinate origin, so models learn displacements and the neutral is added back.
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "audio/audio.h"
#include "ema/landmarks.h"

namespace glossa::ema {

inline constexpr double kFrameRate = 50.0;
inline constexpr int kSamplesPerFrame = 320;  // 16 kHz / 50 fps
inline constexpr int kCorpusVersion = 1;

struct Utterance {
  std::string id;
  std::string speaker;
  std::string text;
  std::string transcript;
  std::map<std::string, std::string> tags;
  size_t frames = 0;
  double seconds = 0;
};

struct Speaker {
  std::string id;
  RowVec neutral;              // 1 x 3L, mm
  std::string neutral_method;  // "mean" or "silence"
};

class Corpus {
 public:
  // Reads and checks manifest.json. Throws glossa::Error naming the file on any problem.
  static Corpus load(const std::filesystem::path& root);

  const std::filesystem::path& root() const { return root_; }
  const LandmarkSet& landmark_set() const { return set_; }
  const std::vector<Utterance>& utterances() const { return utts_; }
  const std::map<std::string, Speaker>& speakers() const { return speakers_; }
  const Speaker& speaker(const std::string& id) const;
  const Utterance& utterance(const std::string& id) const;
  const nlohmann::json& manifest() const { return manifest_; }

  std::filesystem::path audio_path(const Utterance& u) const;
  std::filesystem::path landmarks_path(const Utterance& u) const;
  Audio load_audio(const Utterance& u) const;
  // Absolute positions [frames, 3L]; checks shape and finiteness.
  LandmarkSeq load_landmarks(const Utterance& u) const;

 private:
  std::filesystem::path root_;
  LandmarkSet set_;
  std::vector<Utterance> utts_;
  std::map<std::string, Speaker> speakers_;
  nlohmann::json manifest_;
};

}  // namespace glossa::ema
