#pragma once
// Atomic writes: everything glossa writes goes to a temporary file beside the target and is
// renamed over it only when complete, so a crash or a kill never leaves a half-written output.
#include <filesystem>
#include <functional>
#include <string>
#include <string_view>

namespace glossa::io {

// Writes `bytes` to `path` atomically (temp file + fsync + rename). Creates parent folders.
void write_file_atomic(const std::filesystem::path& path, std::string_view bytes);

// Calls `write(tmp_path)` to produce the file at a temporary path, then renames it to `path`.
// For writers that need a file name of their own (libsndfile). The temp file is removed if
// `write` throws.
void write_via_temp(const std::filesystem::path& path,
                    const std::function<void(const std::filesystem::path&)>& write);

// Reads a whole file; throws glossa::Error naming the file if it cannot be read.
std::string read_file(const std::filesystem::path& path);

}  // namespace glossa::io
