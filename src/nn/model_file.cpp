#include "nn/model_file.h"

#include <zlib.h>

#include <cstring>

#include "core/error.h"
#include "core/shape.h"
#include "io/atomic_file.h"

namespace glossa::nn {
namespace fs = std::filesystem;

namespace {

constexpr char kMagic[8] = {'G', 'L', 'O', 'S', 'S', 'A', 'M', 'F'};

template <typename T>
void put(std::string& out, T v) {
  char b[sizeof(T)];
  std::memcpy(b, &v, sizeof(T));  // glossa targets little-endian hosts
  out.append(b, sizeof(T));
}

template <typename T>
T get(const std::string& in, size_t at) {
  T v;
  std::memcpy(&v, in.data() + at, sizeof(T));
  return v;
}

uint32_t crc(const std::string& s, size_t n) {
  return static_cast<uint32_t>(
      crc32(0L, reinterpret_cast<const Bytef*>(s.data()), static_cast<uInt>(n)));
}

}  // namespace

void ModelFile::write(const fs::path& path) const {
  nlohmann::json h = header;
  nlohmann::json table = nlohmann::json::array();
  uint64_t offset = 0;
  for (const auto& [name, t] : tensors) {
    int64_t count = 1;
    for (int64_t d : t.shape) count *= d;
    if (static_cast<size_t>(count) != t.data.size())
      throw Error("model file: tensor " + name + " has a shape that does not match its data");
    table.push_back({{"name", name}, {"shape", t.shape}, {"offset", offset}});
    offset += t.data.size() * sizeof(float);
  }
  h["tensors"] = table;
  const std::string hs = h.dump();
  std::string out(kMagic, 8);
  put<uint32_t>(out, kModelFileVersion);
  put<uint64_t>(out, hs.size());
  out += hs;
  for (const auto& [name, t] : tensors)
    out.append(reinterpret_cast<const char*>(t.data.data()), t.data.size() * sizeof(float));
  put<uint32_t>(out, crc(out, out.size()));
  io::write_file_atomic(path, out);
}

ModelFile ModelFile::read(const fs::path& path) {
  const std::string in = io::read_file(path);
  if (in.size() < 24 || std::memcmp(in.data(), kMagic, 8) != 0)
    throw file_error(path, "not a glossa model file (bad magic)");
  const auto version = get<uint32_t>(in, 8);
  if (version > kModelFileVersion)
    throw file_error(path, "model file version " + std::to_string(version) +
                               " is newer than this glossa understands (" +
                               std::to_string(kModelFileVersion) + ")");
  const auto hlen = get<uint64_t>(in, 12);
  if (hlen > in.size() - 24) throw file_error(path, "damaged model file (header length)");
  const auto stored_crc = get<uint32_t>(in, in.size() - 4);
  if (stored_crc != crc(in, in.size() - 4))
    throw file_error(path, "damaged model file (checksum mismatch): re-copy or re-train it");
  ModelFile mf;
  try {
    mf.header = nlohmann::json::parse(in.substr(20, hlen));
  } catch (const nlohmann::json::exception& e) {
    throw file_error(path, std::string("damaged model header: ") + e.what());
  }
  const size_t data_start = 20 + hlen;
  const size_t data_len = in.size() - 4 - data_start;
  try {
    for (const auto& t : mf.header.at("tensors")) {
      NamedTensor nt;
      nt.shape = t.at("shape").get<std::vector<int64_t>>();
      const auto n = element_count(nt.shape);
      if (!n)
        throw file_error(path,
                         "damaged model file (a tensor shape is negative or impossibly large)");
      const uint64_t count = *n;
      const auto off = t.at("offset").get<uint64_t>();
      if (off + count * sizeof(float) > data_len)
        throw file_error(path, "damaged model file (tensor " + t.at("name").get<std::string>() +
                                   " runs past the end)");
      nt.data.resize(static_cast<size_t>(count));
      std::memcpy(nt.data.data(), in.data() + data_start + off, count * sizeof(float));
      mf.tensors[t.at("name").get<std::string>()] = std::move(nt);
    }
  } catch (const nlohmann::json::exception& e) {
    throw file_error(path, std::string("damaged model header: ") + e.what());
  }
  mf.header.erase("tensors");
  return mf;
}

}  // namespace glossa::nn
