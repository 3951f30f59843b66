#pragma once
// The layout of the papers' public IMT'22 release: 16 kHz `<id>.wav`, `<id>.npy` landmarks of
// shape [frames, 30] at 50 fps (10 sensors x xyz in the order TD TB BR BL TT UL LC LL LI LJ),
// transcripts and train/test lists. The release's exact folder names are not documented, so
// the reader searches the folder tree: wav and npy files are paired by file stem wherever they
// sit; a transcript is `<id>.txt` or `<id>.lab` beside either, or a line "<id> words..." in a
// file named transcript*/text*; a file whose name contains "train" or "test" (.txt/.lst/.list)
// lists ids (first token per line) and tags them split=train/test.
#include <filesystem>
#include <memory>

#include "ema/source.h"

namespace glossa::ema {

std::unique_ptr<CorpusSource> open_imt22_source(const std::filesystem::path& dir,
                                                const std::string& speaker = "IMT22");

}  // namespace glossa::ema
