// NumPy .npy reading and writing (src/io/npy.h), on byte images built here by hand.
#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <string>
#include <typeinfo>
#include <vector>

#include <fmt/format.h>

#include "core/error.h"
#include "io/atomic_file.h"
#include "io/npy.h"
#include "support/fixtures.h"

namespace glossa::io {
namespace {

namespace fs = std::filesystem;
using testing::TempDir;
using testing::write_bytes;

// Raw bytes of a value in the given byte order.
template <typename T>
std::string raw(T v, bool big_endian) {
  std::string out(sizeof(T), '\0');
  std::memcpy(out.data(), &v, sizeof(T));
  if ((std::endian::native == std::endian::big) != big_endian) {
    for (size_t i = 0; i < sizeof(T) / 2; ++i) std::swap(out[i], out[sizeof(T) - 1 - i]);
  }
  return out;
}

template <typename T>
std::string raw_all(const std::vector<T>& values, bool big_endian) {
  std::string out;
  for (T v : values) out += raw(v, big_endian);
  return out;
}

// A complete .npy image: magic, version, header length (2 bytes for 1.0, 4 for 2.0/3.0), the
// header dict padded with spaces and ending in '\n' so the data starts on a 64-byte boundary.
std::string npy_image(const std::string& dict, const std::string& data, int major = 1) {
  const size_t prefix = major == 1 ? 10 : 12;
  std::string header = dict;
  const size_t total = prefix + header.size() + 1;
  header.append((64 - total % 64) % 64, ' ');
  header += '\n';
  std::string out("\x93NUMPY", 6);
  out += static_cast<char>(major);
  out += '\0';
  if (major == 1) {
    out += raw<uint16_t>(static_cast<uint16_t>(header.size()), false);
  } else {
    out += raw<uint32_t>(static_cast<uint32_t>(header.size()), false);
  }
  return out + header + data;
}

std::string dict(const std::string& descr, const std::string& shape, bool fortran = false) {
  return fmt::format("{{'descr': '{}', 'fortran_order': {}, 'shape': {}, }}", descr,
                     fortran ? "True" : "False", shape);
}

// Expects parse_npy to throw glossa::Error whose message names `name` and contains `needle`.
void expect_error(const std::string& bytes, const std::string& needle) {
  const std::string name = "/data/fixture-under-test.npy";
  try {
    parse_npy(bytes, name);
    ADD_FAILURE() << "expected glossa::Error containing '" << needle << "'";
  } catch (const Error& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find(name), std::string::npos) << "message does not name the file: " << what;
    EXPECT_NE(what.find(needle), std::string::npos) << "message lacks '" << needle << "': " << what;
  } catch (const std::exception& e) {
    ADD_FAILURE() << "threw a non-glossa exception: " << e.what();
  }
}

// ---------------------------------------------------------------------------------------------
// Round trip through the writer.

TEST(Npy, RoundTripWriteRead) {
  TempDir dir;
  const std::vector<std::vector<size_t>> shapes = {{},        {7},    {2, 3},
                                                   {3, 4, 5}, {2, 0}, {1, 1, 1, 2}};
  for (const auto& shape : shapes) {
    size_t count = 1;
    for (size_t d : shape) count *= d;
    std::vector<float> data(count);
    for (size_t i = 0; i < count; ++i)
      data[i] = static_cast<float>(std::sin(0.37 * double(i)) * 1000.0 + double(i) * 1e-3);
    if (count > 2) {
      data[1] = -0.0f;
      data[2] = std::numeric_limits<float>::infinity();
    }
    const fs::path path = dir / fmt::format("a{}.npy", shape.size() * 10 + count);
    write_npy(path, data.data(), shape);
    const NpyArray back = read_npy(path);
    EXPECT_EQ(back.shape, shape);
    ASSERT_EQ(back.data.size(), count);
    EXPECT_EQ(back.size(), count);
    for (size_t i = 0; i < count; ++i) {
      EXPECT_EQ(std::bit_cast<uint32_t>(back.data[i]), std::bit_cast<uint32_t>(data[i]))
          << "element " << i;
    }
  }
}

TEST(Npy, WrittenHeaderFollowsTheFormat) {
  const std::vector<float> data = {1.5f, -2.25f, 3.0f, 4.0f, 5.0f, 6.0f};
  const std::string bytes = npy_bytes(data.data(), {2, 3});
  ASSERT_GE(bytes.size(), 10u);
  EXPECT_EQ(bytes.substr(0, 6), std::string("\x93NUMPY", 6));
  EXPECT_EQ(bytes[6], 1);
  EXPECT_EQ(bytes[7], 0);
  const size_t hlen = static_cast<uint8_t>(bytes[8]) | (static_cast<uint8_t>(bytes[9]) << 8);
  EXPECT_EQ((10 + hlen) % 64, 0u) << "data must start on a 64-byte boundary";
  ASSERT_EQ(bytes.size(), 10 + hlen + 6 * 4);
  const std::string header = bytes.substr(10, hlen);
  EXPECT_EQ(header.back(), '\n');
  EXPECT_NE(header.find("'descr': '<f4'"), std::string::npos) << header;
  EXPECT_NE(header.find("'fortran_order': False"), std::string::npos) << header;
  EXPECT_NE(header.find("'shape': (2, 3)"), std::string::npos) << header;
  // 1-D shapes need the trailing comma of a Python 1-tuple.
  const std::string one = npy_bytes(data.data(), {6});
  EXPECT_NE(one.find("'shape': (6,)"), std::string::npos);
  // Little-endian float32 payload.
  EXPECT_EQ(bytes.substr(10 + hlen, 4), raw(1.5f, false));
  EXPECT_EQ(bytes.substr(10 + hlen + 4, 4), raw(-2.25f, false));
}

TEST(Npy, WriteIsAtomicAndReplacesAnExistingFile) {
  TempDir dir;
  const fs::path path = dir / "sub" / "x.npy";
  const std::vector<float> a = {1, 2, 3};
  const std::vector<float> b = {9, 8};
  write_npy(path, a.data(), {3});
  write_npy(path, b.data(), {2});
  const NpyArray back = read_npy(path);
  EXPECT_EQ(back.shape, std::vector<size_t>{2});
  EXPECT_EQ(back.data, b);
  // Nothing but the target is left in the folder (no temp files).
  size_t entries = 0;
  for ([[maybe_unused]] const auto& e : fs::directory_iterator(path.parent_path())) ++entries;
  EXPECT_EQ(entries, 1u);
}

TEST(Npy, ReadMissingFileNamesIt) {
  TempDir dir;
  const fs::path path = dir / "absent.npy";
  try {
    read_npy(path);
    FAIL() << "expected glossa::Error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find(path.string()), std::string::npos) << e.what();
  }
}

// ---------------------------------------------------------------------------------------------
// Hand-built images of every supported dtype.

TEST(Npy, LittleEndianFloat32) {
  const std::vector<float> v = {0.0f, 1.0f, -3.5f, 1e-20f, 6.02e23f};
  const NpyArray a = parse_npy(npy_image(dict("<f4", "(5,)"), raw_all(v, false)), "x.npy");
  EXPECT_EQ(a.shape, std::vector<size_t>{5});
  EXPECT_EQ(a.data, v);
}

TEST(Npy, BigEndianFloat32) {
  const std::vector<float> v = {0.25f, -1.0f, 123456.0f, -7.75f};
  const NpyArray a = parse_npy(npy_image(dict(">f4", "(2, 2)"), raw_all(v, true)), "x.npy");
  EXPECT_EQ(a.shape, (std::vector<size_t>{2, 2}));
  EXPECT_EQ(a.data, v);
}

TEST(Npy, LittleEndianFloat64) {
  const std::vector<double> v = {0.1, -2.5, 1e10, 3.141592653589793, -1e-30};
  const NpyArray a = parse_npy(npy_image(dict("<f8", "(5,)"), raw_all(v, false)), "x.npy");
  ASSERT_EQ(a.data.size(), v.size());
  for (size_t i = 0; i < v.size(); ++i) EXPECT_EQ(a.data[i], static_cast<float>(v[i])) << i;
}

TEST(Npy, LittleEndianInt16) {
  const std::vector<int16_t> v = {0, 1, -1, 32767, -32768, 1234};
  const NpyArray a = parse_npy(npy_image(dict("<i2", "(3, 2)"), raw_all(v, false)), "x.npy");
  EXPECT_EQ(a.shape, (std::vector<size_t>{3, 2}));
  EXPECT_EQ(a.data, (std::vector<float>{0, 1, -1, 32767, -32768, 1234}));
}

TEST(Npy, BigEndianInt32) {
  const std::vector<int32_t> v = {0, -1, 16777216, -123456, 70000};
  const NpyArray a = parse_npy(npy_image(dict(">i4", "(5,)"), raw_all(v, true)), "x.npy");
  EXPECT_EQ(a.data, (std::vector<float>{0, -1, 16777216, -123456, 70000}));
}

TEST(Npy, UnsignedByte) {
  const std::string data = {'\x00', '\x01', '\x7f', '\x80', '\xfe', '\xff'};
  const NpyArray a = parse_npy(npy_image(dict("|u1", "(6,)"), data), "x.npy");
  EXPECT_EQ(a.data, (std::vector<float>{0, 1, 127, 128, 254, 255}));
}

TEST(Npy, LittleEndianFloat16) {
  // IEEE half bit patterns: 1, -2, 0.5, 65504 (max), smallest subnormal 2^-24, -0, +inf,
  // 0.333251953125 (0x3555) and the largest subnormal (0x03ff = 1023 * 2^-24).
  const std::vector<uint16_t> bits = {0x3C00, 0xC000, 0x3800, 0x7BFF, 0x0001,
                                      0x8000, 0x7C00, 0x3555, 0x03FF};
  const NpyArray a = parse_npy(npy_image(dict("<f2", "(9,)"), raw_all(bits, false)), "x.npy");
  ASSERT_EQ(a.data.size(), bits.size());
  EXPECT_EQ(a.data[0], 1.0f);
  EXPECT_EQ(a.data[1], -2.0f);
  EXPECT_EQ(a.data[2], 0.5f);
  EXPECT_EQ(a.data[3], 65504.0f);
  EXPECT_EQ(a.data[4], std::ldexp(1.0f, -24));
  EXPECT_EQ(a.data[5], 0.0f);
  EXPECT_TRUE(std::signbit(a.data[5]));
  EXPECT_TRUE(std::isinf(a.data[6]) && a.data[6] > 0);
  EXPECT_EQ(a.data[7], 0.333251953125f);
  EXPECT_EQ(a.data[8], 1023.0f * std::ldexp(1.0f, -24));
}

TEST(Npy, NativeOrderAndHeaderKeyOrder) {
  // '=' is native order; numpy may write the keys in any order.
  const std::vector<float> v = {1, 2, 3};
  const std::string d = "{'shape': (3,), 'fortran_order': False, 'descr': '=f4'}";
  const std::string native = raw_all(v, std::endian::native == std::endian::big);
  const NpyArray a = parse_npy(npy_image(d, native), "x.npy");
  EXPECT_EQ(a.shape, std::vector<size_t>{3});
  EXPECT_EQ(a.data, v);
}

TEST(Npy, ScalarAndEmptyShapes) {
  const NpyArray s = parse_npy(npy_image(dict("<f4", "()"), raw(42.0f, false)), "x.npy");
  EXPECT_TRUE(s.shape.empty());
  EXPECT_EQ(s.data, std::vector<float>{42.0f});
  const NpyArray e = parse_npy(npy_image(dict("<f4", "(0, 3)"), ""), "x.npy");
  EXPECT_EQ(e.shape, (std::vector<size_t>{0, 3}));
  EXPECT_TRUE(e.data.empty());
}

// ---------------------------------------------------------------------------------------------
// Fortran order: the file holds the first index fastest; the reader must return C order.

TEST(Npy, FortranOrder2x3) {
  // a[i][j] = 10 i + j; in Fortran order the file holds a00 a10 a01 a11 a02 a12.
  const std::vector<float> fortran = {0, 10, 1, 11, 2, 12};
  const NpyArray a =
      parse_npy(npy_image(dict("<f4", "(2, 3)", true), raw_all(fortran, false)), "x.npy");
  EXPECT_EQ(a.shape, (std::vector<size_t>{2, 3}));
  EXPECT_EQ(a.data, (std::vector<float>{0, 1, 2, 10, 11, 12}));
}

TEST(Npy, FortranOrder2x3x2) {
  // a[i][j][k] = 100 i + 10 j + k, written with i fastest, then j, then k.
  std::vector<int16_t> fortran;
  for (int k = 0; k < 2; ++k)
    for (int j = 0; j < 3; ++j)
      for (int i = 0; i < 2; ++i) fortran.push_back(static_cast<int16_t>(100 * i + 10 * j + k));
  const NpyArray a =
      parse_npy(npy_image(dict(">i2", "(2, 3, 2)", true), raw_all(fortran, true)), "x.npy");
  EXPECT_EQ(a.shape, (std::vector<size_t>{2, 3, 2}));
  std::vector<float> c_order;
  for (int i = 0; i < 2; ++i)
    for (int j = 0; j < 3; ++j)
      for (int k = 0; k < 2; ++k) c_order.push_back(static_cast<float>(100 * i + 10 * j + k));
  EXPECT_EQ(a.data, c_order);
}

TEST(Npy, FortranOrderOneDimensionalIsUnchanged) {
  const std::vector<float> v = {3, 1, 4, 1, 5};
  const NpyArray a = parse_npy(npy_image(dict("<f4", "(5,)", true), raw_all(v, false)), "x.npy");
  EXPECT_EQ(a.data, v);
}

// ---------------------------------------------------------------------------------------------
// Format versions.

TEST(Npy, Version2Header) {
  const std::vector<double> v = {1.25, -8.5, 3.0, 0.0};
  const std::string img = npy_image(dict("<f8", "(2, 2)"), raw_all(v, false), 2);
  ASSERT_EQ(img[6], 2);
  ASSERT_EQ((img.size() - 4 * 8) % 64, 0u) << "fixture: data should start on a 64-byte boundary";
  const NpyArray a = parse_npy(img, "x.npy");
  EXPECT_EQ(a.shape, (std::vector<size_t>{2, 2}));
  EXPECT_EQ(a.data, (std::vector<float>{1.25f, -8.5f, 3.0f, 0.0f}));
}

TEST(Npy, Version3Header) {
  const std::vector<float> v = {5, 6};
  const NpyArray a = parse_npy(npy_image(dict("<f4", "(2,)"), raw_all(v, false), 3), "x.npy");
  EXPECT_EQ(a.data, v);
}

TEST(Npy, UnknownVersionIsRefused) {
  std::string img = npy_image(dict("<f4", "(1,)"), raw(1.0f, false));
  img[6] = 4;
  expect_error(img, "version");
}

// ---------------------------------------------------------------------------------------------
// Malformed files: each refused with glossa::Error naming the file.

TEST(Npy, BadMagic) {
  std::string img = npy_image(dict("<f4", "(1,)"), raw(1.0f, false));
  img[1] = 'M';
  expect_error(img, "magic");
  expect_error("", "magic");
  expect_error("\x93NUMP", "magic");
  expect_error("PK\x03\x04 this is a zip, not an npy file", "magic");
}

TEST(Npy, TruncatedHeader) {
  const std::string img =
      npy_image(dict("<f4", "(4,)"), raw_all(std::vector<float>{1, 2, 3, 4}, false));
  // Cut inside the header dict (header length says 118 bytes, fewer are there).
  expect_error(img.substr(0, 40), "truncated");
  // Version 2.0 with the 4-byte length field cut short.
  const std::string v2 = npy_image(dict("<f4", "(1,)"), raw(1.0f, false), 2);
  expect_error(v2.substr(0, 11), "truncated");
}

TEST(Npy, TruncatedData) {
  const std::vector<float> v = {1, 2, 3, 4, 5, 6};
  const std::string img = npy_image(dict("<f4", "(2, 3)"), raw_all(v, false));
  expect_error(img.substr(0, img.size() - 1), "truncated");
  expect_error(img.substr(0, img.size() - 4 * 3), "truncated");
  expect_error(npy_image(dict("<f4", "(2, 3)"), ""), "truncated");
  // The same through read_npy on a real file.
  TempDir dir;
  const fs::path path = dir / "cut.npy";
  write_bytes(path, img.substr(0, img.size() - 2));
  try {
    read_npy(path);
    FAIL() << "expected glossa::Error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find(path.string()), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("truncated"), std::string::npos) << e.what();
  }
}

TEST(Npy, UnsupportedDtypes) {
  const std::string eight(8, '\0');
  expect_error(npy_image(dict("|O8", "(1,)"), eight), "unsupported");
  expect_error(npy_image(dict("<c8", "(1,)"), eight), "unsupported");
  expect_error(npy_image(dict("<U5", "(1,)"), std::string(20, '\0')), "unsupported");
  expect_error(npy_image(dict("|b1", "(1,)"), std::string(1, '\1')), "unsupported");
  expect_error(npy_image(dict("<f16", "(1,)"), std::string(16, '\0')), "unsupported");
  expect_error(npy_image(dict("<i3", "(1,)"), std::string(3, '\0')), "unsupported");
}

TEST(Npy, StructuredDtypeIsRefused) {
  const std::string d =
      "{'descr': [('a', '<f4'), ('b', '<f4')], 'fortran_order': False, "
      "'shape': (1,), }";
  expect_error(npy_image(d, std::string(8, '\0')), "descr");
}

TEST(Npy, MissingShape) {
  const std::string d = "{'descr': '<f4', 'fortran_order': False, }";
  expect_error(npy_image(d, raw(1.0f, false)), "shape");
}

TEST(Npy, MissingFortranOrder) {
  const std::string d = "{'descr': '<f4', 'shape': (1,), }";
  expect_error(npy_image(d, raw(1.0f, false)), "fortran_order");
}

TEST(Npy, ShapeWhoseSizeOverflowsIsRefused) {
  // 2^62 + 1 float32 elements: the byte count (2^64 + 4) wraps to 4 in 64-bit arithmetic, so a
  // reader that multiplies without checking believes 4 bytes of data suffice.
  const std::string huge = "(4611686018427387905,)";
  try {
    parse_npy(npy_image(dict("<f4", huge), raw(1.0f, false)), "/data/huge.npy");
    ADD_FAILURE() << "expected glossa::Error for an impossible shape";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("/data/huge.npy"), std::string::npos) << e.what();
  } catch (const std::exception& e) {
    ADD_FAILURE() << "BUG: src/io/npy.cpp parse_npy: element count * item size overflows for "
                     "shape "
                  << huge << "; the size check passes and data.resize throws " << typeid(e).name()
                  << " (" << e.what() << ") instead of glossa::Error";
  }
}

TEST(Npy, ShapeWithOverlongDimensionIsRefused) {
  // A dimension that does not fit in 64 bits must be a glossa::Error, not std::out_of_range.
  try {
    parse_npy(npy_image(dict("<f4", "(123456789012345678901234567890,)"), raw(1.0f, false)),
              "/data/long.npy");
    ADD_FAILURE() << "expected glossa::Error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("/data/long.npy"), std::string::npos) << e.what();
  } catch (const std::exception& e) {
    ADD_FAILURE() << "BUG: src/io/npy.cpp parse_header: std::stoull on an overlong shape "
                     "dimension throws "
                  << typeid(e).name() << " (" << e.what() << ") instead of glossa::Error";
  }
}

}  // namespace
}  // namespace glossa::io
