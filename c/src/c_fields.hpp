// The C API's configuration structs (gyro.h's field lists) bound to the C++ configurations'
// field tables (gyro/config_fields.hpp): each C member by name and offset, walked in lockstep
// with the C++ table, so that the C++ table decides names, order, rules and messages and the
// C struct only mirrors it. A C member the table does not have, or one out of order, makes the
// walk fail (and the model configuration's is checked at compile time, c_config.cpp).
// No heap, no exceptions.
#pragma once

#include <cstddef>
#include <cstdint>
#include <cstring>
#include <type_traits>

#include "gyro/config_fields.hpp"
#include "gyro/gyro.h"

namespace gyro::c_api {

enum class CKind : std::uint8_t { kReal, kVec3, kChoice, kNested };

struct CStruct;
struct CField {
  const char* name;
  std::size_t offset;
  CKind kind;
  const CStruct* nested;  // kNested: its members
};
struct CStruct {
  const CField* fields;
  std::size_t count;
};

// The kind of each X(kind, name) of gyro.h, and the nested struct it names.
#define GYRO_C_KIND_REAL CKind::kReal
#define GYRO_C_KIND_VEC3 CKind::kVec3
#define GYRO_C_KIND_CHOICE CKind::kChoice
#define GYRO_C_KIND_AXIS_ERRORS CKind::kNested
#define GYRO_C_KIND_ERROR_SOURCES CKind::kNested
#define GYRO_C_NESTED_REAL nullptr
#define GYRO_C_NESTED_VEC3 nullptr
#define GYRO_C_NESTED_CHOICE nullptr
#define GYRO_C_NESTED_AXIS_ERRORS &kAxisErrors
#define GYRO_C_NESTED_ERROR_SOURCES &kErrorSources
#define GYRO_C_BIND(kind, name) CField{#name, offsetof(GYRO_C_STRUCT, name), GYRO_C_KIND_##kind, GYRO_C_NESTED_##kind},

#define GYRO_C_STRUCT gyro_axis_errors
inline constexpr CField kAxisErrorsFields[] = {GYRO_AXIS_ERRORS_FIELDS(GYRO_C_BIND)};
#undef GYRO_C_STRUCT
inline constexpr CStruct kAxisErrors{kAxisErrorsFields, sizeof(kAxisErrorsFields) / sizeof(CField)};

#define GYRO_C_STRUCT gyro_error_sources
inline constexpr CField kErrorSourcesFields[] = {GYRO_ERROR_SOURCES_FIELDS(GYRO_C_BIND)};
#undef GYRO_C_STRUCT
inline constexpr CStruct kErrorSources{kErrorSourcesFields, sizeof(kErrorSourcesFields) / sizeof(CField)};

#define GYRO_C_STRUCT gyro_model_config
inline constexpr CField kModelConfigFields[] = {GYRO_MODEL_CONFIG_FIELDS(GYRO_C_BIND)};
#undef GYRO_C_STRUCT
inline constexpr CStruct kModelConfig{kModelConfigFields, sizeof(kModelConfigFields) / sizeof(CField)};

#define GYRO_C_STRUCT gyro_plant_config
inline constexpr CField kPlantConfigFields[] = {GYRO_PLANT_CONFIG_FIELDS(GYRO_C_BIND)};
#undef GYRO_C_STRUCT
inline constexpr CStruct kPlantConfig{kPlantConfigFields, sizeof(kPlantConfigFields) / sizeof(CField)};

[[nodiscard]] constexpr bool same_name(const char* a, const char* b) noexcept {
  std::size_t i = 0;
  for (; a[i] != '\0' && b[i] != '\0'; ++i) {
    if (a[i] != b[i]) return false;
  }
  return a[i] == b[i];
}

template <class M>
[[nodiscard]] constexpr CKind kind_of() noexcept {
  if constexpr (std::is_floating_point_v<M>) {
    return CKind::kReal;
  } else if constexpr (kHasEnumNames<M>) {
    return CKind::kChoice;
  } else if constexpr (kHasFieldTable<M>) {
    return CKind::kNested;
  } else {
    static_assert(M::RowsAtCompileTime == 3 && M::ColsAtCompileTime == 1, "a field kind gyro.h cannot carry");
    return CKind::kVec3;
  }
}

// Visits the C++ configuration `c` and the C struct at `base` in lockstep: fn(c_field, address
// of the C member, C++ member) for every leaf (nested structs entered). False if the two do not
// have the same fields in the same order with the same kinds.
template <class Config, class Fn>
[[nodiscard]] constexpr bool walk(const CStruct& s, std::uintptr_t base, Config& c, Fn&& fn) {
  bool ok = true;
  std::size_t i = 0;
  visit_fields(
      [&](const Field& f, auto& member) {
        using M = std::remove_cv_t<std::remove_reference_t<decltype(member)>>;
        if (!ok || i >= s.count || !same_name(f.name, s.fields[i].name) || kind_of<M>() != s.fields[i].kind) {
          ok = false;
          return;
        }
        const CField& cf = s.fields[i++];
        if constexpr (kHasFieldTable<M>) {
          ok = walk(*cf.nested, base + cf.offset, member, fn);
        } else {
          fn(cf, base + cf.offset, member);
        }
      },
      c);
  return ok && i == s.count;
}

// The C struct's address as an integer for walk() (no pointer arithmetic on the caller's type).
[[nodiscard]] inline std::uintptr_t address_of(const void* p) noexcept { return reinterpret_cast<std::uintptr_t>(p); }

// Whether the C struct and the C++ table agree (a walk over a default configuration).
template <class Config>
[[nodiscard]] constexpr bool binds(const CStruct& s) {
  Config c{};
  return walk(s, 0, c, [](const CField&, std::uintptr_t, const auto&) {});
}

// C struct -> C++ configuration. A choice outside its names is refused here, naming the field
// (the C++ enums are bytes: a wrapped int would pass their check).
template <class Config>
[[nodiscard]] ConfigCheck read_config(const CStruct& s, const void* from, Config& to) noexcept {
  ConfigCheck refused{};
  const bool ok = walk(s, address_of(from), to, [&refused](const CField& cf, std::uintptr_t at, auto& member) noexcept {
    using M = std::remove_cv_t<std::remove_reference_t<decltype(member)>>;
    const auto* p = reinterpret_cast<const unsigned char*>(at);
    if constexpr (std::is_floating_point_v<M>) {
      double v = 0;
      std::memcpy(&v, p, sizeof v);
      member = static_cast<M>(v);
    } else if constexpr (kHasEnumNames<M>) {
      int v = 0;
      std::memcpy(&v, p, sizeof v);
      constexpr auto names = enum_names(M{});
      if (v < 0 || static_cast<std::size_t>(v) >= names.size()) {
        if (refused.ok()) {
          refused = ConfigCheck{Status::kOutOfRange, cf.name, static_cast<double>(v), 0.0, Relation::kNone, nullptr,
                                "a choice: the index of one of its names (gyro_config_choice_name)"};
        }
        return;
      }
      member = static_cast<M>(v);
    } else {
      double v[3] = {0, 0, 0};
      std::memcpy(v, p, sizeof v);
      member = M(static_cast<typename M::Scalar>(v[0]), static_cast<typename M::Scalar>(v[1]),
                 static_cast<typename M::Scalar>(v[2]));
    }
  });
  if (!ok) return ConfigCheck{Status::kOutOfRange, "(configuration)", 0.0, 0.0, Relation::kNone, nullptr,
                              "the C struct does not match the library's field table"};
  return refused;
}

// C++ configuration -> C struct.
template <class Config>
[[nodiscard]] bool write_config(const CStruct& s, const Config& from, void* to) noexcept {
  Config copy = from;
  return walk(s, address_of(to), copy, [](const CField&, std::uintptr_t at, const auto& member) noexcept {
    using M = std::remove_cv_t<std::remove_reference_t<decltype(member)>>;
    auto* p = reinterpret_cast<unsigned char*>(at);
    if constexpr (std::is_floating_point_v<M>) {
      const double v = static_cast<double>(member);
      std::memcpy(p, &v, sizeof v);
    } else if constexpr (kHasEnumNames<M>) {
      const int v = static_cast<int>(member);
      std::memcpy(p, &v, sizeof v);
    } else {
      const double v[3] = {static_cast<double>(member(0)), static_cast<double>(member(1)),
                           static_cast<double>(member(2))};
      std::memcpy(p, v, sizeof v);
    }
  });
}

// The refusal as gyro.h spells it.
inline void to_c(const ConfigCheck& c, gyro_refusal* out) noexcept {
  if (out == nullptr) return;
  out->status = static_cast<int>(c.status);
  out->field = c.ok() ? nullptr : c.field;
  out->value = c.value;
  out->bound = c.bound;
  out->relation = static_cast<int>(c.relation);
  out->bound_name = c.bound_name;
  out->rule = c.rule;
}

// The leaves of a C struct (nested members flattened), with dotted names
// ("errors.pitch.static_drift_rad_s") and offsets from the struct's start, computed at
// compile time: what the by-name functions of gyro.h look up.
struct Leaf {
  char name[64]{};
  std::size_t offset{0};
  CKind kind{CKind::kReal};
};
template <std::size_t N>
struct Leaves {
  Leaf leaf[N]{};
  std::size_t count{0};
};

[[nodiscard]] constexpr std::size_t count_leaves(const CStruct& s) noexcept {
  std::size_t n = 0;
  for (std::size_t i = 0; i < s.count; ++i) n += s.fields[i].kind == CKind::kNested ? count_leaves(*s.fields[i].nested) : 1;
  return n;
}

template <std::size_t N>
constexpr void add_leaves(const CStruct& s, const char* prefix, std::size_t base, Leaves<N>& out) noexcept {
  for (std::size_t i = 0; i < s.count; ++i) {
    const CField& f = s.fields[i];
    char name[64]{};
    std::size_t k = 0;
    for (std::size_t j = 0; prefix[j] != '\0' && k + 1 < sizeof name; ++j) name[k++] = prefix[j];
    for (std::size_t j = 0; f.name[j] != '\0' && k + 1 < sizeof name; ++j) name[k++] = f.name[j];
    if (f.kind == CKind::kNested) {
      if (k + 1 < sizeof name) name[k++] = '.';
      add_leaves(*f.nested, name, base + f.offset, out);
      continue;
    }
    Leaf& l = out.leaf[out.count++];
    for (std::size_t j = 0; j < sizeof name; ++j) l.name[j] = name[j];
    l.offset = base + f.offset;
    l.kind = f.kind;
  }
}

template <std::size_t N>
[[nodiscard]] constexpr Leaves<N> make_leaves(const CStruct& s) noexcept {
  Leaves<N> out{};
  add_leaves(s, "", 0, out);
  return out;
}

}  // namespace gyro::c_api
