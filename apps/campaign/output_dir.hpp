// The output directory of gyro_campaign. It never harms a user's files: every file is
// written to a temporary in the target directory and renamed over its name only once it is
// complete, so an interrupted or failed write leaves the previous file (or none), never a
// torn one; no output may be one of the inputs (the campaign, its base scenario, the
// directories being merged); and a file is replaced only in a directory gyro_campaign has
// claimed (its marker file, .gyro_campaign), never in someone else's.
#pragma once

#include <filesystem>
#include <functional>
#include <ostream>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

namespace gyro::campaign {

class OutputError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// The marker of a directory gyro_campaign writes to.
inline constexpr const char* kOutputMarker = ".gyro_campaign";

class OutputDir {
 public:
  // Creates `dir` if needed. Throws OutputError if it cannot, or if it is one of
  // `input_dirs`.
  OutputDir(std::filesystem::path dir, std::vector<std::filesystem::path> inputs,
            const std::vector<std::filesystem::path>& input_dirs = {});

  // Throws OutputError if `relative` would be one of the inputs.
  void check(const std::string& relative) const;

  // Checks every name (check()), then claims the directory: one without the marker may not
  // hold a file of these names already (OutputError naming it); the marker is then written.
  void claim(const std::vector<std::string>& names) const;

  // Writes `content` to dir/relative atomically (a temporary beside it, then a rename).
  void write(const std::string& relative, std::string_view content) const;
  // The same, the content written by `fill` to the stream.
  void write(const std::string& relative, const std::function<void(std::ostream&)>& fill) const;

  // A fresh temporary path beside dir/relative (same directory, so a rename is atomic), and
  // the rename that publishes it.
  [[nodiscard]] std::filesystem::path temporary_for(const std::string& relative) const;
  void publish(const std::filesystem::path& temporary, const std::string& relative) const;

  [[nodiscard]] const std::filesystem::path& path() const noexcept { return dir_; }

 private:
  std::filesystem::path dir_;
  std::vector<std::filesystem::path> inputs_;
};

// Reads a whole file; throws OutputError naming it.
[[nodiscard]] std::string read_file(const std::filesystem::path& p);

}  // namespace gyro::campaign
