// CSV output of gyro_sil: one header row, then one row per tick. Numbers are written with
// std::to_chars in scientific form with 9 digits after the point (as printf's %.9e), which
// does not depend on the locale; identical values give identical bytes.
#pragma once

#include <charconv>
#include <cstdint>
#include <cstdio>
#include <span>
#include <string>
#include <string_view>

namespace gyro::sil {

// "%.9e" of v without the locale: "-1.234567890e-05", "nan", "inf".
void append_scientific(std::string& out, double v);

// The longest text append_scientific writes: "-1.234567890e-308".
inline constexpr std::size_t kMaxScientificChars = 17;

class CsvWriter {
 public:
  // Writes to `out` (not owned; the caller opens and closes it).
  explicit CsvWriter(std::FILE* out) noexcept : out_(out) {}

  void header(std::span<const std::string_view> columns);

  // Fields of the current row, left to right; end_row() writes it.
  CsvWriter& number(double v);
  CsvWriter& integer(std::uint64_t v);
  CsvWriter& text(std::string_view v);  // written as is: no commas, quotes or newlines
  void end_row();

  [[nodiscard]] std::uint64_t rows() const noexcept { return rows_; }
  // Bytes handed to the stream so far.
  [[nodiscard]] std::uint64_t bytes() const noexcept { return bytes_; }
  // False once a write failed (disk full, closed pipe).
  [[nodiscard]] bool ok() const noexcept { return ok_; }

 private:
  void separator() {
    if (fields_++ != 0) line_ += ',';
  }
  void flush_line();

  std::FILE* out_;
  std::string line_;
  std::size_t fields_{0};  // in the current row
  std::uint64_t rows_{0};
  std::uint64_t bytes_{0};
  bool ok_{true};
};

}  // namespace gyro::sil
