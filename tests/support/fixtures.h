#pragma once
// Helpers shared by the tests: temporary folders and generated fixtures.
#include <filesystem>
#include <string>

namespace glossa::testing {

// A fresh empty folder under the system temp dir, removed when the object dies.
class TempDir {
 public:
  TempDir();
  ~TempDir();
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;
  const std::filesystem::path& path() const { return path_; }
  std::filesystem::path operator/(const std::string& name) const { return path_ / name; }

 private:
  std::filesystem::path path_;
};

// Writes raw bytes to a file (no atomicity needed in tests).
void write_bytes(const std::filesystem::path& path, const std::string& bytes);

// ../shared/data, or empty when it is absent (tests that need it then skip with a message).
std::filesystem::path shared_data_dir();

// Path of the built `glossa` executable.
std::filesystem::path cli_path();

// Runs a shell command, returns its exit code and captures stdout+stderr into `output`.
int run_command(const std::string& command, std::string* output = nullptr);

}  // namespace glossa::testing
