// A refusal of a campaign file, its base scenario or the command line: the file, the field
// as a JSON path ("dispersions[2].path") and the reason, as scenarios are refused.
#pragma once

#include <stdexcept>
#include <string>

namespace gyro::campaign {

class CampaignError : public std::runtime_error {
 public:
  CampaignError(std::string file, std::string field, std::string reason)
      : std::runtime_error(file + ": " + field + ": " + reason),
        file_(std::move(file)),
        field_(std::move(field)),
        reason_(std::move(reason)) {}
  [[nodiscard]] const std::string& file() const noexcept { return file_; }
  [[nodiscard]] const std::string& field() const noexcept { return field_; }
  [[nodiscard]] const std::string& reason() const noexcept { return reason_; }

 private:
  std::string file_, field_, reason_;
};

}  // namespace gyro::campaign
