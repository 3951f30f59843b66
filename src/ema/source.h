#pragma once
// A corpus source: something on disk in a corpus' own layout that yields utterances of raw
// EMA (native rate, native sensors, NaN where a sensor dropped out) plus the audio file.
// Each reader in ema/readers/ implements this; `import_corpus` turns any source into a
// normalised glossa corpus.
#include <filesystem>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "ema/landmarks.h"

namespace glossa::ema {

struct RawUtterance {
  std::string id;
  std::string speaker;
  std::string text;        // text (sentence) identifier, used for text-disjoint splits
  std::string transcript;  // words, when the corpus has them
  std::map<std::string, std::string> tags;  // e.g. emotion, split from a corpus' own lists
  std::filesystem::path audio_path;
  LandmarkSeq ema;  // native rate and sensors, mm, may contain NaN
};

class CorpusSource {
 public:
  virtual ~CorpusSource() = default;
  // Short name of the layout ("stem", "imt22", "ag501", "est").
  virtual std::string format() const = 0;
  // Utterance ids in a stable order.
  virtual std::vector<std::string> ids() const = 0;
  // Loads one utterance. Throws glossa::Error naming the file on malformed data.
  virtual RawUtterance load(const std::string& id) const = 0;
  // Free-form description stored in the corpus manifest (axes, origin, provenance).
  virtual nlohmann::json describe() const { return nlohmann::json::object(); }
};

// Names of reference (head-stabilisation) sensors: REF-UI (upper incisor), REF-LM and REF-RM
// (left and right mastoid), or any other name starting with "REF".
bool is_reference_sensor(const std::string& name);

}  // namespace glossa::ema
