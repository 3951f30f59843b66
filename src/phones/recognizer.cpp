#include "phones/recognizer.h"

#include <pocketsphinx.h>
#include <sphinxbase/cmd_ln.h>
#include <sphinxbase/err.h>
#include <sphinxbase/fsg_model.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <memory>
#include <mutex>
#include <set>
#include <string_view>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "core/error.h"

namespace glossa::phones {
namespace {
namespace fs = std::filesystem;

constexpr double kFrameSeconds = 0.01;  // pocketsphinx's default -frate 100
constexpr const char* kAcousticModel = "en-us";
constexpr const char* kPhoneLm = "en-us-phone.lm.bin";
constexpr const char* kDictionary = "cmudict-en-us.dict";
constexpr const char* kSilWord = "SIL";

// sphinxbase logs every step to stderr; glossa reports its own errors instead.
void silence_sphinx_log() {
  static std::once_flag once;
  std::call_once(once, [] { err_set_logfp(nullptr); });
}

struct DecoderFree {
  void operator()(ps_decoder_t* ps) const { ps_free(ps); }
};
using Decoder = std::unique_ptr<ps_decoder_t, DecoderFree>;

struct FsgFree {
  void operator()(fsg_model_t* f) const { fsg_model_free(f); }
};
using Fsg = std::unique_ptr<fsg_model_t, FsgFree>;

std::string beam_str(double v) { return fmt::format("{:g}", v); }

void check_audio(const Audio& audio, const char* what) {
  if (audio.sample_rate != kSampleRate)
    throw Error(fmt::format("{}: audio must be {} Hz mono, got {} Hz", what, kSampleRate,
                            audio.sample_rate));
  if (audio.samples.empty()) throw Error(fmt::format("{}: the audio is empty", what));
  // pocketsphinx needs at least a few frames to produce anything.
  if (audio.samples.size() < static_cast<size_t>(kSampleRate / 20))
    throw Error(fmt::format("{}: the audio is too short ({:.3f} s; at least 0.05 s needed)", what,
                            audio.seconds()));
}

void check_options(const RecognizerOptions& o, const char* what) {
  auto prob = [what](const char* name, double v) {
    if (!(v > 0 && v <= 1))
      throw Error(
          fmt::format("{}: RecognizerOptions::{} must be in (0, 1], got {}", what, name, v));
  };
  prob("beam", o.beam);
  prob("pbeam", o.pbeam);
  prob("align_beam", o.align_beam);
  prob("pause_prob", o.pause_prob);
  if (!(o.lw > 0 && std::isfinite(o.lw)))
    throw Error(fmt::format("{}: RecognizerOptions::lw must be positive, got {}", what, o.lw));
}

std::vector<int16_t> to_pcm16(const std::vector<float>& x) {
  std::vector<int16_t> out(x.size());
  for (size_t i = 0; i < x.size(); ++i) {
    float v = std::isfinite(x[i]) ? std::clamp(x[i], -1.0f, 1.0f) : 0.0f;
    out[i] = static_cast<int16_t>(std::lround(v * 32767.0f));
  }
  return out;
}

// Creates a decoder from "-name value" pairs (the acoustic model and quiet logging are added).
Decoder make_decoder(const std::string& model_dir, std::vector<std::string> args,
                     const char* what) {
  silence_sphinx_log();
  const std::string hmm = (fs::path(model_dir) / kAcousticModel).string();
  // No voice-activity cut (it would shift the times); a fixed-seed dither so digital silence
  // does not become degenerate features, and the results stay reproducible.
  std::vector<std::string> all = {"-hmm",    hmm,   "-remove_silence", "no",
                                  "-dither", "yes", "-seed",           "1"};
  all.insert(all.end(), args.begin(), args.end());
  std::vector<char*> argv;
  std::string prog = "glossa";
  argv.push_back(prog.data());
  for (auto& a : all) argv.push_back(a.data());
  cmd_ln_t* config =
      cmd_ln_parse_r(nullptr, ps_args(), static_cast<int32>(argv.size()), argv.data(), TRUE);
  if (!config) throw Error(fmt::format("{}: bad pocketsphinx configuration", what));
  Decoder ps(ps_init(config));
  cmd_ln_free_r(config);
  if (!ps)
    throw Error(fmt::format("{}: pocketsphinx could not load the model in {}", what, model_dir));
  return ps;
}

struct Segment {
  std::string word;
  int first = 0, last = 0;  // frames, inclusive
};

// Decodes the whole utterance with the decoder's active search and returns its segments.
std::vector<Segment> decode(ps_decoder_t* ps, const Audio& audio, const char* what) {
  const auto pcm = to_pcm16(audio.samples);
  if (ps_start_utt(ps) < 0) throw Error(fmt::format("{}: pocketsphinx could not start", what));
  const int frames = ps_process_raw(ps, pcm.data(), pcm.size(), FALSE, TRUE);
  if (ps_end_utt(ps) < 0 || frames < 0)
    throw Error(fmt::format("{}: pocketsphinx failed to decode the audio", what));
  std::vector<Segment> segs;
  for (ps_seg_t* it = ps_seg_iter(ps); it; it = ps_seg_next(it)) {
    Segment s;
    const char* w = ps_seg_word(it);
    s.word = w ? w : "";
    ps_seg_frames(it, &s.first, &s.last);
    segs.push_back(std::move(s));
  }
  return segs;
}

// Segments -> contiguous phones covering [0, seconds]: pocketsphinx's units normalised
// (anything else is silence), gaps filled with silence, consecutive silences merged.
PhoneSeq to_phone_seq(const std::vector<Segment>& segs, double seconds) {
  PhoneSeq raw;
  for (const auto& s : segs) {
    if (s.last < s.first) continue;
    std::string p = normalize_phone(s.word);
    if (p.empty()) p = kSilWord;
    raw.push_back({p, s.first * kFrameSeconds, (s.last + 1) * kFrameSeconds});
  }
  PhoneSeq out;
  auto push = [&out](TimedPhone p) {
    if (!out.empty() && out.back().phone == kSilWord && p.phone == kSilWord) {
      out.back().end = std::max(out.back().end, p.end);
      return;
    }
    out.push_back(std::move(p));
  };
  double t = 0;
  for (auto& p : raw) {
    if (p.start > t + 1e-9) {
      if (p.start - t >= kFrameSeconds - 1e-9)
        push({kSilWord, t, p.start});
      else if (!out.empty())
        out.back().end = p.start;
      else
        p.start = t;
    }
    p.start = std::max(p.start, t);
    p.end = std::max(p.end, p.start);
    t = p.end;
    push(std::move(p));
  }
  if (t < seconds) push({kSilWord, t, seconds});
  // The last frame may reach past the end of the samples.
  for (auto& p : out) {
    p.start = std::min(p.start, seconds);
    p.end = std::min(p.end, seconds);
  }
  while (out.size() > 1 && out.back().phone == kSilWord && out.back().end <= out.back().start)
    out.pop_back();
  return out;
}

using Pron = std::vector<std::string>;
using Prons = std::map<std::string, std::vector<Pron>>;

// Parses "ARPAbet phones" (stress digits allowed). Returns false on an unknown symbol.
bool parse_pron(std::string_view text, Pron* pron, std::string* bad) {
  pron->clear();
  size_t i = 0;
  while (i < text.size()) {
    while (i < text.size() && std::isspace(static_cast<unsigned char>(text[i]))) ++i;
    size_t j = i;
    while (j < text.size() && !std::isspace(static_cast<unsigned char>(text[j]))) ++j;
    if (j == i) break;
    const std::string_view sym = text.substr(i, j - i);
    std::string p = normalize_phone(sym);
    if (p.empty() || p == kSilWord) {
      *bad = std::string(sym);
      return false;
    }
    pron->push_back(std::move(p));
    i = j;
  }
  return true;
}

// The dictionary's text, read once per path.
std::shared_ptr<const std::string> dict_text(const std::string& path) {
  static std::mutex mu;
  static std::map<std::string, std::shared_ptr<const std::string>> cache;
  std::lock_guard lock(mu);
  if (auto it = cache.find(path); it != cache.end()) return it->second;
  std::ifstream in(path, std::ios::binary);
  if (!in) throw file_error(path, "cannot open the pronunciation dictionary");
  auto text = std::make_shared<const std::string>(std::istreambuf_iterator<char>(in),
                                                  std::istreambuf_iterator<char>());
  if (text->empty()) throw file_error(path, "the pronunciation dictionary is empty");
  cache.emplace(path, text);
  return text;
}

// The pronunciations of `words` (lower case) in a CMU-format dictionary ("word PH PH ...",
// "word(2) ..." for alternates, "#" comments). Words it lacks are absent from the result;
// entries with units other than ARPAbet phones are skipped.
Prons lookup(const std::string& path, const std::set<std::string>& words) {
  const auto text = dict_text(path);
  Prons out;
  const std::string& t = *text;
  for (size_t pos = 0; pos < t.size();) {
    size_t eol = t.find('\n', pos);
    if (eol == std::string::npos) eol = t.size();
    std::string_view line(t.data() + pos, eol - pos);
    pos = eol + 1;
    const size_t head_end = std::min(line.find_first_of(" \t"), line.size());
    std::string word(line.substr(0, head_end));
    if (auto paren = word.find('('); paren != std::string::npos && paren > 0 && word.back() == ')')
      word.resize(paren);
    for (auto& c : word) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    if (!words.count(word)) continue;
    std::string_view rest = line.substr(head_end);
    if (auto hash = rest.find('#'); hash != std::string_view::npos) rest = rest.substr(0, hash);
    Pron pron;
    std::string bad;
    if (!parse_pron(rest, &pron, &bad) || pron.empty()) continue;
    auto& prons = out[word];
    if (std::find(prons.begin(), prons.end(), pron) == prons.end())
      prons.push_back(std::move(pron));
  }
  return out;
}

std::string dictionary_path(const RecognizerOptions& o) {
  if (!o.dictionary.empty()) return o.dictionary;
  return (fs::path(resolve_model_dir(o)) / kDictionary).string();
}

// Whether `phones` (no SIL) is one pronunciation of each word in turn.
bool fits(const std::vector<std::string>& phones, const std::vector<std::vector<Pron>>& words) {
  std::set<size_t> at = {0};
  for (const auto& prons : words) {
    std::set<size_t> next;
    for (size_t pos : at)
      for (const auto& pron : prons)
        if (pos + pron.size() <= phones.size() &&
            std::equal(pron.begin(), pron.end(), phones.begin() + static_cast<long>(pos)))
          next.insert(pos + pron.size());
    at = std::move(next);
    if (at.empty()) return false;
  }
  return at.count(phones.size()) > 0;
}

// options.pronunciations first, then the dictionary (one pass for all words).
std::vector<std::vector<Pron>> pronunciations_of(const std::vector<std::string>& words,
                                                 const RecognizerOptions& options) {
  auto given_for = [&](const std::string& w) -> const std::vector<std::string>* {
    auto it = options.pronunciations.find(w);
    return it != options.pronunciations.end() && !it->second.empty() ? &it->second : nullptr;
  };
  std::set<std::string> wanted;
  for (const auto& w : words)
    if (!given_for(w)) wanted.insert(w);
  Prons found;
  std::string path;
  if (!wanted.empty()) {
    path = dictionary_path(options);
    found = lookup(path, wanted);
  }
  std::vector<std::string> missing;
  for (const auto& w : wanted)
    if (!found.count(w)) missing.push_back(fmt::format("'{}'", w));
  if (missing.size() == 1)
    throw Error(fmt::format(
        "the word {} is not in the pronunciation dictionary {}; spell it differently or give its "
        "pronunciation (RecognizerOptions::pronunciations, glossa phones --pron WORD=PHONES)",
        missing[0], path));
  if (!missing.empty())
    throw Error(fmt::format(
        "the words {} are not in the pronunciation dictionary {}; spell them differently or give "
        "their pronunciations (RecognizerOptions::pronunciations, glossa phones --pron "
        "WORD=PHONES)",
        fmt::join(missing, ", "), path));
  std::vector<std::vector<Pron>> out;
  for (const auto& w : words) {
    if (const auto* texts = given_for(w)) {
      std::vector<Pron> given;
      for (const auto& text : *texts) {
        Pron pron;
        std::string bad;
        if (!parse_pron(text, &pron, &bad))
          throw Error(fmt::format("pronunciation '{}' of '{}': '{}' is not an ARPAbet phone", text,
                                  w, bad));
        if (pron.empty()) throw Error(fmt::format("empty pronunciation given for '{}'", w));
        given.push_back(std::move(pron));
      }
      out.push_back(std::move(given));
      continue;
    }
    out.push_back(found.at(w));
  }
  return out;
}

}  // namespace

std::string resolve_model_dir(const RecognizerOptions& options) {
  std::string dir = options.model_dir;
  const char* source = "RecognizerOptions::model_dir";
  if (dir.empty()) {
    if (const char* env = std::getenv("GLOSSA_POCKETSPHINX_MODELDIR"); env && *env) {
      dir = env;
      source = "$GLOSSA_POCKETSPHINX_MODELDIR";
    } else {
      dir = GLOSSA_POCKETSPHINX_MODELDIR;
      source = "the default model folder";
    }
  }
  const fs::path p(dir);
  std::error_code ec;
  if (fs::exists(p / kAcousticModel / "mdef", ec)) return p.string();
  if (fs::exists(p / "en-us" / kAcousticModel / "mdef", ec)) return (p / "en-us").string();
  throw Error(fmt::format(
      "{}: no pocketsphinx US English model here ({}; expected {}/mdef, {} and {}); install the "
      "Debian package pocketsphinx-en-us or point GLOSSA_POCKETSPHINX_MODELDIR at the model",
      dir, source, kAcousticModel, kPhoneLm, kDictionary));
}

PhoneSeq recognize_phones(const Audio& audio, const RecognizerOptions& options) {
  constexpr const char* what = "phone recognition";
  check_audio(audio, what);
  check_options(options, what);
  const std::string dir = resolve_model_dir(options);
  const std::string lm = (fs::path(dir) / kPhoneLm).string();
  if (!fs::exists(lm))
    throw file_error(lm,
                     "phone language model missing; install the Debian package "
                     "pocketsphinx-en-us");
  Decoder ps = make_decoder(
      dir,
      {"-allphone", lm, "-dict", "/dev/null", "-backtrace", "yes", "-beam", beam_str(options.beam),
       "-pbeam", beam_str(options.pbeam), "-lw", beam_str(options.lw)},
      what);
  const auto segs = decode(ps.get(), audio, what);
  if (segs.empty())
    throw Error(
        fmt::format("{}: pocketsphinx found no hypothesis for the audio ({:.2f} s; too short?)",
                    what, audio.seconds()));
  return to_phone_seq(segs, audio.seconds());
}

std::vector<std::string> transcript_words(const std::string& transcript) {
  std::vector<std::string> words;
  std::string cur;
  auto flush = [&] {
    // Quotes around a word are not part of it.
    size_t b = cur.find_first_not_of('\''), e = cur.find_last_not_of('\'');
    if (b != std::string::npos) words.push_back(cur.substr(b, e - b + 1));
    cur.clear();
  };
  for (unsigned char c : transcript) {
    if (std::isspace(c) || c == '-' || c == '/')
      flush();
    else if (std::isalnum(c) || c == '\'' || c >= 0x80)
      cur += static_cast<char>(std::tolower(c));
  }
  flush();
  return words;
}

std::vector<std::vector<std::string>> pronunciations(const std::string& word,
                                                     const RecognizerOptions& options) {
  return pronunciations_of({word}, options).front();
}

PhoneSeq align_phones(const Audio& audio, const std::string& transcript,
                      const RecognizerOptions& options) {
  constexpr const char* what = "phone alignment";
  check_audio(audio, what);
  check_options(options, what);
  const auto words = transcript_words(transcript);
  if (words.empty())
    throw Error(fmt::format("{}: the transcript '{}' has no words", what, transcript));
  auto prons = pronunciations_of(words, options);
  if (!options.alternates)
    for (auto& p : prons) p.resize(1);

  const std::string dir = resolve_model_dir(options);
  const std::string beam = beam_str(options.align_beam);
  Decoder ps = make_decoder(dir,
                            {"-dict", "/dev/null", "-fsgusefiller", "no", "-bestpath", "no",
                             "-beam", beam, "-pbeam", beam, "-wbeam", beam, "-maxhmmpf", "-1"},
                            what);
  // A dictionary whose words are the phones themselves, so the segments are phones.
  for (const auto& p : arpabet())
    if (ps_add_word(ps.get(), p.c_str(), p.c_str(), FALSE) < 0)
      throw Error(fmt::format("{}: the acoustic model lacks the phone {}", what, p));

  // The grammar: states at word boundaries, each with an optional silence (a self-loop), and
  // for each word one chain of phone arcs per pronunciation.
  int n_states = 1;
  for (const auto& alts : prons)
    for (const auto& pron : alts) n_states += static_cast<int>(pron.size()) - 1;
  n_states += static_cast<int>(prons.size());
  Fsg fsg(fsg_model_init("glossa_align", ps_get_logmath(ps.get()), 1.0f, n_states));
  const int sil = fsg_model_word_add(fsg.get(), kSilWord);
  const int32 pause_logp = logmath_log(ps_get_logmath(ps.get()), options.pause_prob);
  int next_state = 1, boundary = 0;
  fsg->start_state = 0;
  fsg_model_trans_add(fsg.get(), 0, 0, 0, sil);
  for (const auto& alts : prons) {
    const int end = next_state++;
    for (const auto& pron : alts) {
      int from = boundary;
      for (size_t i = 0; i < pron.size(); ++i) {
        const int to = i + 1 == pron.size() ? end : next_state++;
        fsg_model_trans_add(fsg.get(), from, to, 0, fsg_model_word_add(fsg.get(), pron[i].c_str()));
        from = to;
      }
    }
    const bool last = &alts == &prons.back();
    fsg_model_trans_add(fsg.get(), end, end, last ? 0 : pause_logp, sil);
    boundary = end;
  }
  fsg->final_state = boundary;
  if (next_state != n_states) throw std::logic_error("align_phones: grammar state count");
  // ps_set_fsg takes its own reference.
  if (ps_set_fsg(ps.get(), "align", fsg.get()) < 0 || ps_set_search(ps.get(), "align") < 0)
    throw Error(fmt::format("{}: pocketsphinx rejected the alignment grammar", what));

  const auto segs = decode(ps.get(), audio, what);
  PhoneSeq seq = to_phone_seq(segs, audio.seconds());
  std::vector<std::string> phones;
  for (const auto& p : seq)
    if (p.phone != kSilWord) phones.push_back(p.phone);
  if (phones.empty() || !fits(phones, prons))
    throw Error(fmt::format(
        "{}: the audio ({:.2f} s) could not be aligned to the transcript '{}' (the decoder did "
        "not reach the end of the transcript; is it the right text for this audio?)",
        what, audio.seconds(), transcript));
  return seq;
}

}  // namespace glossa::phones
