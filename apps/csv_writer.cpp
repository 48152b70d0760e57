#include "csv_writer.hpp"

#include <array>
#include <cmath>

namespace gyro::sil {

void append_scientific(std::string& out, double v) {
  if (std::isnan(v)) {
    out += "nan";
    return;
  }
  if (std::isinf(v)) {
    out += v < 0 ? "-inf" : "inf";
    return;
  }
  std::array<char, 40> buf{};
  const std::to_chars_result r = std::to_chars(buf.data(), buf.data() + buf.size(), v, std::chars_format::scientific, 9);
  out.append(buf.data(), r.ptr);
}

void CsvWriter::header(std::span<const std::string_view> columns) {
  line_.clear();
  fields_ = 0;
  for (std::string_view c : columns) {
    separator();
    line_ += c;
  }
  flush_line();
}

CsvWriter& CsvWriter::number(double v) {
  separator();
  append_scientific(line_, v);
  return *this;
}

CsvWriter& CsvWriter::integer(std::uint64_t v) {
  separator();
  std::array<char, 24> buf{};
  const std::to_chars_result r = std::to_chars(buf.data(), buf.data() + buf.size(), v);
  line_.append(buf.data(), r.ptr);
  return *this;
}

CsvWriter& CsvWriter::text(std::string_view v) {
  separator();
  line_ += v;
  return *this;
}

void CsvWriter::end_row() {
  flush_line();
  ++rows_;
}

void CsvWriter::flush_line() {
  line_ += '\n';
  if (ok_ && std::fwrite(line_.data(), 1, line_.size(), out_) != line_.size()) ok_ = false;
  bytes_ += line_.size();
  line_.clear();
  fields_ = 0;
}

}  // namespace gyro::sil
