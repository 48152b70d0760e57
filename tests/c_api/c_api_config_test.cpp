// The C API's configuration structs against the C++ field tables: every field of
// GyroModelConfig and GimbalPlantConfig set by its name in C reaches the C++ member of that name
// (nested ones under their dotted names), the defaults are the C++ initialisers, and a refusal
// names the field as the C++ check does.
#include <gtest/gtest.h>

#include <cstring>
#include <map>
#include <string>
#include <type_traits>

#include "c_fields.hpp"  // c/src: the binding under test
#include "gyro/gimbal_plant.hpp"
#include "gyro/gyro.h"
#include "gyro/gyro_model.hpp"

namespace gyro {
namespace {

// Every leaf of a C++ configuration by dotted name: its numbers as doubles (an enum as its
// index), walked with the C++ table alone.
template <class Config>
void leaves(const Config& c, const std::string& prefix, std::map<std::string, std::vector<double>>& out) {
  visit_fields(
      [&](const Field& f, const auto& m) {
        using M = std::decay_t<decltype(m)>;
        const std::string name = prefix + f.name;
        if constexpr (std::is_floating_point_v<M>) {
          out[name] = {static_cast<double>(m)};
        } else if constexpr (kHasEnumNames<M>) {
          out[name] = {static_cast<double>(static_cast<int>(m))};
        } else if constexpr (kHasFieldTable<M>) {
          leaves(m, name + ".", out);
        } else {
          out[name] = {static_cast<double>(m(0)), static_cast<double>(m(1)), static_cast<double>(m(2))};
        }
      },
      c);
}

template <class Config>
std::map<std::string, std::vector<double>> leaves(const Config& c) {
  std::map<std::string, std::vector<double>> out;
  leaves(c, "", out);
  return out;
}

// Sets every leaf of a C struct by name to a value of its own (a choice to its last name),
// converts it with the binding, and compares the C++ configuration's leaves by name.
template <class Config, class CStruct>
void expect_every_field_reaches_its_member(int kind, const c_api::CStruct& table) {
  CStruct c{};
  ASSERT_EQ(gyro_config_init(kind, &c), GYRO_OK);
  std::map<std::string, std::vector<double>> expected;
  const std::size_t n = gyro_config_field_count(kind);
  for (std::size_t i = 0; i < n; ++i) {
    const char* name = gyro_config_field_name(kind, i);
    ASSERT_NE(name, nullptr);
    const std::size_t len = gyro_config_field_length(kind, name);
    if (len == 0) {  // a choice: its last name
      std::size_t last = 0;
      while (gyro_config_choice_name(kind, name, last + 1) != nullptr) ++last;
      ASSERT_EQ(gyro_config_set_choice(kind, &c, name, gyro_config_choice_name(kind, name, last)), GYRO_OK) << name;
      expected[name] = {static_cast<double>(last)};
      continue;
    }
    std::vector<double> v;
    for (std::size_t j = 0; j < len; ++j) v.push_back(1.0 + static_cast<double>(i) + 0.25 * static_cast<double>(j));
    ASSERT_EQ(gyro_config_set(kind, &c, name, v.data(), v.size()), GYRO_OK) << name;
    expected[name] = v;
  }
  Config cpp{};
  const ConfigCheck read = c_api::read_config(table, &c, cpp);
  ASSERT_TRUE(read.ok()) << (read.field != nullptr ? read.field : "") << ": " << (read.rule != nullptr ? read.rule : "");
  EXPECT_EQ(leaves(cpp), expected);
  EXPECT_EQ(expected.size(), n);
}

TEST(CApiConfig, GivenEveryModelFieldByNameThenItReachesItsCppMember) {
  expect_every_field_reaches_its_member<GyroModelConfig<double>, gyro_model_config>(GYRO_MODEL_CONFIG,
                                                                                     c_api::kModelConfig);
}

TEST(CApiConfig, GivenEveryPlantFieldByNameThenItReachesItsCppMember) {
  expect_every_field_reaches_its_member<GimbalPlantConfig<double>, gyro_plant_config>(GYRO_PLANT_CONFIG,
                                                                                       c_api::kPlantConfig);
}

TEST(CApiConfig, GivenTheDefaultsThenTheyAreTheCppInitialisers) {
  gyro_model_config m{};
  gyro_plant_config p{};
  ASSERT_EQ(gyro_config_init(GYRO_MODEL_CONFIG, &m), GYRO_OK);
  ASSERT_EQ(gyro_config_init(GYRO_PLANT_CONFIG, &p), GYRO_OK);
  GyroModelConfig<double> cm{};
  GimbalPlantConfig<double> cp{};
  ASSERT_TRUE(c_api::read_config(c_api::kModelConfig, &m, cm).ok());
  ASSERT_TRUE(c_api::read_config(c_api::kPlantConfig, &p, cp).ok());
  EXPECT_EQ(leaves(cm), leaves(GyroModelConfig<double>{}));
  EXPECT_EQ(leaves(cp), leaves(GimbalPlantConfig<double>{}));
  EXPECT_EQ(gyro_config_init(3, &m), GYRO_UNKNOWN_FIELD);
  EXPECT_EQ(gyro_config_size(0), 0u);
}

TEST(CApiConfig, GivenAPlantRefusalThenTheFieldIsTheCppChecks) {
  gyro_plant_config c{};
  ASSERT_EQ(gyro_config_init(GYRO_PLANT_CONFIG, &c), GYRO_OK);
  GimbalPlantConfig<double> cpp{};
  ASSERT_TRUE(c_api::read_config(c_api::kPlantConfig, &c, cpp).ok());
  GimbalPlant<double> plant;
  const ConfigCheck expected = plant.configure(cpp, 1e-3);
  ASSERT_FALSE(expected.ok());
  gyro_plant_d* p = gyro_plant_d_create();
  gyro_refusal r{};
  EXPECT_EQ(gyro_plant_d_configure(p, &c, 1e-3, &r), static_cast<int>(expected.status));
  EXPECT_STREQ(r.field, expected.field);
  char text[300];
  char cpp_text[300];
  EXPECT_GT(gyro_refusal_text(&r, text, sizeof text), 0);
  EXPECT_GT(format_refusal(expected, nullptr, cpp_text, sizeof cpp_text), 0);
  EXPECT_STREQ(text, cpp_text);
  gyro_plant_d_destroy(p);
}

TEST(CApiConfig, GivenAChoiceOutOfItsNamesThenItIsRefusedByName) {
  gyro_plant_config c{};
  ASSERT_EQ(gyro_config_init(GYRO_PLANT_CONFIG, &c), GYRO_OK);
  c.spin_drive = 256;  // would wrap to a valid byte
  GimbalPlantConfig<double> cpp{};
  const ConfigCheck r = c_api::read_config(c_api::kPlantConfig, &c, cpp);
  EXPECT_EQ(r.status, Status::kOutOfRange);
  EXPECT_STREQ(r.field, "spin_drive");
  const double index = 2.0;
  EXPECT_EQ(gyro_config_set(GYRO_PLANT_CONFIG, &c, "spin_drive", &index, 1), GYRO_OUT_OF_RANGE);
  const double half = 0.5;
  EXPECT_EQ(gyro_config_set(GYRO_PLANT_CONFIG, &c, "spin_drive", &half, 1), GYRO_OUT_OF_RANGE);
  EXPECT_EQ(gyro_config_choice(GYRO_PLANT_CONFIG, &c, "spin_drive"), nullptr);
}

}  // namespace
}  // namespace gyro
