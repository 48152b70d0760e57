// The answer of a configuration check (gyro/config_check.hpp) as a caller holds it: the list
// keeps refusals only and finds them by field, the first refusal stays the first, and the
// message names the field, the relation and the rule, falling back to plain words where a
// refusal carries no field, no rule or no bound.
#include <gtest/gtest.h>

#include <string>

#include "gyro/config_check.hpp"
#include "support/requirements.hpp"

namespace gyro {
namespace config_check_test {

ConfigCheck refusal(const char* field, Relation relation) {
  return ConfigCheck{Status::kOutOfRange, field, 2.0, 1.0, relation, nullptr, "the rule"};
}

std::string formatted(const ConfigCheck& c) {
  char buf[160];
  const int n = format_refusal(c, "cfg.", buf, sizeof buf);
  EXPECT_GT(n, 0);
  return buf;
}

TEST(ConfigCheckList, AnAcceptedCheckIsNeitherKeptNorCounted) {
  GYRO_VERIFIES("CONF-6");
  ConfigCheckList<2> list;
  list(ConfigCheck{});
  EXPECT_TRUE(list.empty());
  EXPECT_EQ(list.size(), 0u);
  list(refusal("tick_s", Relation::kAbove));
  EXPECT_EQ(list.total(), 1u);
}

TEST(ConfigCheckList, FindNamesOnlyARefusalOfThatField) {
  GYRO_VERIFIES("CONF-6");
  ConfigCheckList<4> list;
  list(refusal(nullptr, Relation::kNone));  // a refusal that names no field
  list(refusal("tick_s", Relation::kAbove));
  ASSERT_NE(list.find("tick_s"), nullptr);
  EXPECT_EQ(list.find("tick_s"), &list[1]);
  EXPECT_EQ(list.find("friction"), nullptr);  // every item looked at, none matches
  EXPECT_EQ(list.find(nullptr), nullptr);
}

TEST(FirstRefusal, AcceptedChecksNeitherSetNorReplaceTheFirst) {
  GYRO_VERIFIES("CONF-6");
  FirstRefusal first;
  first(ConfigCheck{});
  EXPECT_TRUE(first.first.ok());
  first(refusal("tick_s", Relation::kAbove));
  first(ConfigCheck{});
  first(refusal("friction", Relation::kBelow));
  EXPECT_STREQ(first.first.field, "tick_s");
}

TEST(FormatRefusal, NoBufferOrAnEmptyOneIsLeftAlone) {
  GYRO_VERIFIES("CONF-2");
  const ConfigCheck c = refusal("tick_s", Relation::kAbove);
  EXPECT_EQ(format_refusal(c, nullptr, nullptr, 16), 0);
  char buf[4] = {'x', 'x', 'x', 'x'};
  EXPECT_EQ(format_refusal(c, nullptr, buf, 0), 0);
  EXPECT_EQ(buf[0], 'x');
  EXPECT_GT(format_refusal(c, nullptr, buf, sizeof buf), 0);  // truncated, terminated
  EXPECT_EQ(buf[3], '\0');
}

TEST(FormatRefusal, EachRelationHasItsWording) {
  GYRO_VERIFIES("CONF-2");
  EXPECT_EQ(formatted(refusal("f", Relation::kBelow)), "cfg.f = 2 is below its lower bound (1): the rule");
  EXPECT_EQ(formatted(refusal("f", Relation::kAbove)), "cfg.f = 2 is above its upper bound (1): the rule");
  EXPECT_EQ(formatted(refusal("f", Relation::kNotFinite)), "cfg.f is not a finite number: the rule");
  EXPECT_EQ(formatted(refusal("f", Relation::kNone)), "cfg.f: the rule");
  // A relation outside the enumeration (a corrupted value) gets the plain wording too.
  EXPECT_EQ(formatted(refusal("f", static_cast<Relation>(200))), "cfg.f: the rule");
}

TEST(FormatRefusal, NoFieldOrRuleFallsBackToPlainWords) {
  GYRO_VERIFIES("CONF-2");
  ConfigCheck c = refusal(nullptr, Relation::kNone);
  c.rule = nullptr;
  EXPECT_EQ(formatted(c), std::string("cfg.(unnamed): ") + to_string(Status::kOutOfRange));
}

}  // namespace config_check_test
}  // namespace gyro
