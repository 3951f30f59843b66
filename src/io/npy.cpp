#include "io/npy.h"

#include <bit>
#include <cstdint>
#include <cstring>
#include <numeric>
#include <regex>

#include "core/error.h"
#include "core/shape.h"
#include "io/atomic_file.h"

namespace glossa::io {

size_t NpyArray::size() const {
  return std::accumulate(shape.begin(), shape.end(), size_t{1}, std::multiplies<>());
}

namespace {

struct Header {
  char byte_order = '<';  // '<', '>' or '|'
  char kind = 'f';        // 'f', 'i', 'u'
  int item_size = 4;
  bool fortran = false;
  std::vector<size_t> shape;
};

Header parse_header(const std::string& h, const std::string& name) {
  Header out;
  std::smatch m;
  static const std::regex descr_re(R"('descr'\s*:\s*'([<>|=])([a-zA-Z])(\d+)')");
  if (!std::regex_search(h, m, descr_re))
    throw file_error(name, "malformed .npy header: no readable 'descr' (got " + h + ")");
  out.byte_order = m[1].str()[0];
  if (out.byte_order == '=') out.byte_order = '<';
  out.kind = m[2].str()[0];
  out.item_size = std::stoi(m[3].str());
  const bool ok_kind =
      (out.kind == 'f' && (out.item_size == 2 || out.item_size == 4 || out.item_size == 8)) ||
      ((out.kind == 'i' || out.kind == 'u') &&
       (out.item_size == 1 || out.item_size == 2 || out.item_size == 4 || out.item_size == 8));
  if (!ok_kind)
    throw file_error(name, "unsupported .npy dtype '" + m[1].str() + m[2].str() + m[3].str() +
                               "' (expected a float or integer array)");
  static const std::regex fortran_re(R"('fortran_order'\s*:\s*(True|False))");
  if (!std::regex_search(h, m, fortran_re))
    throw file_error(name, "malformed .npy header: no 'fortran_order'");
  out.fortran = m[1].str() == "True";
  static const std::regex shape_re(R"('shape'\s*:\s*\(([^)]*)\))");
  if (!std::regex_search(h, m, shape_re))
    throw file_error(name, "malformed .npy header: no 'shape'");
  const std::string dims = m[1].str();
  static const std::regex int_re(R"(\d+)");
  for (auto it = std::sregex_iterator(dims.begin(), dims.end(), int_re);
       it != std::sregex_iterator(); ++it) {
    const std::string d = it->str();
    if (d.size() > 15) throw file_error(name, "impossible .npy shape dimension " + d);
    out.shape.push_back(static_cast<size_t>(std::stoull(d)));
  }
  return out;
}

template <typename T>
T load_swapped(const char* p, bool swap) {
  T v;
  std::memcpy(&v, p, sizeof(T));
  if (swap) {
    char b[sizeof(T)];
    std::memcpy(b, &v, sizeof(T));
    for (size_t i = 0; i < sizeof(T) / 2; ++i) std::swap(b[i], b[sizeof(T) - 1 - i]);
    std::memcpy(&v, b, sizeof(T));
  }
  return v;
}

float half_to_float(uint16_t h) {
  const uint32_t sign = (h & 0x8000u) << 16;
  uint32_t exp = (h >> 10) & 0x1f;
  uint32_t mant = h & 0x3ff;
  uint32_t bits;
  if (exp == 0) {
    if (mant == 0) {
      bits = sign;
    } else {  // subnormal: normalise
      exp = 127 - 15 + 1;
      while ((mant & 0x400) == 0) {
        mant <<= 1;
        --exp;
      }
      mant &= 0x3ff;
      bits = sign | (exp << 23) | (mant << 13);
    }
  } else if (exp == 31) {
    bits = sign | 0x7f800000u | (mant << 13);
  } else {
    bits = sign | ((exp - 15 + 127) << 23) | (mant << 13);
  }
  return std::bit_cast<float>(bits);
}

float convert_item(const char* p, const Header& h) {
  const bool little_host = std::endian::native == std::endian::little;
  const bool swap = h.item_size > 1 && ((h.byte_order == '<') != little_host);
  switch (h.kind) {
    case 'f':
      if (h.item_size == 2) return half_to_float(load_swapped<uint16_t>(p, swap));
      if (h.item_size == 4) return load_swapped<float>(p, swap);
      return static_cast<float>(load_swapped<double>(p, swap));
    case 'i':
      if (h.item_size == 1) return static_cast<float>(static_cast<int8_t>(*p));
      if (h.item_size == 2) return load_swapped<int16_t>(p, swap);
      if (h.item_size == 4) return static_cast<float>(load_swapped<int32_t>(p, swap));
      return static_cast<float>(load_swapped<int64_t>(p, swap));
    default:
      if (h.item_size == 1) return static_cast<float>(static_cast<uint8_t>(*p));
      if (h.item_size == 2) return load_swapped<uint16_t>(p, swap);
      if (h.item_size == 4) return static_cast<float>(load_swapped<uint32_t>(p, swap));
      return static_cast<float>(load_swapped<uint64_t>(p, swap));
  }
}

}  // namespace

NpyArray parse_npy(std::string_view bytes, const std::string& name) {
  static constexpr char kMagic[] = "\x93NUMPY";
  if (bytes.size() < 10 || std::memcmp(bytes.data(), kMagic, 6) != 0)
    throw file_error(name, "not a .npy file (bad magic)");
  const auto major = static_cast<uint8_t>(bytes[6]);
  size_t header_len = 0;
  size_t offset = 0;
  if (major == 1) {
    header_len = static_cast<uint8_t>(bytes[8]) | (static_cast<uint8_t>(bytes[9]) << 8);
    offset = 10;
  } else if (major == 2 || major == 3) {
    if (bytes.size() < 12) throw file_error(name, "truncated .npy header");
    header_len = 0;
    for (int i = 0; i < 4; ++i) header_len |= size_t(static_cast<uint8_t>(bytes[8 + i])) << (8 * i);
    offset = 12;
  } else {
    throw file_error(name, "unsupported .npy format version " + std::to_string(major));
  }
  if (bytes.size() < offset + header_len) throw file_error(name, "truncated .npy header");
  const Header h = parse_header(std::string(bytes.substr(offset, header_len)), name);
  offset += header_len;

  NpyArray out;
  out.shape = h.shape;
  const auto n = element_count(h.shape);
  if (!n) throw file_error(name, "impossible .npy shape (more than 2^40 elements)");
  const auto count = static_cast<size_t>(*n);
  const size_t need = count * static_cast<size_t>(h.item_size);
  if (bytes.size() - offset < need)
    throw file_error(name, fmt::format("truncated .npy data: shape needs {} bytes, file has {}",
                                       need, bytes.size() - offset));
  out.data.resize(count);
  const char* base = bytes.data() + offset;
  if (!h.fortran || h.shape.size() < 2) {
    for (size_t i = 0; i < count; ++i) out.data[i] = convert_item(base + i * h.item_size, h);
    return out;
  }
  // Fortran order: the first index varies fastest. Walk the C-order destination and compute
  // the Fortran source offset for each element.
  const size_t nd = h.shape.size();
  std::vector<size_t> fstride(nd, 1);
  for (size_t d = 1; d < nd; ++d) fstride[d] = fstride[d - 1] * h.shape[d - 1];
  std::vector<size_t> idx(nd, 0);
  for (size_t i = 0; i < count; ++i) {
    size_t src = 0;
    for (size_t d = 0; d < nd; ++d) src += idx[d] * fstride[d];
    out.data[i] = convert_item(base + src * h.item_size, h);
    for (size_t d = nd; d-- > 0;) {
      if (++idx[d] < h.shape[d]) break;
      idx[d] = 0;
    }
  }
  return out;
}

NpyArray read_npy(const std::filesystem::path& path) {
  return parse_npy(read_file(path), path.string());
}

std::string npy_bytes(const float* data, const std::vector<size_t>& shape) {
  std::string dims;
  for (size_t i = 0; i < shape.size(); ++i) {
    dims += std::to_string(shape[i]);
    if (shape.size() == 1 || i + 1 < shape.size()) dims += ",";
    if (i + 1 < shape.size()) dims += " ";
  }
  std::string header = "{'descr': '<f4', 'fortran_order': False, 'shape': (" + dims + "), }";
  // Pad so that magic(6)+version(2)+len(2)+header is a multiple of 64, ending in '\n'.
  const size_t total = 10 + header.size() + 1;
  header.append((64 - total % 64) % 64, ' ');
  header += '\n';
  std::string out("\x93NUMPY\x01\x00", 8);
  out += static_cast<char>(header.size() & 0xff);
  out += static_cast<char>((header.size() >> 8) & 0xff);
  out += header;
  size_t count = std::accumulate(shape.begin(), shape.end(), size_t{1}, std::multiplies<>());
  const size_t at = out.size();
  out.resize(at + count * 4);
  for (size_t i = 0; i < count; ++i) {
    uint32_t bits = std::bit_cast<uint32_t>(data[i]);
    if constexpr (std::endian::native == std::endian::big) bits = __builtin_bswap32(bits);
    std::memcpy(out.data() + at + i * 4, &bits, 4);
  }
  return out;
}

void write_npy(const std::filesystem::path& path, const float* data,
               const std::vector<size_t>& shape) {
  write_file_atomic(path, npy_bytes(data, shape));
}

}  // namespace glossa::io
