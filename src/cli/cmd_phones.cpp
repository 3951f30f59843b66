#include <filesystem>

#include "audio/decode.h"
#include "cli/commands.h"
#include "core/error.h"
#include "phones/recognizer.h"

namespace glossa::cli {

void add_phones_command(CLI::App& app, std::vector<std::pair<CLI::App*, Run>>& runs) {
  struct Args {
    std::string audio, text, out, model_dir;
    std::vector<std::string> prons;
  };
  auto a = std::make_shared<Args>();
  CLI::App* p = app.add_subcommand(
      "phones",
      "Phones (ARPAbet + SIL) with their times from speech, with pocketsphinx: free phone "
      "recognition, or forced alignment to a transcript with --text");
  p->add_option("audio", a->audio, "Audio file (WAV, FLAC, OGG, MP3; any rate, any channels)")
      ->required();
  p->add_option("-t,--text", a->text,
                "Transcript of the audio: align its dictionary pronunciation (CMU dictionary) "
                "instead of recognising phones freely");
  p->add_option("-o,--out", a->out,
                "Write the phone file ('start end PHONE' lines, seconds) here instead of stdout");
  p->add_option("--pron", a->prons,
                "Pronunciation for --text, WORD=PHONES (ARPAbet, e.g. 'glossa=G L AA S AH'); "
                "repeat for more words or alternates; replaces the dictionary's");
  p->add_option("--model-dir", a->model_dir,
                "pocketsphinx model folder (default: $GLOSSA_POCKETSPHINX_MODELDIR, else the "
                "one of the Debian package pocketsphinx-en-us)");
  runs.emplace_back(p, [a] {
    phones::RecognizerOptions options;
    options.model_dir = a->model_dir;
    for (const auto& entry : a->prons) {
      const auto eq = entry.find('=');
      const auto words = eq == std::string::npos ? std::vector<std::string>{}
                                                 : phones::transcript_words(entry.substr(0, eq));
      if (words.size() != 1) throw Error(fmt::format("--pron '{}': expected WORD=PHONES", entry));
      options.pronunciations[words[0]].push_back(entry.substr(eq + 1));
    }
    const Audio audio = audio::load_audio(a->audio);
    const phones::PhoneSeq seq = a->text.empty() ? phones::recognize_phones(audio, options)
                                                 : phones::align_phones(audio, a->text, options);
    if (a->out.empty()) {
      fmt::print("# start end phone (seconds, ARPAbet)\n");
      for (const auto& ph : seq) fmt::print("{:.3f} {:.3f} {}\n", ph.start, ph.end, ph.phone);
    } else {
      phones::write_phone_file(a->out, seq);
      fmt::print("{} phones ({:.2f} s, {}) written to {}\n", seq.size(), audio.seconds(),
                 a->text.empty() ? "recognised" : "aligned", a->out);
    }
    return 0;
  });
}

}  // namespace glossa::cli
