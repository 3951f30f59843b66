#include <filesystem>

#include "audio/decode.h"
#include "cli/commands.h"
#include "core/error.h"
#include "export/landmarks_writer.h"
#include "nn/model.h"

namespace glossa::cli {
namespace fs = std::filesystem;

void add_predict_command(CLI::App& app, std::vector<std::pair<CLI::App*, Run>>& runs) {
  struct Args {
    std::string audio, model, out;
  };
  auto a = std::make_shared<Args>();
  CLI::App* p = app.add_subcommand(
      "predict", "Predict landmark trajectories (50 fps, mm) from audio; writes CSV and .npy");
  p->add_option("audio", a->audio, "Audio file (WAV, FLAC, OGG, MP3; any rate, any channels)")
      ->required();
  p->add_option("-m,--model", a->model, "Model file")->required();
  p->add_option("-o,--out", a->out,
                "Output path without extension (default: the audio's name); writes .csv and .npy");
  runs.emplace_back(p, [a] {
    const auto model = nn::Model::load(a->model);
    const Audio audio = audio::load_audio(a->audio);
    const LandmarkSeq seq = model.predict(audio);
    const fs::path base = a->out.empty() ? fs::path(a->audio).replace_extension("")
                                         : fs::path(a->out);
    const fs::path csv = fs::path(base.string() + ".csv"), npy = fs::path(base.string() + ".npy");
    exporter::write_landmarks_csv(csv, seq);
    exporter::write_landmarks_npy(npy, seq);
    fmt::print("{} frames ({:.2f} s) of [{}] written to {} and {}\n", seq.frames(),
               seq.seconds(), seq.set.joined(), csv.string(), npy.string());
    return 0;
  });
}

}  // namespace glossa::cli
