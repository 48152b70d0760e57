// gyro_sil's outputs, written so that no file of the user's is ever harmed:
//   - an output path is refused when it is the scenario file (the same file, however spelt:
//     symbolic links, hard links, ../), the other output, a directory, or something that is not
//     a regular file (a device, a socket; the CSV may go to a character device or a FIFO, such
//     as /dev/null or /dev/stdout, which are written in place);
//   - each output is written to a temporary file created exclusively (O_CREAT | O_EXCL, a fresh
//     random name ".NAME.XXXXXXXXXX.tmp") in the final file's directory, and renamed over the
//     final path only once complete; until then, an error, an exception or a signal removes it
//     (and the directories created for it), and the existing file is untouched;
//   - an output that is a symbolic link to a file is written through: the target is replaced.
#pragma once

#include <cstdio>
#include <filesystem>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

namespace gyro::sil {

// An output path refused before anything runs (exit status 2).
class OutputRefused : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// An output that could not be created or written (exit status 1).
class OutputError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct OutputTarget {
  enum class Kind { kFile, kStream };
  std::string given;                 // as on the command line ("-": standard output)
  std::filesystem::path final_path;  // kFile: where the temporary is renamed to (symbolic links resolved)
  Kind kind{Kind::kFile};            // kStream: standard output, a character device or a FIFO
};

struct OutputPlan {
  OutputTarget csv;
  std::optional<OutputTarget> png;
};

// Checks the outputs named on the command line (`csv` "-" is standard output; `png` empty is
// no plot) against the scenario file and each other. Throws OutputRefused; OutputError when a
// path cannot even be inspected.
[[nodiscard]] OutputPlan plan_outputs(const std::filesystem::path& scenario, const std::string& csv,
                                      const std::string& png);

// A temporary file created exclusively and registered for removal on a signal; removed when
// destroyed uncommitted, together with the directories created for it.
class TempFile {
 public:
  // Beside `final_path`, in its directory (created if missing), with the permissions of the
  // file it will replace (else 0666 less the umask).
  [[nodiscard]] static TempFile beside(const std::filesystem::path& final_path);
  // A private file (mode 0600) in $TMPDIR (or /tmp), never committed.
  [[nodiscard]] static TempFile private_file(const std::string& stem);

  TempFile(TempFile&& other) noexcept;
  TempFile& operator=(TempFile&&) = delete;
  TempFile(const TempFile&) = delete;
  TempFile& operator=(const TempFile&) = delete;
  ~TempFile();

  [[nodiscard]] const std::filesystem::path& path() const noexcept { return path_; }
  // The file, open for writing, until close().
  [[nodiscard]] std::FILE* stream() const noexcept { return stream_; }
  // Flushes and closes it (and, for a file to be renamed, syncs it to the disk). OutputError.
  void close();
  // close(), then renames it onto the final path. OutputError.
  void commit();

 private:
  TempFile() = default;
  void remove_all() noexcept;

  std::filesystem::path path_;
  std::filesystem::path final_path_;  // empty for a private file
  std::FILE* stream_{nullptr};
  int slot_{-1};
  std::vector<std::pair<std::filesystem::path, int>> created_dirs_;  // outermost first, with slots
  bool done_{false};                                                 // committed or removed
};

// Copies the file at `from` to `to` (an open stream). OutputError.
void copy_to_stream(const std::filesystem::path& from, std::FILE* to, const std::string& to_name);

// Opens a stream target for writing in place (no O_CREAT, no O_TRUNC). OutputError.
[[nodiscard]] std::FILE* open_stream(const OutputTarget& t);

}  // namespace gyro::sil
