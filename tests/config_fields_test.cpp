// The configuration field tables (gyro/config_fields.hpp): what check() refuses through them,
// the lockstep cast, and docs/scenarios.md's field tables against them (so they cannot drift).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "config_doc.hpp"
#include "gyro/component_config.hpp"
#include "gyro/report_sample.hpp"
#include "gyro/seeker_example.hpp"
#include "gyro/simulated_gyro.hpp"
#include "support/requirements.hpp"

namespace gyro {
namespace {

// Every field of a table, by name, with its row.
template <class Config>
std::map<std::string, Field> rows_of(const Config& c) {
  std::map<std::string, Field> out;
  visit_fields([&](const Field& f, const auto&) { out.emplace(f.name, f); }, c);
  return out;
}

TEST(ConfigFields, GivenEachTableWHENVisitedTHENEveryNameIsUniqueAndRefusalsAreFailures) {
  GYRO_VERIFIES("CONF-1");
  const auto check_table = [](const auto& config) {
    int rows = 0;
    std::set<std::string> names;
    visit_fields(
        [&](const Field& f, const auto&) {
          ++rows;
          EXPECT_TRUE(names.insert(f.name).second) << f.name;
          EXPECT_NE(f.refusal, Status::kOk) << f.name;
        },
        config);
    EXPECT_EQ(static_cast<std::size_t>(rows), names.size());
    EXPECT_GT(rows, 0);
  };
  const SimulatedGyroConfig<double> stub{};
  check_table(GyroComponentConfig<double>{});
  check_table(stub.gyro);
  check_table(stub.gyro.errors.pitch);
  check_table(stub.gimbal);
  check_table(stub.pickoff);
  check_table(stub.torquer);
  check_table(stub);
}

// Each number's own rule, field by field: a breach is refused naming that field with the
// row's status (and a NaN with kNonFiniteInput).
TEST(ConfigFields, GivenTheSeekerComponentWHENOneNumberBreaksItsRuleTHENCheckNamesIt) {
  GYRO_VERIFIES("CONF-1", "CONF-2");
  const GyroComponentConfig<double> good = SeekerExample<double>::component();
  ASSERT_TRUE(check(good).ok());
  int breached = 0;
  visit_fields(
      [&](const Field& f, const auto& member) {
        using M = std::decay_t<decltype(member)>;
        if constexpr (std::is_same_v<M, double>) {
          if (f.rule == Rule::kNone) return;
          for (const double bad : {std::nan(""), f.rule == Rule::kPositive ? 0.0 : -1.0}) {
            GyroComponentConfig<double> c = good;
            visit_fields(
                [&](const Field& g, auto& m) {
                  if constexpr (std::is_same_v<std::decay_t<decltype(m)>, double>) {
                    if (std::string(g.name) == f.name) m = bad;
                  }
                },
                c);
            const ConfigCheck r = check(c);
            EXPECT_EQ(r.status, std::isnan(bad) ? Status::kNonFiniteInput : f.refusal) << f.name;
            ASSERT_NE(r.field, nullptr) << f.name;
            EXPECT_STREQ(r.field, f.name);
            ++breached;
          }
        } else if constexpr (std::is_same_v<M, std::uint32_t>) {
          if (f.rule != Rule::kNonZero) return;
          GyroComponentConfig<double> c = good;
          visit_fields(
              [&](const Field& g, auto& m) {
                if constexpr (std::is_same_v<std::decay_t<decltype(m)>, std::uint32_t>) {
                  if (std::string(g.name) == f.name) m = 0;
                }
              },
              c);
          const ConfigCheck r = check(c);
          EXPECT_EQ(r.status, f.refusal) << f.name;
          ASSERT_NE(r.field, nullptr) << f.name;
          EXPECT_STREQ(r.field, f.name);
          ++breached;
        }
      },
      good);
  EXPECT_GE(breached, 2 * 19 + 6);  // the 19 numbers and 6 counts with a rule of their own
}

// Every number of the stub's and the model's tables has a finite range, a unit (or none for
// a ratio) and a reason; only counts that may take any 64-bit value are left unbounded.
TEST(ConfigFields, GivenTheStubAndModelTablesWHENListedTHENEveryNumberHasBothBoundsAndAReason) {
  GYRO_VERIFIES("CONF-1");
  const std::set<std::string> any_value = {"seed", "start_tick", "duration_ticks"};
  int numbers = 0;
  const auto expect_bounded = [&](const auto& config) {
    visit_fields(
        [&](const Field& f, const auto& member) {
          using M = std::decay_t<decltype(member)>;
          constexpr bool kNumber = std::is_floating_point_v<M> || std::is_base_of_v<Eigen::EigenBase<M>, M> ||
                                   (std::is_integral_v<M> && !std::is_same_v<M, bool>);
          if constexpr (kNumber) {
            ++numbers;
            ASSERT_NE(f.why, nullptr) << f.name;
            EXPECT_GT(std::string(f.why).size(), 10u) << f.name;
            if (any_value.count(f.name)) {
              EXPECT_EQ(f.rule, Rule::kNone) << f.name;
              EXPECT_NE(std::string(f.why).find("any"), std::string::npos) << f.name;
              return;
            }
            EXPECT_NE(f.rule, Rule::kNone) << f.name;
            EXPECT_TRUE(std::isfinite(f.lower) && std::isfinite(f.upper)) << f.name;
            EXPECT_LT(f.lower, f.upper) << f.name;
            ASSERT_NE(f.unit, nullptr) << f.name;
          }
        },
        config);
  };
  const SimulatedGyroConfig<double> stub{};
  expect_bounded(stub);
  expect_bounded(stub.gyro);
  expect_bounded(stub.gyro.errors.pitch);
  expect_bounded(stub.gimbal);
  expect_bounded(stub.pickoff);
  expect_bounded(stub.torquer);
  expect_bounded(stub.faults[0]);
  EXPECT_EQ(numbers, 5 + 11 + 6 + 21 + 5 + 2 + 4);
}

// The configurations the repository ships keep every new bound.
TEST(ConfigFields, GivenTheShippedConfigurationsWHENCheckedTHENAccepted) {
  GYRO_VERIFIES("CONF-8");
  EXPECT_TRUE(check(SeekerExample<double>::stub()).ok());
  EXPECT_TRUE(check(SeekerExample<float>::stub()).ok());
  EXPECT_TRUE(check(SeekerExample<double>::gimbal()).ok());
  EXPECT_TRUE(check(ReportSample<double>::config()).ok());
  EXPECT_TRUE(check(ReportSample<float>::config()).ok());
  SimulatedGyroConfig<double> report = SeekerExample<double>::stub();
  report.plant = PlantKind::kReport;
  report.gyro = ReportSample<double>::config();
  report.spin_hz = ReportSample<double>::kSpinHz;
  report.spin_down_time_constant_s = 20.0;
  report.gimbal_stop_rad = 0.5;
  EXPECT_TRUE(check(report).ok()) << check(report).field;
}

// A value beyond one of the stub's or the model's bounds: refused, and the message names the
// field, the value and the bound.
TEST(ConfigFields, GivenAValueBeyondAStubOrModelBoundWHENCheckedTHENTheMessageNamesTheField) {
  GYRO_VERIFIES("CONF-1");
  const auto message = [](const ConfigCheck& r) {
    char buf[256];
    (void)format_refusal(r, nullptr, buf, sizeof buf);
    return std::string(buf);
  };
  struct Case {
    const char* field;
    const char* text;  // a part of the message
    ConfigCheck refusal;
  };
  std::vector<Case> cases;
  {
    SimulatedGyroConfig<double> c = SeekerExample<double>::stub();
    c.spin_hz = 2e5;
    c.gimbal.max_spin_hz = 2e5;
    cases.push_back({"max_spin_hz", "above its upper bound (100000)", check(c)});
    c = SeekerExample<double>::stub();
    c.faults[2] = {FaultKind::kSaturatedTorquer, 5, 0, 0, 2e12};
    cases.push_back({"faults[2].magnitude", "above its upper bound (1e+12)", check(c)});
    c = SeekerExample<double>::stub();
    c.plant = PlantKind::kReport;
    c.gyro = ReportSample<double>::config();
    c.spin_hz = ReportSample<double>::kSpinHz;
    c.spin_down_time_constant_s = 2e9;
    cases.push_back({"spin_down_time_constant_s", "above its upper bound (1e+09)", check(c)});
  }
  {
    GimbalPlantConfig<double> g = SeekerExample<double>::gimbal();
    g.coulomb_rate_scale_rad_s = 2.0;
    cases.push_back({"coulomb_rate_scale_rad_s", "above its upper bound (1)", check(g)});
    g = SeekerExample<double>::gimbal();
    g.spin_servo_bandwidth_rad_s = 2e6;
    cases.push_back({"spin_servo_bandwidth_rad_s", "above its upper bound (1e+06)", check(g)});
    g = SeekerExample<double>::gimbal();
    g.mass_unbalance = -2e12;
    cases.push_back({"mass_unbalance", "below its lower bound (-1e+12)", check(g)});
    g = SeekerExample<double>::gimbal();
    g.max_specific_force = 1e8;
    cases.push_back({"max_specific_force", "above its upper bound (1e+07)", check(g)});
    g = SeekerExample<double>::gimbal();
    g.spin_down_time_s = 2e9;
    cases.push_back({"spin_down_time_s", "above its upper bound (1e+09)", check(g)});
  }
  {
    GyroModelConfig<double> m = ReportSample<double>::config();
    m.errors.yaw.torquer_cross_coupling = 1.5;
    cases.push_back({"errors.yaw.torquer_cross_coupling", "above its upper bound (1)", check(m)});
    m = ReportSample<double>::config();
    m.errors.pitch.static_drift_rad_s = -2.0;
    cases.push_back({"errors.pitch.static_drift_rad_s", "below its lower bound (-1)", check(m)});
    m = ReportSample<double>::config();
    m.errors.pitch.coulomb_friction_rad_s = -1e-3;
    cases.push_back({"errors.pitch.coulomb_friction_rad_s", "is below 0 (0)", check(m)});
    m = ReportSample<double>::config();
    m.errors.yaw.in_plane_erection_1_s = 20.0;
    cases.push_back({"errors.yaw.in_plane_erection_1_s", "above its upper bound (10)", check(m)});
  }
  for (const Case& k : cases) {
    EXPECT_EQ(k.refusal.status, Status::kOutOfRange) << k.field;
    ASSERT_NE(k.refusal.field, nullptr) << k.field;
    EXPECT_STREQ(k.refusal.field, k.field);
    const std::string m = message(k.refusal);
    EXPECT_EQ(m.rfind(std::string(k.field) + " = ", 0), 0u) << m;
    EXPECT_NE(m.find(k.text), std::string::npos) << m;
  }
  // float: the same rows.
  GimbalPlantConfig<float> f = SeekerExample<float>::gimbal();
  f.coulomb_rate_scale_rad_s = 2.0f;
  EXPECT_STREQ(check(f).field, "coulomb_rate_scale_rad_s");
}

TEST(ConfigFields, GivenADoubleStubConfigurationWHENCastToFloatTHENEveryFieldIsCarried) {
  GYRO_VERIFIES("RULE-8");
  SimulatedGyroConfig<double> d = SeekerExample<double>::stub();
  d.seed = 77;
  d.gyro.errors.yaw.coulomb_friction_rad_s = 0.125;
  d.pickoff.bias_rad = Vector2<double>(0.25, -0.5);
  d.faults[3] = FaultEvent<double>{FaultKind::kBiasJump, 5, 6, 1, 0.1};
  SimulatedGyroConfig<float> f;
  cast_fields(d, f);
  EXPECT_EQ(f.plant, d.plant);
  EXPECT_EQ(f.seed, 77u);
  EXPECT_EQ(f.tick_s, static_cast<float>(d.tick_s));
  EXPECT_EQ(f.gyro.errors.yaw.coulomb_friction_rad_s, 0.125f);
  EXPECT_EQ(f.gimbal.inner_gimbal_inertia, d.gimbal.inner_gimbal_inertia.cast<float>());
  EXPECT_EQ(f.gimbal.spin_drive, d.gimbal.spin_drive);
  EXPECT_EQ(f.pickoff.bias_rad, Vector2<float>(0.25f, -0.5f));
  EXPECT_EQ(f.faults[3].kind, FaultKind::kBiasJump);
  EXPECT_EQ(f.faults[3].duration_ticks, 6u);
  EXPECT_EQ(f.faults[3].magnitude, 0.1f);
  // Back to double: every field that is exact in float comes back as it was.
  SimulatedGyroConfig<double> back;
  cast_fields(f, back);
  int differ = 0;
  visit_fields(
      [&](const Field&, const auto& a, const auto& b) {
        using M = std::decay_t<decltype(a)>;
        if constexpr (std::is_floating_point_v<M>) {
          if (static_cast<double>(static_cast<float>(a)) != b) ++differ;
        }
      },
      d, back);
  EXPECT_EQ(differ, 0);
}

// docs/scenarios.md: the rows of the table under `heading` (up to the next heading), as
// (keys in backticks of the first cell, the third cell).
struct DocRow {
  std::vector<std::string> keys;
  std::string third;
  std::string text;
};
std::vector<DocRow> doc_table(const std::string& heading) {
  std::ifstream in(std::string(GYRO_SOURCE_DIR) + "/docs/scenarios.md");
  std::string line;
  bool inside = false;
  std::vector<DocRow> rows;
  while (std::getline(in, line)) {
    if (line.rfind("#", 0) == 0) {
      if (inside) break;
      inside = line == heading;
      continue;
    }
    if (!inside || line.rfind("| `", 0) != 0) continue;
    for (std::size_t p = line.find("\\|"); p != std::string::npos; p = line.find("\\|", p)) line.replace(p, 2, "/");
    std::vector<std::string> cells;
    std::stringstream ss(line.substr(1));
    std::string cell;
    while (std::getline(ss, cell, '|')) cells.push_back(cell);
    DocRow row;
    row.text = line;
    row.third = cells.size() > 2 ? cells[2] : "";
    for (std::size_t p = cells[0].find('`'); p != std::string::npos; p = cells[0].find('`', p + 1)) {
      const std::size_t q = cells[0].find('`', p + 1);
      row.keys.push_back(cells[0].substr(p + 1, q - p - 1));
      p = q;
    }
    rows.push_back(row);
  }
  EXPECT_FALSE(rows.empty()) << heading;
  return rows;
}

bool says_required(const DocRow& r) { return r.third.find("required") != std::string::npos; }

// Every documented key is a table field given in files, and every such field is documented
// once, marked required exactly when the table requires it.
template <class Config>
void expect_documented(const std::string& heading, const Config& c) {
  const std::string prefix;
  std::map<std::string, const DocRow*> documented;
  const std::vector<DocRow> rows = doc_table(heading);
  for (const DocRow& r : rows) {
    for (const std::string& k : r.keys) EXPECT_TRUE(documented.emplace(k, &r).second) << k << " twice";
  }
  std::set<std::string> fields;
  visit_fields(
      [&](const Field& f, const auto&) {
        if (f.presence == Presence::kImplied) return;
        const std::string key = prefix + (f.section ? std::string(f.section) + "." : "") + f.name;
        fields.insert(key);
        const auto it = documented.find(key);
        ASSERT_NE(it, documented.end()) << key << " is not in docs/scenarios.md under " << heading;
        EXPECT_EQ(says_required(*it->second), f.presence == Presence::kRequired) << it->second->text;
      },
      c);
  for (const auto& [k, row] : documented) {
    (void)row;
    if (!fields.count(k) && k.rfind(prefix, 0) == 0) ADD_FAILURE() << k << " is documented but no field";
  }
}

// The docs' generated tables hold what gyro_config_doc would write from the field tables.
TEST(ConfigFields, GivenTheGeneratedDocTablesWHENRegeneratedTHENUnchanged) {
  GYRO_VERIFIES("CONF-8");
  for (const doc::Generated& g : doc::generated_tables()) {
    const std::string page = doc::read_file(std::string(GYRO_SOURCE_DIR) + "/docs/" + g.file);
    std::string regenerated = page;
    ASSERT_TRUE(doc::replace_between(regenerated, g.name, g.text)) << g.file << ": " << g.name;
    EXPECT_EQ(page, regenerated) << "docs/" << g.file << " (" << g.name << ") differs from the field tables: run "
                                 << "gyro_config_doc docs";
  }
}

TEST(ConfigFields, GivenTheScenarioDocsWHENComparedWithTheTablesTHENTheyAgree) {
  GYRO_VERIFIES("CONF-8");
  const GyroComponentConfig<double> component{};
  const GimbalPlantConfig<double> gimbal{};
  expect_documented("### `component` (the flight software)", component);
  expect_documented("#### `gyro.gimbal` (plant `gimbal`)", gimbal);
  expect_documented("#### `gyro.errors.pitch` and `gyro.errors.yaw` (plant `report`)", AxisErrorSources<double>{});

  // gyro: the model's and the stub's fields, the pickoff and torquer ones, the error sources' objects.
  const std::vector<DocRow> rows = doc_table("### `gyro` (the simulated hardware)");
  std::set<std::string> documented;
  for (const DocRow& r : rows) documented.insert(r.keys.begin(), r.keys.end());
  std::set<std::string> fields = {"plant", "faults"};  // schema keys, not fields
  const auto expect_row = [&](const Field& f, const std::string& key) {
    fields.insert(key);
    EXPECT_TRUE(documented.count(key)) << key << " is not in docs/scenarios.md";
    for (const DocRow& r : rows) {
      if (std::find(r.keys.begin(), r.keys.end(), key) != r.keys.end()) {
        EXPECT_EQ(says_required(r), f.presence == Presence::kRequired) << r.text;
      }
    }
  };
  const auto visit_gyro = [&](const Field& f, const auto& member) {
    using M = std::decay_t<decltype(member)>;
    if (f.presence == Presence::kImplied) return;
    if constexpr (std::is_same_v<M, GyroErrorSources<double>>) {
      // The objects here, their keys in their own generated table (below).
      visit_fields([&](const Field& axis, const auto&) { expect_row(axis, std::string(f.name) + "." + axis.name); },
                   member);
    } else if constexpr (kHasFieldTable<M>) {
      visit_fields([&](const Field& g, const auto&) { expect_row(g, g.name); }, member);
    } else {
      expect_row(f, (f.section ? std::string(f.section) + "." : "") + f.name);
    }
  };
  const SimulatedGyroConfig<double> stub{};
  visit_fields(visit_gyro, stub);
  visit_fields(visit_gyro, stub.gyro);
  for (const std::string& k : documented) EXPECT_TRUE(fields.count(k)) << k << " is documented but no field";
}

// Every name of an enumeration gives its own enumerator back; an unknown name or a value
// outside the enumeration gives none (and leaves the target as it was).
template <class E>
void expect_names_round_trip(E unnamed_default) {
  constexpr auto names = enum_names(E{});
  std::set<std::string> seen;
  for (std::size_t i = 0; i < names.size(); ++i) {
    E e = unnamed_default;
    ASSERT_TRUE(enum_from_name(names[i], e)) << names[i];
    EXPECT_EQ(static_cast<std::size_t>(e), i) << names[i];
    EXPECT_STREQ(enum_name(e), names[i]);
    EXPECT_TRUE(seen.insert(names[i]).second) << names[i] << " names two enumerators";
  }
  E e = unnamed_default;
  EXPECT_FALSE(enum_from_name(std::string(names[0]) + "x", e));
  EXPECT_FALSE(enum_from_name("", e));
  EXPECT_EQ(e, unnamed_default);
  EXPECT_EQ(enum_name(static_cast<E>(names.size())), nullptr);
}

TEST(ConfigFields, GivenEachEnumerationWHENANameIsLookedUpTHENItsOwnEnumeratorComesBack) {
  GYRO_VERIFIES("TLM-5");
  expect_names_round_trip(Status::kInputIgnored);
  expect_names_round_trip(TorquerAxes::kGimbal);
  expect_names_round_trip(ModeRequest::kUncage);
  expect_names_round_trip(SpinDrive::kFree);
  expect_names_round_trip(GyroMode::kFault);
  expect_names_round_trip(PortStatus::kHardwareFault);
  expect_names_round_trip(PlantKind::kGimbal);
  expect_names_round_trip(FaultKind::kSpinMotorFailure);
  static_assert(enum_name(Status::kWrongMode)[0] == 'w', "usable in constant expressions");
}

TEST(EnumNames, AValueOutsideTheEnumerationIsNamedAsUnknown) {
  GYRO_VERIFIES("TLM-5");
  // A corrupted value (e.g. from telemetry) is named, never read out of bounds.
  EXPECT_STREQ(enum_name_or(static_cast<GyroMode>(99), "unknown"), "unknown");
  EXPECT_STREQ(enum_name_or(GyroMode::kUncaging, "unknown"), "uncaging");
  EXPECT_STREQ(enum_name_or(static_cast<PortStatus>(77), "?"), "?");
  EXPECT_STREQ(fault_kind_name(FaultKind::kNone), "");
  EXPECT_STREQ(fault_kind_name(static_cast<FaultKind>(kFaultKindCount)), "");
  EXPECT_STREQ(fault_kind_name(FaultKind::kBiasJump), "bias_jump");
}

}  // namespace
}  // namespace gyro
