#pragma once
// The one exception type glossa throws for bad input: it always names the file (or the option)
// and the problem, so the CLI can print it as is.
#include <filesystem>
#include <stdexcept>
#include <string>

#include <fmt/format.h>

namespace glossa {

class Error : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// "path: message", the form every file error takes.
inline Error file_error(const std::filesystem::path& path, const std::string& message) {
  return Error(fmt::format("{}: {}", path.string(), message));
}

}  // namespace glossa
