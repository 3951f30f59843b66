#pragma once
// Element counts of array shapes read from files, where a damaged header must not overflow.
#include <cstdint>
#include <optional>
#include <type_traits>
#include <vector>

namespace glossa {

// No array glossa reads has more elements than this (2^40 floats = 4 TiB).
inline constexpr uint64_t kMaxElements = uint64_t{1} << 40;

// The product of `shape`, or nothing when a dimension is negative or the product would exceed
// kMaxElements.
template <typename Int>
std::optional<uint64_t> element_count(const std::vector<Int>& shape) {
  uint64_t count = 1;
  for (Int d : shape) {
    if constexpr (std::is_signed_v<Int>)
      if (d < 0) return std::nullopt;
    const auto u = static_cast<uint64_t>(d);
    if (u != 0 && count > kMaxElements / u) return std::nullopt;
    count *= u;
  }
  return count;
}

}  // namespace glossa
