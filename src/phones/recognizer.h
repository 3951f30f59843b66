#pragma once
// Phones from speech with pocketsphinx (CMU Sphinx, US English model of the Debian package
// pocketsphinx-en-us): free phone recognition, and forced alignment of a known transcript.
// Both take glossa's 16 kHz mono audio and return ARPAbet phones plus "SIL" whose times cover
// the whole audio, contiguous, with no two silences in a row.
#include <map>
#include <string>
#include <vector>

#include "audio/audio.h"
#include "phones/phone_seq.h"

namespace glossa::phones {

struct RecognizerOptions {
  // The folder with the acoustic model en-us/, the phone language model en-us-phone.lm.bin and
  // the dictionary cmudict-en-us.dict (the parent folder of such a folder is accepted too).
  // Empty: $GLOSSA_POCKETSPHINX_MODELDIR, else the one pocketsphinx-en-us installs.
  std::string model_dir;
  // Pronunciation dictionary for align_phones (CMU format, "word(2)" for alternates). Empty:
  // cmudict-en-us.dict of the model folder.
  std::string dictionary;
  // Extra pronunciations for align_phones: lower-case word -> one or more space-separated
  // ARPAbet strings ("G L AA S AH"; stress digits are ignored). They replace the dictionary's
  // pronunciations of the word, and let words the dictionary lacks be aligned.
  std::map<std::string, std::vector<std::string>> pronunciations;
  // align_phones lets the aligner choose among a word's alternate pronunciations; false uses
  // only the first one.
  bool alternates = true;
  // Search settings of recognize_phones: pocketsphinx's suggestion for phone decoding (beam
  // 1e-20, language weight 2), with a phone beam of 1e-10 instead of 1e-20, which gave the
  // same phones on test speech at a third of the time.
  double beam = 1e-20;
  double pbeam = 1e-10;
  double lw = 2.0;
  // Beam of align_phones: wide, so the forced path is never pruned away.
  double align_beam = 1e-80;
  // align_phones: probability of a pause between two words (leading and trailing silence are
  // free). Below 1 it keeps the aligner from taking a word-final stop closure for a pause.
  double pause_prob = 1e-3;
};

// The model folder the options resolve to (the one holding en-us/). Throws glossa::Error
// naming the folder, and the package to install, when the acoustic model is missing.
std::string resolve_model_dir(const RecognizerOptions& options = {});

// Free phone recognition (pocketsphinx allphone search with its phone n-gram). The audio must
// be 16 kHz and non-empty.
PhoneSeq recognize_phones(const Audio& audio, const RecognizerOptions& options = {});

// The words of a transcript as the dictionary spells them: lower-cased, split at white space,
// hyphens and slashes, punctuation other than apostrophes removed.
std::vector<std::string> transcript_words(const std::string& transcript);

// The pronunciations (ARPAbet, no stress) of a word: options.pronunciations first, then the
// dictionary. Throws glossa::Error naming the word when it has none.
std::vector<std::vector<std::string>> pronunciations(const std::string& word,
                                                     const RecognizerOptions& options = {});

// Forced alignment of `transcript` to the audio: the phones of the transcript's words in order
// (one pronunciation per word), with optional silence between words and at both ends. Throws
// glossa::Error naming the word for a word without a pronunciation, and when the audio cannot
// be aligned to the transcript.
PhoneSeq align_phones(const Audio& audio, const std::string& transcript,
                      const RecognizerOptions& options = {});

}  // namespace glossa::phones
