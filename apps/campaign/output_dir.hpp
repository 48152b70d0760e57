// The output directory of gyro_campaign. It never harms a user's files:
//   - every file is written to a temporary in its directory (created exclusively, removed on
//     an error or a signal: sil::TempFile) and renamed over its name only once complete, so
//     an interrupted or failed write leaves the previous file (or none), never a torn one;
//   - no output may be one of the inputs (the campaign, its base scenario, the directories
//     being merged);
//   - a file is replaced only in a directory gyro_campaign has claimed (its marker file,
//     .gyro_campaign), never in someone else's;
//   - below the directory the user named, nothing is followed: a symbolic link in place of an
//     output or of a sub-directory (plots/) is refused, and so is anything that is not a
//     regular file or directory; an output the user may not write (read-only) is not
//     replaced;
//   - one gyro_campaign at a time: the directory is locked while the process lives
//     (dir_lock.hpp), and a second run into it is refused.
#pragma once

#include <filesystem>
#include <functional>
#include <optional>
#include <ostream>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "dir_lock.hpp"
#include "output_files.hpp"

namespace gyro::campaign {

class OutputError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// The marker of a directory gyro_campaign writes to.
inline constexpr const char* kOutputMarker = ".gyro_campaign";

class OutputDir {
 public:
  // Creates `dir` if needed and locks it. Throws OutputError if it cannot, if it is one of
  // `input_dirs`, or if another gyro_campaign holds it.
  OutputDir(std::filesystem::path dir, std::vector<std::filesystem::path> inputs,
            const std::vector<std::filesystem::path>& input_dirs = {});

  // Throws OutputError if `relative` would be one of the inputs, if a symbolic link (or
  // anything but a directory) stands in place of one of its directories below the output
  // directory, or if it exists and is a symbolic link, not a regular file, or read-only.
  void check(const std::string& relative) const;

  // Checks every name (check()), then claims the directory: one without the marker may not
  // hold a file of these names already (OutputError naming it); the marker is then written.
  void claim(const std::vector<std::string>& names) const;

  // Writes `content` to dir/relative atomically (a temporary beside it, then a rename).
  void write(const std::string& relative, std::string_view content) const;
  // The same, the content written by `fill` to the stream.
  void write(const std::string& relative, const std::function<void(std::ostream&)>& fill) const;

  // A fresh temporary file beside dir/relative (same directory, so a rename is atomic; open
  // for writing until closed, removed if never published), and the rename that publishes it.
  [[nodiscard]] sil::TempFile temporary_for(const std::string& relative) const;
  void publish(sil::TempFile& temporary, const std::string& relative) const;

  [[nodiscard]] const std::filesystem::path& path() const noexcept { return dir_; }

 private:
  std::filesystem::path dir_;
  std::vector<std::filesystem::path> inputs_;
  std::optional<DirectoryLock> lock_;
};

// Reads a whole input file of at most `max_bytes` (checked before reading, bounded_read.hpp);
// `what` names the kind of file in the message. Throws OutputError naming it.
[[nodiscard]] std::string read_file(const std::filesystem::path& p, std::uint64_t max_bytes, const std::string& what);

}  // namespace gyro::campaign
