// One table per configuration struct: each field's name, its rule and where a configuration
// file gives it. The table is a visitor beside the struct,
//
//   template <typename T> struct FieldTable<GyroComponentConfig<T>> {
//     template <class Visit, class... C> static constexpr void visit(Visit&& v, C&... c) {
//       v(Field{"tick_s", Rule::kPositive, Status::kNonPositiveStep, Presence::kImplied}, c.tick_s...);
//       ...
//
// called with one configuration (validation, parsing, documentation) or with several of the
// same struct in lockstep (a double configuration cast to float). Everything that lists a
// struct's fields walks its table; adding a field is a struct member and a table row.
// No heap, no exceptions, no RTTI; C++17.
#pragma once

#include <Eigen/Core>
#include <array>
#include <cstddef>
#include <cmath>
#include <cstdint>
#include <limits>
#include <string_view>
#include <type_traits>

#include "gyro/config_check.hpp"
#include "gyro/enum_names.hpp"
#include "gyro/status.hpp"

namespace gyro {

// What a field must be on its own (cross-field rules stay in the struct's check()).
enum class Rule : std::uint8_t {
  kNone,         // nothing on its own (checked with other fields, or any value allowed)
  kFinite,       // a finite number (every coefficient of a vector)
  kPositive,     // > 0
  kNonNegative,  // >= 0 (every coefficient of a vector)
  kNonZero,      // a count >= 1
};

// Where a configuration file (a gyro_sil scenario) gives the field.
enum class Presence : std::uint8_t {
  kRequired,  // must be given
  kOptional,  // may be left out: the struct's initialiser stands
  kImplied,   // never read under this name: set from elsewhere (the run's tick, another field)
};

inline constexpr double kNoBound = std::numeric_limits<double>::infinity();

// A field's own range is [lower, upper] (both inclusive; for Rule::kPositive also > 0), in
// `unit`, for the reason `why`. Fields that have no range of their own (a choice, a switch, a
// nested struct) keep the infinite defaults; rules between fields are the struct's check_all().
struct Field {
  const char* name;                      // as files, refusals and docs spell it
  Rule rule{Rule::kNone};
  Status refusal{Status::kOutOfRange};   // when the rule fails (non-finite: kNonFiniteInput)
  Presence presence{Presence::kRequired};
  const char* section{nullptr};          // the object that holds it in a file (nullptr: none)
  double lower{-kNoBound};               // smallest accepted value (each coefficient of a vector)
  double upper{kNoBound};                // largest accepted value
  const char* unit{""};                  // as docs print it ("rad", "s", "1/s", "ticks")
  const char* why{nullptr};              // the reason for the range, one short clause
};

// The table of Config (specialised beside each configuration struct).
template <class Config>
struct FieldTable {
  static constexpr bool kDefined = false;
};

template <class Config>
inline constexpr bool kHasFieldTable = FieldTable<std::remove_const_t<Config>>::kDefined;

// Visits the fields of `c` (and, in lockstep, of `more`, configurations of the same struct
// in another scalar type): v(field, c.member, more.member...).
template <class Visit, class Config, class... More>
constexpr void visit_fields(Visit&& v, Config& c, More&... more) {
  FieldTable<std::remove_const_t<Config>>::visit(v, c, more...);
}

namespace field_detail {
template <class M>
struct IsEigen : std::is_base_of<Eigen::EigenBase<M>, M> {};
template <class M>
struct IsArray : std::false_type {};
template <class E, std::size_t N>
struct IsArray<std::array<E, N>> : std::true_type {};
}  // namespace field_detail

// How many fields of Config have a member type that `Select` takes (constexpr).
template <class Config, template <class> class Select>
[[nodiscard]] constexpr std::size_t count_fields() noexcept {
  std::size_t n = 0;
  const Config c{};
  visit_fields([&n](const Field&, const auto& m) { n += Select<std::decay_t<decltype(m)>>::value ? 1u : 0u; }, c);
  return n;
}
template <class M>
struct AnyField : std::true_type {};

// Every floating-point number in `c` (nested structs included) is finite.
template <class Config>
[[nodiscard]] bool all_fields_finite(const Config& c) noexcept {
  bool ok = true;
  visit_fields(
      [&ok](const Field&, const auto& value) noexcept {
        using M = std::decay_t<decltype(value)>;
        if constexpr (std::is_floating_point_v<M>) {
          ok = ok && std::isfinite(value);
        } else if constexpr (field_detail::IsEigen<M>::value) {
          ok = ok && value.allFinite();
        } else if constexpr (kHasFieldTable<M>) {
          ok = ok && all_fields_finite(value);
        }
      },
      c);
  return ok;
}

namespace field_detail {
// The refusal of `f` = v against its own rule and range (ok when it keeps them).
[[nodiscard]] inline ConfigCheck scalar_check(const Field& f, double v, bool real) noexcept {
  const char* why = f.why != nullptr ? f.why : "the field's own range";
  if (real && !std::isfinite(v)) {
    return ConfigCheck{Status::kNonFiniteInput, f.name, v, 0.0, Relation::kNotFinite, nullptr, why};
  }
  if (f.rule == Rule::kPositive && !(v > 0.0)) {
    return refuse_below(f.name, v, f.lower > 0.0 ? f.lower : 0.0, f.lower > 0.0 ? nullptr : "0 (must be > 0)", why,
                        f.refusal);
  }
  if ((f.rule == Rule::kNonNegative) && v < 0.0) {
    return refuse_below(f.name, v, f.lower > 0.0 ? f.lower : 0.0, f.lower > 0.0 ? nullptr : "0", why, f.refusal);
  }
  if (f.rule == Rule::kNonZero && v == 0.0) {
    return refuse_below(f.name, v, f.lower > 1.0 ? f.lower : 1.0, f.lower > 1.0 ? nullptr : "1", why, f.refusal);
  }
  if (v < f.lower) return refuse_below(f.name, v, f.lower, nullptr, why, f.refusal);
  if (v > f.upper) return refuse_above(f.name, v, f.upper, nullptr, why, f.refusal);
  return {};
}
}  // namespace field_detail

// The refusal of `value` against the field's own rule and range; ok when it keeps them.
// Fields with Rule::kNone are not looked at (their rules are the struct's).
template <class M>
[[nodiscard]] ConfigCheck field_check(const Field& f, const M& value) noexcept {
  if (f.rule == Rule::kNone) return {};
  if constexpr (std::is_floating_point_v<M>) {
    return field_detail::scalar_check(f, static_cast<double>(value), true);
  } else if constexpr (field_detail::IsEigen<M>::value) {
    for (Eigen::Index i = 0; i < value.size(); ++i) {
      const ConfigCheck c = field_detail::scalar_check(f, static_cast<double>(value(i)), true);
      if (!c.ok()) return c;
    }
  } else if constexpr (std::is_integral_v<M> && !std::is_same_v<M, bool>) {
    return field_detail::scalar_check(f, static_cast<double>(value), false);
  } else if constexpr (kHasFieldTable<M>) {
    if (f.rule == Rule::kFinite && !all_fields_finite(value)) {
      return ConfigCheck{Status::kNonFiniteInput, f.name, 0.0, 0.0, Relation::kNotFinite, nullptr, "every number finite"};
    }
  }
  return {};
}

// Status::kOk when `value` keeps the field's own rule and range; otherwise the status to refuse with.
template <class M>
[[nodiscard]] Status rule_status(const Field& f, const M& value) noexcept {
  return field_check(f, value).status;
}

// Hands the refusal of every field of `c` whose own rule or range fails, among those `Select`
// takes (by member type), to sink(const ConfigCheck&), in table order.
template <template <class> class Select, class Config, class Sink>
void check_fields(const Config& c, Sink&& sink) noexcept {
  visit_fields(
      [&sink](const Field& f, const auto& value) noexcept {
        using M = std::decay_t<decltype(value)>;
        if constexpr (Select<M>::value) {
          const ConfigCheck r = field_check(f, value);
          if (!r.ok()) sink(r);
        }
      },
      c);
}

// The first field of `c` whose own rule fails among those `Select` takes (by member type):
// its status and name; {kOk, nullptr} when none.
struct FieldRefusal {
  Status status{Status::kOk};
  const char* field{nullptr};
  ConfigCheck check{};  // the whole refusal (value, bound, rule)
};
template <template <class> class Select, class Config>
[[nodiscard]] FieldRefusal first_refusal(const Config& c) noexcept {
  FirstRefusal first;
  check_fields<Select>(c, first);
  return FieldRefusal{first.first.status, first.first.field, first.first};
}

// Member selections for first_refusal: the numbers and vectors, or the counts.
template <class M>
struct RealFields
    : std::bool_constant<std::is_floating_point_v<M> || field_detail::IsEigen<M>::value || kHasFieldTable<M>> {};
template <class M>
struct CountFields : std::bool_constant<std::is_integral_v<M> && !std::is_same_v<M, bool>> {};
template <class M>
struct SwitchFields : std::is_same<M, bool> {};

// `from` in another scalar type, field by field (numbers cast, everything else copied).
template <class To, class From>
void cast_fields(const From& from, To& to) noexcept {
  visit_fields(
      [](const Field&, const auto& src, auto& dst) noexcept {
        using S = std::decay_t<decltype(src)>;
        using D = std::decay_t<decltype(dst)>;
        if constexpr (std::is_floating_point_v<S>) {
          dst = static_cast<D>(src);
        } else if constexpr (field_detail::IsEigen<S>::value) {
          dst = src.template cast<typename D::Scalar>();
        } else if constexpr (kHasFieldTable<S>) {
          cast_fields(src, dst);
        } else if constexpr (field_detail::IsArray<S>::value) {
          for (std::size_t i = 0; i < src.size(); ++i) cast_fields(src[i], dst[i]);
        } else {
          dst = src;
        }
      },
      from, to);
}

}  // namespace gyro
