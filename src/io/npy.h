#pragma once
// NumPy .npy arrays (format versions 1.0, 2.0 and 3.0). Reading accepts the numeric dtypes
// corpora use (float16/32/64, signed and unsigned integers) in either byte order and in C or
// Fortran order, and returns C-ordered float32. Writing always produces little-endian float32.
#include <cstddef>
#include <filesystem>
#include <string_view>
#include <vector>

namespace glossa::io {

struct NpyArray {
  std::vector<size_t> shape;
  std::vector<float> data;  // C order

  size_t size() const;
};

// Throws glossa::Error naming `path` on a bad magic, a truncated file, a malformed header,
// an unsupported dtype (object, string, complex, bool) or a size that does not match the shape.
NpyArray read_npy(const std::filesystem::path& path);
// Parses an in-memory .npy image; `name` is used in error messages.
NpyArray parse_npy(std::string_view bytes, const std::string& name);

// Writes a little-endian float32 array atomically.
void write_npy(const std::filesystem::path& path, const float* data,
               const std::vector<size_t>& shape);
std::string npy_bytes(const float* data, const std::vector<size_t>& shape);

}  // namespace glossa::io
