// gyro.h's configuration structs by name (gyro_config_*): sizes, defaults, and each leaf field
// read and written by its dotted name, from the compile-time leaf tables of c_fields.hpp.
// Flight part: no heap, no exceptions.
#include <cmath>
#include <cstring>

#include "c_fields.hpp"
#include "gyro/gimbal_plant_config.hpp"
#include "gyro/gyro_model.hpp"

namespace gyro::c_api {
namespace {

// The model's configuration is a literal type: its C struct is checked against the table here;
// the plant's (Eigen members) at every configure and by the C API's tests.
static_assert(binds<GyroModelConfig<double>>(kModelConfig), "gyro_model_config does not match GyroModelConfig's table");

constexpr std::size_t kModelLeafCount = count_leaves(kModelConfig);
constexpr std::size_t kPlantLeafCount = count_leaves(kPlantConfig);
constexpr Leaves<kModelLeafCount> kModelLeaves = make_leaves<kModelLeafCount>(kModelConfig);
constexpr Leaves<kPlantLeafCount> kPlantLeaves = make_leaves<kPlantLeafCount>(kPlantConfig);

// One configuration kind: its C struct, its leaves and its C++ configuration.
template <class Config, std::size_t N>
struct Kind {
  using CppConfig = Config;
  const CStruct& c_struct;
  const Leaves<N>& leaves;
  std::size_t size;

  [[nodiscard]] const Leaf* find(const char* name) const noexcept {
    if (name == nullptr) return nullptr;
    for (std::size_t i = 0; i < leaves.count; ++i) {
      if (std::strcmp(leaves.leaf[i].name, name) == 0) return &leaves.leaf[i];
    }
    return nullptr;
  }
  // The names of the choice at offset `at` (nullptr: no choice there), as enum_names gives them.
  [[nodiscard]] const char* choice_name(std::size_t at, std::size_t index) const noexcept {
    const char* found = nullptr;
    Config c{};
    (void)walk(c_struct, 0, c, [&](const CField&, std::uintptr_t offset, const auto& member) noexcept {
      using M = std::remove_cv_t<std::remove_reference_t<decltype(member)>>;
      if constexpr (kHasEnumNames<M>) {
        constexpr auto names = enum_names(M{});
        if (offset == at && index < names.size()) found = names[index];
      }
    });
    return found;
  }
};

constexpr Kind<GyroModelConfig<double>, kModelLeafCount> kModel{kModelConfig, kModelLeaves, sizeof(gyro_model_config)};
constexpr Kind<GimbalPlantConfig<double>, kPlantLeafCount> kPlant{kPlantConfig, kPlantLeaves, sizeof(gyro_plant_config)};

// fn(kind) for the configuration `kind` names; `otherwise` when none.
template <class Fn, class R>
R with_kind(int kind, R otherwise, Fn&& fn) noexcept {
  if (kind == GYRO_MODEL_CONFIG) return fn(kModel);
  if (kind == GYRO_PLANT_CONFIG) return fn(kPlant);
  return otherwise;
}

[[nodiscard]] std::size_t length_of(const Leaf& l) noexcept {
  return l.kind == CKind::kVec3 ? 3u : (l.kind == CKind::kReal ? 1u : 0u);
}
unsigned char* at(void* config, const Leaf& l) noexcept { return static_cast<unsigned char*>(config) + l.offset; }
const unsigned char* at(const void* config, const Leaf& l) noexcept {
  return static_cast<const unsigned char*>(config) + l.offset;
}

}  // namespace
}  // namespace gyro::c_api

using gyro::c_api::CKind;
using gyro::c_api::Leaf;
using gyro::c_api::with_kind;

extern "C" {

size_t gyro_config_size(int kind) {
  return with_kind(kind, std::size_t{0}, [](const auto& k) noexcept { return k.size; });
}

int gyro_config_init(int kind, void* config) {
  if (config == nullptr) return GYRO_NULL_ARGUMENT;
  return with_kind(kind, static_cast<int>(GYRO_UNKNOWN_FIELD), [config](const auto& k) noexcept {
    std::memset(config, 0, k.size);
    const typename std::remove_reference_t<decltype(k)>::CppConfig defaults{};
    return gyro::c_api::write_config(k.c_struct, defaults, config) ? static_cast<int>(GYRO_OK)
                                                                    : static_cast<int>(GYRO_INTERNAL_ERROR);
  });
}

size_t gyro_config_field_count(int kind) {
  return with_kind(kind, std::size_t{0}, [](const auto& k) noexcept { return k.leaves.count; });
}

const char* gyro_config_field_name(int kind, size_t index) {
  return with_kind(kind, static_cast<const char*>(nullptr), [index](const auto& k) noexcept {
    return index < k.leaves.count ? static_cast<const char*>(k.leaves.leaf[index].name) : nullptr;
  });
}

size_t gyro_config_field_length(int kind, const char* name) {
  return with_kind(kind, std::size_t{0}, [name](const auto& k) noexcept {
    const Leaf* l = k.find(name);
    return l != nullptr ? gyro::c_api::length_of(*l) : std::size_t{0};
  });
}

int gyro_config_set(int kind, void* config, const char* name, const double* values, size_t n) {
  if (config == nullptr || values == nullptr) return GYRO_NULL_ARGUMENT;
  return with_kind(kind, static_cast<int>(GYRO_UNKNOWN_FIELD), [=](const auto& k) noexcept {
    const Leaf* l = k.find(name);
    if (l == nullptr) return static_cast<int>(GYRO_UNKNOWN_FIELD);
    if (l->kind == CKind::kChoice) {  // by its index
      if (n != 1 || !(values[0] >= 0.0 && values[0] < 256.0) || values[0] != std::floor(values[0])) {
        return static_cast<int>(GYRO_OUT_OF_RANGE);
      }
      if (k.choice_name(l->offset, static_cast<std::size_t>(values[0])) == nullptr) return static_cast<int>(GYRO_OUT_OF_RANGE);
      const int v = static_cast<int>(values[0]);
      std::memcpy(gyro::c_api::at(config, *l), &v, sizeof v);
      return static_cast<int>(GYRO_OK);
    }
    if (n != gyro::c_api::length_of(*l)) return static_cast<int>(GYRO_OUT_OF_RANGE);
    std::memcpy(gyro::c_api::at(config, *l), values, n * sizeof(double));
    return static_cast<int>(GYRO_OK);
  });
}

int gyro_config_get(int kind, const void* config, const char* name, double* values, size_t n) {
  if (config == nullptr || values == nullptr) return GYRO_NULL_ARGUMENT;
  return with_kind(kind, static_cast<int>(GYRO_UNKNOWN_FIELD), [=](const auto& k) noexcept {
    const Leaf* l = k.find(name);
    if (l == nullptr) return static_cast<int>(GYRO_UNKNOWN_FIELD);
    if (l->kind == CKind::kChoice) {
      if (n < 1) return static_cast<int>(GYRO_OUT_OF_RANGE);
      int v = 0;
      std::memcpy(&v, gyro::c_api::at(config, *l), sizeof v);
      values[0] = v;
      return static_cast<int>(GYRO_OK);
    }
    const std::size_t len = gyro::c_api::length_of(*l);
    if (n < len) return static_cast<int>(GYRO_OUT_OF_RANGE);
    std::memcpy(values, gyro::c_api::at(config, *l), len * sizeof(double));
    return static_cast<int>(GYRO_OK);
  });
}

int gyro_config_set_choice(int kind, void* config, const char* name, const char* choice) {
  if (config == nullptr || choice == nullptr) return GYRO_NULL_ARGUMENT;
  return with_kind(kind, static_cast<int>(GYRO_UNKNOWN_FIELD), [=](const auto& k) noexcept {
    const Leaf* l = k.find(name);
    if (l == nullptr || l->kind != CKind::kChoice) return static_cast<int>(GYRO_UNKNOWN_FIELD);
    for (int i = 0; i < 256; ++i) {
      const char* n = k.choice_name(l->offset, static_cast<std::size_t>(i));
      if (n == nullptr) break;
      if (std::strcmp(n, choice) == 0) {
        std::memcpy(gyro::c_api::at(config, *l), &i, sizeof i);
        return static_cast<int>(GYRO_OK);
      }
    }
    return static_cast<int>(GYRO_UNKNOWN_FIELD);
  });
}

const char* gyro_config_choice(int kind, const void* config, const char* name) {
  if (config == nullptr) return nullptr;
  return with_kind(kind, static_cast<const char*>(nullptr), [=](const auto& k) noexcept -> const char* {
    const Leaf* l = k.find(name);
    if (l == nullptr || l->kind != CKind::kChoice) return nullptr;
    int v = 0;
    std::memcpy(&v, gyro::c_api::at(config, *l), sizeof v);
    return v < 0 ? nullptr : k.choice_name(l->offset, static_cast<std::size_t>(v));
  });
}

const char* gyro_config_choice_name(int kind, const char* name, size_t index) {
  return with_kind(kind, static_cast<const char*>(nullptr), [=](const auto& k) noexcept -> const char* {
    const Leaf* l = k.find(name);
    if (l == nullptr || l->kind != CKind::kChoice) return nullptr;
    return k.choice_name(l->offset, index);
  });
}

}  // extern "C"
