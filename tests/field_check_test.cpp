// One field against its own rule (gyro/config_fields.hpp, field_check and all_fields_finite)
// for rows the shipped tables do not have: a positive field whose range starts at 0, a
// non-negative or count field with a lower bound above the rule's, no reason given, a nested
// struct under a rule other than kFinite, and a nested struct that holds an Eigen vector.
#include <gtest/gtest.h>

#include <Eigen/Core>
#include <cmath>
#include <limits>
#include <string>

#include "gyro/config_fields.hpp"
#include "support/requirements.hpp"

namespace gyro {
namespace field_check_test {

// A configuration with a scalar and a vector, for the finiteness of nested structs.
struct ScalarAndVector {
  double gain{1.0};
  Eigen::Vector2d offset{Eigen::Vector2d::Zero()};
};

}  // namespace field_check_test

template <>
struct FieldTable<field_check_test::ScalarAndVector> {
  static constexpr bool kDefined = true;
  template <class Visit, class... C>
  static constexpr void visit(Visit&& v, C&... c) {
    v(Field{"gain", Rule::kFinite}, c.gain...);
    v(Field{"offset", Rule::kFinite}, c.offset...);
  }
};

namespace field_check_test {

Field field(Rule rule, double lower, const char* why = "the reason") {
  return Field{"f", rule, Status::kOutOfRange, Presence::kRequired, nullptr, lower, kNoBound, "", why};
}

TEST(FieldCheck, APositiveFieldFromZeroIsRefusedAgainstZero) {
  GYRO_VERIFIES("CONF-1");
  const ConfigCheck r = field_check(field(Rule::kPositive, 0.0), 0.0);
  EXPECT_EQ(r.relation, Relation::kBelow);
  EXPECT_EQ(r.bound, 0.0);
  EXPECT_STREQ(r.bound_name, "0 (must be > 0)");
  const ConfigCheck above = field_check(field(Rule::kPositive, 2.0), 1.0);  // its range's own bound
  EXPECT_EQ(above.bound, 2.0);
  EXPECT_EQ(above.bound_name, nullptr);
}

TEST(FieldCheck, ANegativeValueIsRefusedAgainstARaisedLowerBound) {
  GYRO_VERIFIES("CONF-1");
  const ConfigCheck r = field_check(field(Rule::kNonNegative, 0.5), -1.0);
  EXPECT_EQ(r.relation, Relation::kBelow);
  EXPECT_EQ(r.bound, 0.5);
  EXPECT_EQ(r.bound_name, nullptr);
  EXPECT_EQ(field_check(field(Rule::kNonNegative, 0.0), -1.0).bound_name, std::string("0"));
}

TEST(FieldCheck, AZeroCountIsRefusedAgainstARaisedLowerBound) {
  GYRO_VERIFIES("CONF-1");
  const ConfigCheck r = field_check(field(Rule::kNonZero, 3.0), 0u);
  EXPECT_EQ(r.relation, Relation::kBelow);
  EXPECT_EQ(r.bound, 3.0);
  EXPECT_EQ(r.bound_name, nullptr);
  EXPECT_STREQ(field_check(field(Rule::kNonZero, 0.0), 0u).bound_name, "1");
}

TEST(FieldCheck, AFieldWithoutAReasonNamesItsOwnRange) {
  GYRO_VERIFIES("CONF-1");
  const ConfigCheck r = field_check(field(Rule::kPositive, 1.0, nullptr), -1.0);
  EXPECT_FALSE(r.ok());
  EXPECT_STREQ(r.rule, "the field's own range");
}

TEST(FieldCheck, ANestedVectorMustBeFiniteToo) {
  GYRO_VERIFIES("CONF-1");
  const double nan = std::numeric_limits<double>::quiet_NaN();
  ScalarAndVector c;
  EXPECT_TRUE(all_fields_finite(c));
  c.offset(1) = nan;
  EXPECT_FALSE(all_fields_finite(c));  // the vector alone
  c.gain = nan;
  EXPECT_FALSE(all_fields_finite(c));
  c.offset(1) = 0.0;
  EXPECT_FALSE(all_fields_finite(c));  // the scalar alone
  const Field nested{"nested", Rule::kFinite};
  EXPECT_EQ(field_check(nested, c).status, Status::kNonFiniteInput);
  EXPECT_EQ(field_check(nested, c).relation, Relation::kNotFinite);
}

TEST(FieldCheck, ANestedStructIsOnlyCheckedFiniteUnderRuleFinite) {
  GYRO_VERIFIES("CONF-1");
  ScalarAndVector c;
  c.gain = std::numeric_limits<double>::infinity();
  EXPECT_FALSE(field_check(Field{"nested", Rule::kFinite}, c).ok());
  // Its own table's rules are the struct's: a positive rule on the whole says nothing of it.
  EXPECT_TRUE(field_check(Field{"nested", Rule::kPositive}, c).ok());
}

}  // namespace field_check_test
}  // namespace gyro
