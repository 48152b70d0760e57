// Names of enumerations, one table per enumeration: an enum_names(E) beside each enum gives
// its values' names as files, logs and bindings spell them, in enumerator order, and every
// lookup goes through the three functions below (no switch of names anywhere else).
// No heap, no exceptions, no RTTI; C++17.
#pragma once

#include <cstddef>
#include <string_view>
#include <type_traits>

namespace gyro {

// An enumeration whose names (as files and bindings spell them, in enumerator order) are given
// by an enum_names(E) beside it.
template <class E, class = void>
inline constexpr bool kHasEnumNames = false;
template <class E>
inline constexpr bool kHasEnumNames<E, std::void_t<decltype(enum_names(E{}))>> = true;

// The name enum_names(E) gives `e`; nullptr for a value outside the enumeration.
template <class E>
[[nodiscard]] constexpr const char* enum_name(E e) noexcept {
  constexpr auto names = enum_names(E{});
  const auto i = static_cast<std::size_t>(e);
  return i < names.size() ? names[i] : nullptr;
}

// The enumerator `name` spells; false, and `out` left as it was, if none does.
template <class E>
[[nodiscard]] constexpr bool enum_from_name(std::string_view name, E& out) noexcept {
  constexpr auto names = enum_names(E{});
  for (std::size_t i = 0; i < names.size(); ++i) {
    if (name == std::string_view(names[i])) {
      out = static_cast<E>(i);
      return true;
    }
  }
  return false;
}

// enum_name(e), or `unknown` for a value outside the enumeration (for messages and logs).
template <class E>
[[nodiscard]] constexpr const char* enum_name_or(E e, const char* unknown) noexcept {
  const char* name = enum_name(e);
  return name != nullptr ? name : unknown;
}

}  // namespace gyro
