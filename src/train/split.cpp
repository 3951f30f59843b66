#include "train/split.h"

#include <algorithm>
#include <random>
#include <set>
#include <sstream>

#include "core/error.h"

namespace glossa::train {

namespace {

std::set<std::string> parse_list(const std::string& s) {
  std::set<std::string> out;
  std::stringstream ss(s);
  std::string tok;
  while (std::getline(ss, tok, ',')) {
    tok.erase(0, tok.find_first_not_of(' '));
    tok.erase(tok.find_last_not_of(' ') + 1);
    if (!tok.empty()) out.insert(tok);
  }
  return out;
}

}  // namespace

Split make_split(const ema::Corpus& corpus, const std::string& rule, double val_fraction,
                 uint64_t seed) {
  if (val_fraction < 0 || val_fraction >= 1) throw Error("split: val fraction must be in [0, 1)");
  Split s;
  s.rule = rule;
  const auto colon = rule.find(':');
  const std::string kind = rule.substr(0, colon);
  const std::string arg = colon == std::string::npos ? "" : rule.substr(colon + 1);
  std::mt19937_64 rng(seed);
  std::vector<const ema::Utterance*> rest;
  const auto& utts = corpus.utterances();

  if (kind == "text" || kind == "speaker") {
    const auto keys = parse_list(arg);
    if (keys.empty()) throw Error("split '" + rule + "': name at least one " + kind);
    std::set<std::string> seen;
    for (const auto& u : utts) {
      const std::string& key = kind == "text" ? u.text : u.speaker;
      seen.insert(key);
      (keys.count(key) ? s.test : s.train).push_back(u.id);
    }
    for (const auto& k : keys)
      if (!seen.count(k)) throw Error("split '" + rule + "': the corpus has no " + kind + " '" + k + "'");
  } else if (kind == "tag") {
    if (arg.empty()) throw Error("split '" + rule + "': name the tag, e.g. tag:split");
    for (const auto& u : utts) {
      auto it = u.tags.find(arg);
      (it != u.tags.end() && it->second == "test" ? s.test : s.train).push_back(u.id);
    }
    if (s.test.empty()) throw Error("split '" + rule + "': no utterance is tagged " + arg + "=test");
  } else if (kind == "random") {
    double frac = 0;
    try {
      frac = std::stod(arg);
    } catch (...) {
      throw Error("split '" + rule + "': expected random:FRACTION");
    }
    if (frac <= 0 || frac >= 1) throw Error("split '" + rule + "': fraction must be in (0, 1)");
    std::vector<std::string> ids;
    for (const auto& u : utts) ids.push_back(u.id);
    std::shuffle(ids.begin(), ids.end(), rng);
    const auto n_test = static_cast<size_t>(std::max(1.0, frac * ids.size()));
    s.test.assign(ids.begin(), ids.begin() + static_cast<long>(n_test));
    s.train.assign(ids.begin() + static_cast<long>(n_test), ids.end());
  } else if (kind == "none") {
    for (const auto& u : utts) s.train.push_back(u.id);
  } else {
    throw Error("unknown split rule '" + rule + "' (use text:..., speaker:..., tag:..., random:F or none)");
  }
  if (s.train.empty()) throw Error("split '" + rule + "' leaves no training utterances");

  if (val_fraction > 0) {
    if (kind == "text") {
      // Hold out whole texts of the training part.
      std::vector<std::string> texts;
      for (const auto& id : s.train) {
        const std::string& t = corpus.utterance(id).text;
        if (std::find(texts.begin(), texts.end(), t) == texts.end()) texts.push_back(t);
      }
      std::sort(texts.begin(), texts.end());
      std::shuffle(texts.begin(), texts.end(), rng);
      const auto n_val = static_cast<size_t>(std::max(1.0, std::round(val_fraction * texts.size())));
      if (n_val >= texts.size()) throw Error("split '" + rule + "': too few texts for validation");
      const std::set<std::string> val_texts(texts.begin(), texts.begin() + static_cast<long>(n_val));
      std::vector<std::string> train;
      for (const auto& id : s.train)
        (val_texts.count(corpus.utterance(id).text) ? s.val : train).push_back(id);
      s.train = train;
    } else {
      std::vector<std::string> ids = s.train;
      std::shuffle(ids.begin(), ids.end(), rng);
      const auto n_val = static_cast<size_t>(std::max(1.0, std::round(val_fraction * ids.size())));
      if (n_val >= ids.size()) throw Error("split '" + rule + "': too few utterances for validation");
      s.val.assign(ids.begin(), ids.begin() + static_cast<long>(n_val));
      s.train.assign(ids.begin() + static_cast<long>(n_val), ids.end());
      std::sort(s.val.begin(), s.val.end());
      std::sort(s.train.begin(), s.train.end());
    }
  }
  return s;
}

}  // namespace glossa::train
