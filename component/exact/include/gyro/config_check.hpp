// The answer of a configuration check: which field is refused, its value, the bound it broke
// and the rule that bound comes from, without heap. check(config) returns the first refusal;
// check_all(config, sink) hands every violated rule to `sink` (a ConfigCheckList collects
// them); format_refusal writes the message into a caller's buffer:
//
//   component.residual_limit_rad = 1e-05 is below 2 pickoff LSBs (0.000122): a healthy gyro
//   would latch a fault
//
// No heap, no exceptions, no RTTI; C++17.
#pragma once

#include <array>
#include <cstddef>
#include <string_view>
#include <cstdint>
#include <cstdio>

#include "gyro/status.hpp"

namespace gyro {

// How the refused value stands to its bound.
enum class Relation : std::uint8_t {
  kNone = 0,   // no bound to name (a choice outside its enumeration, an overflow)
  kBelow,      // value < bound
  kAbove,      // value > bound
  kNotFinite,  // NaN or an infinity
};

// Names the configuration field a refusal is about (field nullptr when accepted). The texts
// are static strings; value and bound are doubles whatever the configuration's scalar.
struct ConfigCheck {
  Status status{Status::kOk};
  const char* field{nullptr};
  double value{0};                  // the refused value (as a double)
  double bound{0};                  // the bound it broke
  Relation relation{Relation::kNone};
  const char* bound_name{nullptr};  // what the bound is ("2 pickoff LSBs"); nullptr: its own range
  const char* rule{nullptr};        // why ("a healthy gyro would latch a fault")
  [[nodiscard]] constexpr bool ok() const noexcept { return status == Status::kOk; }
};

// A refusal of `field` = value for breaking `bound` (below or above it), with the rule's texts.
[[nodiscard]] constexpr ConfigCheck refuse_below(const char* field, double value, double bound, const char* bound_name,
                                                 const char* rule, Status st = Status::kOutOfRange) noexcept {
  return ConfigCheck{st, field, value, bound, Relation::kBelow, bound_name, rule};
}
[[nodiscard]] constexpr ConfigCheck refuse_above(const char* field, double value, double bound, const char* bound_name,
                                                 const char* rule, Status st = Status::kOutOfRange) noexcept {
  return ConfigCheck{st, field, value, bound, Relation::kAbove, bound_name, rule};
}

// Up to N refusals, in the order the rules ran; more are counted, not kept.
template <std::size_t N>
class ConfigCheckList {
 public:
  void operator()(const ConfigCheck& c) noexcept {
    if (c.ok()) return;
    if (size_ < N) items_[size_++] = c;
    ++total_;
  }
  [[nodiscard]] std::size_t size() const noexcept { return size_; }
  [[nodiscard]] std::size_t total() const noexcept { return total_; }  // kept and dropped
  [[nodiscard]] bool empty() const noexcept { return total_ == 0; }
  [[nodiscard]] const ConfigCheck& operator[](std::size_t i) const noexcept { return items_[i]; }
  [[nodiscard]] const ConfigCheck* begin() const noexcept { return items_.data(); }
  [[nodiscard]] const ConfigCheck* end() const noexcept { return items_.data() + size_; }
  // The refusal that names `field`, or nullptr.
  [[nodiscard]] const ConfigCheck* find(const char* field) const noexcept {
    for (std::size_t i = 0; i < size_; ++i) {
      if (items_[i].field != nullptr && field != nullptr &&
          std::string_view(items_[i].field) == std::string_view(field)) {
        return &items_[i];
      }
    }
    return nullptr;
  }

 private:
  std::array<ConfigCheck, N> items_{};
  std::size_t size_{0};
  std::size_t total_{0};
};

// Keeps the first refusal it is handed (what check() returns).
struct FirstRefusal {
  ConfigCheck first{};
  void operator()(const ConfigCheck& c) noexcept {
    if (first.ok() && !c.ok()) first = c;
  }
};

// Writes "<prefix><field> = <value> is below <bound name> (<bound>): <rule>" into buf (always
// terminated when n > 0); returns what snprintf returns. prefix may be nullptr.
// Truncating into a small buffer is the contract (the return says how much was wanted): GCC's
// warning on a buffer it can see is too small is no defect here.
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wformat-truncation"
#endif
inline int format_refusal(const ConfigCheck& c, const char* prefix, char* buf, std::size_t n) noexcept {
  if (buf == nullptr || n == 0) return 0;
  const char* p = prefix != nullptr ? prefix : "";
  const char* f = c.field != nullptr ? c.field : "(unnamed)";
  const char* rule = c.rule != nullptr ? c.rule : to_string(c.status);
  switch (c.relation) {
    case Relation::kBelow:
    case Relation::kAbove: {
      const char* rel = c.relation == Relation::kBelow ? "below" : "above";
      const char* what = c.bound_name != nullptr ? c.bound_name
                         : c.relation == Relation::kBelow ? "its lower bound"
                                                          : "its upper bound";
      return std::snprintf(buf, n, "%s%s = %.6g is %s %s (%.6g): %s", p, f, c.value, rel, what, c.bound, rule);
    }
    case Relation::kNotFinite: return std::snprintf(buf, n, "%s%s is not a finite number: %s", p, f, rule);
    case Relation::kNone: break;
  }
  return std::snprintf(buf, n, "%s%s: %s", p, f, rule);
}
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic pop
#endif

}  // namespace gyro
