#pragma once
// The model file: one self-describing, versioned file.
//   bytes 0-7   "GLOSSAMF"
//   u32         format version
//   u64         header length, then the header: JSON (encoder, decoder, normalisation,
//               landmark set, neutral poses, training summary, and the tensor table)
//   tensors     little-endian float32, at the offsets the table gives
//   u32         CRC-32 of everything before it
// A wrong magic, a newer version, a bad checksum or a table that does not fit the file is
// refused with a message naming the file; nothing is half-loaded.
#include <cstdint>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace glossa::nn {

inline constexpr uint32_t kModelFileVersion = 1;

struct NamedTensor {
  std::vector<int64_t> shape;
  std::vector<float> data;
};

struct ModelFile {
  nlohmann::json header;
  std::map<std::string, NamedTensor> tensors;

  static ModelFile read(const std::filesystem::path& path);
  void write(const std::filesystem::path& path) const;  // atomic
};

}  // namespace glossa::nn
