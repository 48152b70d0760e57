// The stop-protection table: the flight component against the SIL stub's gimbal plant, two
// gyros, the body turning the gimbal toward its stop in each mode (tools/stop_envelope.hpp
// runs each case). Writes docs/stop-protection.md and its detailed rows as CSV.
//
// Usage: gyro_stop_envelope [--scenarios DIR] [--markdown out.md] [--csv out.csv] [--jobs N]
//        gyro_stop_envelope [--scenarios DIR] --case GYRO MODE TURN DIRECTION ROLL CONE
//          one row, e.g. --case seeker free_zero 0.2 yaw 0 0 (names as in the CSV)
#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <exception>
#include <map>
#include <string>
#include <thread>
#include <vector>

#include "text_file.hpp"
#include "stop_envelope.hpp"

namespace {

using namespace gyro::stop_envelope;

constexpr double kSeekerTurns[] = {0, 0.2, 0.35, 0.45, 0.5, 0.7, 1, 2};
// The report's gyro is held to its slew-rate limits (0.1745 rad/s): two turns inside them too.
constexpr double kReportTurns[] = {0, 0.1, 0.15, 0.2, 0.35, 0.45, 0.5, 0.7, 1, 2};
constexpr double kRolls[] = {0, 5, 10};
constexpr double kCones[] = {0, 10, 20};
constexpr int kMaxListed = 40;  // within-authority contacts listed one by one (all are in the CSV)

struct Row {
  int gyro{};
  Case k{};
  Authority a{};
  double demand_turn_plus_u{};  // the demand were the outward command added to the turn
  Result r{};
  [[nodiscard]] bool within() const { return a.demand <= 1.0; }
};

std::string fmt(const char* f, double v) {
  char b[256];
  std::snprintf(b, sizeof b, f, v);
  return b;
}
std::string ms(double s) { return s < 0 ? std::string("-") : fmt("%.0f", s * 1e3); }

// The largest turn of one direction, without roll, whose hold is within authority.
double authority_rad_s(const Gyro& g, Direction d) {
  double lo = 0, hi = 10;
  for (int i = 0; i < 60; ++i) {
    const double mid = 0.5 * (lo + hi);
    Case k;
    k.turn_rad_s = mid;
    k.direction = d;
    (authority(g, k).demand <= 1.0 ? lo : hi) = mid;
  }
  return lo;
}

const char* kIntro = R"(# Stop protection: the gimbal against its stop, per mode

**Generated** by `scripts/stop-envelope.sh` (`tools/stop_envelope.cpp`, the runs in
`tools/stop_envelope.hpp`; the ctest `stop_envelope_test` flies a small grid of them). Do not
edit by hand: run the script. The detailed rows are in `docs/stop-protection.csv`.

The flight component (`GyroComponent<double>`) flies against the SIL stub (`SimulatedGyro`)
with the nonlinear gimbal plant (`docs/gimbal-plant.md`), whose stop is a rigid contact on the
total cone angle between spin axis and body x. Everything measured about the stop is the
plant's truth: contact is `at_gimbal_stop()` after a tick (the plant resolves it at every
sub-step), the closest approach is the stop angle less the largest cone the plant reached at a
tick's end. The component's side is its telemetry: the first tick of each flag, and whether it
went to safe mode (a fault latched).

## The gyros

- **seeker**: `scenarios/seeker_slew.json`'s gyro and component as they are: the gimbal plant
  (H = 0.0754 N m s, friction 4e-4 N m s per bearing, stop 0.4 rad), its pickoff (61 urad
  LSB, bias, 0.2 ms lag, 50 urad noise) and torquer imperfections (scale factors 1.02 / 0.98,
  saturation 0.05 N m), the component's torque limit 0.04 N m, cone limit 0.35 rad, margin
  0.03 rad (protection cone c_p = 0.32 rad), 1 kHz tick.
- **report**: `scenarios/report_sample.json`'s rotor, component (torque limit 500 lbf ft,
  slew-rate limits 10 deg/s, cone limit 0.436 rad, margin 0.02 rad: c_p = 0.416 rad), tick
  (2,828 Hz) and stop (0.5 rad), put on the gimbal plant with these choices (the report has no
  gimbal): rotor transverse inertia A = 1.6 slug ft^2 (J0 = 3 <= 2A), thin gimbal rings making
  the effective inertias at zero angles the report's J1 = 2.25 (inner ring (0.45, 0.65, 0.2))
  and J2 = 2.0 (outer ring (0.4, 0.2, 0.2)), the report's friction 5 on each bearing, no dry
  friction, no mass unbalance, the 100 Hz spin held by a motor (limit 1e4, bandwidth 5 rad/s),
  stop restitution 0.2 (as the seeker's), ideal pickoffs and torquers (the report models none).

## A case

- **Body**: a turn b across body x in a direction: pitch (0, b, 0), yaw (0, 0, b), diagonal
  (0, b, b)/sqrt2, or rotating (0, b cos t, b sin t) (1 rad/s round x), plus a roll p about x.
  The rates ramp up over the first 50 ms of flight (smoothstep), then hold; 3 s of flight.
- **Starting cone c**: the stub is powered up (gimbals at zero, body at rest) and run with the
  torquers off, the component not yet active, while the body turns by c about the case's
  turn axis (a half-sine rate, peak 1.5 rad/s): the free spin axis is left at the cone c, on
  the side the case's turn drives it toward. Then the component is activated (caged) at that
  offset and, in every mode but caged, asked to uncage at its first tick ("uncage there").
  The start cone in the CSV is the plant's at activation.
- **Modes**: free with a zero slew command; free with the spin axis commanded toward body x
  (inward) or away from it (outward) at u (seeker 0.15 rad/s, report 0.05 rad/s), along its
  measured clock angle (near the centre, outward is the turn's way, inward is zero);
  uncaging for the whole flight (`uncage_settle_ticks` longer than the flight); caged (no
  uncage request: the cage loop pulls the gimbal in from c while the body turns). In the free
  modes the component is free after the configuration's `uncage_settle_ticks` (seeker 50 ms,
  report one tick).
)";

const char* kCriterion = R"(
## Within the torquer's authority: the criterion

Near the stop the protection must hold the gimbal where the body's turn pushes it: the spin
axis then moves with the body's outward rate, w = (wb . n) n on the gimbal axes (n the
outward unit at the spin axis's clock angle, wb the body's rate resolved on the gimbal axes),
its tangential part left at the command (the commands here are radial, so zero); an outward
command is withheld there and adds nothing to the hold. The component's torque law
(`gyro/gimbal_geometry.hpp`)

    T1 = h w_z + f (w - wb)_y,    T2 = -h w_y cos(theta) + f (w - wb)_z / cos(theta)

gives the torque of that hold, with h = H + J0 |p| (the inner gimbal's roll adds to the
rotor's momentum) and f the bearings' friction (which the hold must overcome on the part of
the body's rate it does not follow, roll included). A case is **within authority** when, at
the protection cone c_p and at every clock angle the case visits (the turn's own, +-5 deg,
for a fixed turn without roll; all of them for a rolling body or a rotating turn),

    |T_i| <= min(max_torque * scale_factor_i, the torquer electronics' saturation)   (i = 1, 2)
    |w_i| <= the axis's slew-rate limit (max_pitch_rate_rad_s, max_yaw_rate_rad_s)

whichever binds first: `demand` in the CSV is the worst ratio of needed to available (within
authority: demand <= 1). For a turn about one gimbal axis without roll this is the familiar
b <= min(delivered torque / H, slew-rate limit), less a friction term, with two corrections
the plant has and a bare max_torque / H misses: a torquer's scale factor (the seeker's outer
axis delivers 0.98 of the 0.04 N m the component may command, its inner axis 1.02), and the
outer axis's cos(theta) (a steady outer torque precesses the pitch at -T2 / (H cos theta), so
holding a pitch turn at c_p costs cos(c_p) less torque). The issue's 0.53 rad/s is
0.04 / 0.0754 without either. The report's gyro is held by its slew-rate limits (0.1745
rad/s) long before its torquer (500 / 1885 = 0.265 rad/s). A diagonal turn splits the hold
over both axes, so more of it is within authority (the table below); a rolling body or a
rotating turn brings the whole turn onto each axis in turn. The commanded u is itself within
authority (0.15 < 0.54, 0.05 < 0.17 rad/s), and an outward command adds nothing at the hold
(the protection withholds it), so the criterion does not add u to the turn: the outward rows
with a turn within authority but turn + u beyond it are the ones that test that.
)";

// --case: one row, every figure.
int run_one(const std::vector<Gyro>& gyros, const std::vector<std::string>& a) {
  Row r;
  r.gyro = a[0] == "report" ? 1 : 0;
  bool known = a[0] == "report" || a[0] == "seeker";
  bool mode_known = false, dir_known = false;
  for (Mode m : kModes) {
    if (a[1] == mode_key(m)) {
      r.k.mode = m;
      mode_known = true;
    }
  }
  for (Direction d : kDirections) {
    if (a[3] == direction_key(d)) {
      r.k.direction = d;
      dir_known = true;
    }
  }
  if (!known || !mode_known || !dir_known) {
    std::fprintf(stderr, "--case GYRO MODE TURN DIRECTION ROLL CONE: unknown gyro, mode or direction\n");
    return 2;
  }
  r.k.turn_rad_s = std::atof(a[2].c_str());
  r.k.roll_rad_s = std::atof(a[4].c_str());
  r.k.cone_deg = std::atof(a[5].c_str());
  const Gyro& g = gyros[static_cast<std::size_t>(r.gyro)];
  r.a = authority(g, r.k);
  const auto t0 = std::chrono::steady_clock::now();
  r.r = run_case(g, r.k);
  const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  if (!r.r.ok) {
    std::fprintf(stderr, "%s\n", r.r.error.c_str());
    return 1;
  }
  std::printf("demand %.3f (torque %.3f, rate %.3f): %s authority\n", r.a.demand, r.a.torque_share, r.a.rate_share,
              r.within() ? "within" : "beyond");
  std::printf("start cone %.4f rad, largest %.4f, stop %.4f, c_p %.4f, closest %.4f rad\n", r.r.start_cone_rad,
              r.r.max_cone_rad, g.stop_rad(), g.protect_cone_rad(), r.r.closest_rad);
  std::printf("contact ticks %llu, first at %.4f s; cone past c_p at %.4f s\n",
              static_cast<unsigned long long>(r.r.contact_ticks), r.r.first_contact_s, r.r.first_beyond_cp_s);
  std::printf("first: stop_protect %.4f, beyond_authority %.4f, gimbal_limit %.4f, safe mode %.4f s; final mode %s\n",
              r.r.first_protect_s, r.r.first_beyond_s, r.r.first_limit_s, r.r.first_fault_s,
              gyro::enum_name(r.r.final_mode));
  std::printf("stop_protect switchings %llu, beyond_authority %llu ticks, furthest out %.4f rad, torquer saturated "
              "%llu ticks, worst residual %.2e rad%s\n",
              static_cast<unsigned long long>(r.r.protect_toggles), static_cast<unsigned long long>(r.r.beyond_ticks),
              r.r.furthest_out_rad, static_cast<unsigned long long>(r.r.saturated_ticks),
              r.r.worst_residual_rad, r.r.residual_fault ? ", residual fault" : "");
  std::printf("flags seen: %s\nflags up to contact: %s\n(%.2f s of run time)\n", flag_names(r.r.flags_seen).c_str(),
              flag_names(r.r.flags_at_contact).c_str(), s);
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  std::string scenarios = "scenarios", markdown, csv;
  unsigned jobs = 1;
  std::vector<std::string> one;  // --case
  for (int i = 1; i < argc; ++i) {
    auto value = [&]() -> std::string {
      if (i + 1 >= argc) {
        std::fprintf(stderr, "%s needs a value\n", argv[i]);
        std::exit(2);
      }
      return argv[++i];
    };
    if (std::strcmp(argv[i], "--scenarios") == 0) {
      scenarios = value();
    } else if (std::strcmp(argv[i], "--markdown") == 0) {
      markdown = value();
    } else if (std::strcmp(argv[i], "--csv") == 0) {
      csv = value();
    } else if (std::strcmp(argv[i], "--case") == 0 && i + 6 < argc) {
      one.assign(argv + i + 1, argv + i + 7);
      i += 6;
    } else if (std::strcmp(argv[i], "--jobs") == 0) {
      jobs = static_cast<unsigned>(std::max(1, std::atoi(value().c_str())));
    } else {
      std::fprintf(stderr, "usage: gyro_stop_envelope [--scenarios DIR] [--markdown out.md] [--csv out.csv] [--jobs N]\n");
      return 2;
    }
  }

  std::vector<Gyro> gyros;
  try {
    gyros.push_back(seeker_gyro(scenarios + "/seeker_slew.json"));
    gyros.push_back(report_gyro(scenarios + "/report_sample.json"));
  } catch (const std::exception& e) {
    std::fprintf(stderr, "%s\n", e.what());
    return 1;
  }

  if (!one.empty()) return run_one(gyros, one);

  std::vector<Row> rows;
  for (int gi = 0; gi < 2; ++gi) {
    const bool seeker = gi == 0;
    const double* turns = seeker ? kSeekerTurns : kReportTurns;
    const std::size_t n_turns = seeker ? std::size(kSeekerTurns) : std::size(kReportTurns);
    for (std::size_t ti = 0; ti < n_turns; ++ti) {
      for (Direction d : kDirections) {
        if (turns[ti] == 0 && d != Direction::kPitch) continue;  // no turn: one direction
        for (double p : kRolls) {
          for (double c : kCones) {
            for (Mode m : kModes) {
              Row r;
              r.gyro = gi;
              r.k = Case{turns[ti], d, p, c, m};
              r.a = authority(gyros[static_cast<std::size_t>(gi)], r.k);
              Case plus = r.k;
              plus.turn_rad_s += gyros[static_cast<std::size_t>(gi)].command_rad_s;
              r.demand_turn_plus_u = authority(gyros[static_cast<std::size_t>(gi)], plus).demand;
              rows.push_back(r);
            }
          }
        }
      }
    }
  }

  const auto t0 = std::chrono::steady_clock::now();
  std::atomic<std::size_t> next{0};
  auto work = [&]() {
    for (std::size_t i = next++; i < rows.size(); i = next++) {
      rows[i].r = run_case(gyros[static_cast<std::size_t>(rows[i].gyro)], rows[i].k);
    }
  };
  std::vector<std::thread> pool;
  for (unsigned j = 1; j < jobs; ++j) pool.emplace_back(work);
  work();
  for (std::thread& t : pool) t.join();
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  int not_reached = 0;
  for (const Row& r : rows) not_reached += r.r.reached_mode ? 0 : 1;
  for (const Row& r : rows) {
    if (!r.r.ok) {
      std::fprintf(stderr, "%s %s turn %g %s roll %g cone %g: %s\n", gyros[static_cast<std::size_t>(r.gyro)].name.c_str(),
                   mode_key(r.k.mode), r.k.turn_rad_s, direction_key(r.k.direction), r.k.roll_rad_s, r.k.cone_deg,
                   r.r.error.c_str());
      return 1;
    }
  }

  const std::uint32_t protect_bit = flag_bit("gimbal_stop_protect");
  const std::uint32_t beyond_bit = flag_bit("stop_beyond_authority");
  const std::uint32_t limit_bit = flag_bit("gimbal_limit");

  std::string md = kIntro;
  md += kCriterion;
  md += "\nAuthority so derived (the largest turn without roll that is within it):\n\n";
  md += "| gyro | c_p (rad) | stop (rad) | pitch turn | yaw turn | diagonal turn |\n|---|---|---|---|---|---|\n";
  for (const Gyro& g : gyros) {
    md += "| " + g.name + fmt(" | %.3f", g.protect_cone_rad()) + fmt(" | %.3f", g.stop_rad()) +
          fmt(" | %.3f rad/s", authority_rad_s(g, Direction::kPitch)) +
          fmt(" | %.3f rad/s", authority_rad_s(g, Direction::kYaw)) +
          fmt(" | %.3f rad/s |\n", authority_rad_s(g, Direction::kDiagonal));
  }
  if (beyond_bit == 0u) {
    md += "\nThis build's component has no `stop_beyond_authority` flag: its column reads 0 throughout.\n";
  }

  // The aggregate table.
  md += fmt("\n## The table\n\n%.0f cases", static_cast<double>(rows.size()));
  md += ": turns " + std::string("0, 0.2, 0.35, 0.45, 0.5, 0.7, 1, 2 rad/s (the report's gyro also 0.1 and 0.15)") +
        ", four directions (one at no turn), roll 0, 5, 10 rad/s, starting cone 0, 10, 20 deg, five modes. "
        "Per gyro, mode and authority: how many cases touched the stop, the closest any case came to it (0: "
        "contact), and in how many cases the component raised `gimbal_stop_protect`, "
        "`stop_beyond_authority`, `gimbal_limit`, or latched a fault (safe mode).\n\n";
  md += "| gyro | mode | authority | cases | contacts | closest approach (mrad) | stop_protect | "
        "beyond_authority | gimbal_limit | fault latched |\n|---|---|---|---|---|---|---|---|---|---|\n";
  int contacts_within = 0;
  for (int gi = 0; gi < 2; ++gi) {
    for (Mode m : kModes) {
      for (int inside = 1; inside >= 0; --inside) {
        int n = 0, contacts = 0, prot = 0, beyond = 0, limit = 0, faults = 0;
        double closest = 1e300;
        for (const Row& r : rows) {
          if (r.gyro != gi || r.k.mode != m || r.within() != (inside == 1)) continue;
          ++n;
          contacts += r.r.contact_ticks > 0 ? 1 : 0;
          closest = std::min(closest, r.r.closest_rad);
          prot += (r.r.flags_seen & protect_bit) != 0u ? 1 : 0;
          beyond += beyond_bit != 0u && (r.r.flags_seen & beyond_bit) != 0u ? 1 : 0;
          limit += (r.r.flags_seen & limit_bit) != 0u ? 1 : 0;
          faults += r.r.fault ? 1 : 0;
        }
        if (n == 0) continue;
        if (inside == 1) contacts_within += contacts;
        const std::string c = inside == 1 && contacts > 0 ? fmt("**%.0f**", contacts) : fmt("%.0f", contacts);
        md += "| " + gyros[static_cast<std::size_t>(gi)].name + " | " + mode_name(m) + " | " +
              (inside == 1 ? "within" : "beyond") + fmt(" | %.0f", n) + " | " + c + fmt(" | %.1f", closest * 1e3) +
              fmt(" | %.0f", prot) + fmt(" | %.0f", beyond) + fmt(" | %.0f", limit) + fmt(" | %.0f |\n", faults);
      }
    }
  }

  // The outward command at the edge of authority.
  {
    int n = 0, contacts = 0;
    for (const Row& r : rows) {
      if (r.k.mode != Mode::kFreeOutward || !r.within() || r.demand_turn_plus_u <= 1.0 || r.k.turn_rad_s == 0) continue;
      ++n;
      contacts += r.r.contact_ticks > 0 ? 1 : 0;
    }
    md += fmt("\nOf the outward-command cases within authority, %.0f would be beyond it were the command added to "
              "the turn (turn + u); ", n) + fmt("%.0f of them touched the stop.\n", contacts);
  }

  // How the protection flies, within authority.
  md += "\n## How it flies within authority\n\n";
  md += "Per gyro and mode, the cases within authority: the furthest the plant's cone went past c_p, or past "
        "its starting cone where it started beyond c_p (mrad; negative: it stayed inside), how many raised "
        "`stop_beyond_authority` and its ticks (max per case), how many raised a residual fault (the pickoffs against the component's "
        "prediction), the component's worst residual before any safe mode (mrad), the switchings of "
        "`gimbal_stop_protect` (chatter; median / max per case) and the ticks of `torquer_saturated` (max per case).\n\n";
  md += "| gyro | mode | cases | furthest past c_p (mrad) | beyond_authority raised | its ticks | residual fault | worst residual (mrad) | stop_protect "
        "switchings | saturated ticks |\n|---|---|---|---|---|---|---|---|---|---|\n";
  for (int gi = 0; gi < 2; ++gi) {
    for (Mode m : kModes) {
      std::vector<double> toggles;
      int n = 0, residual_faults = 0, beyond = 0;
      double past = -1e300, worst_res = 0, saturated = 0, beyond_ticks = 0;
      for (const Row& r : rows) {
        if (r.gyro != gi || r.k.mode != m || !r.within()) continue;
        ++n;
        past = std::max(past, r.r.furthest_out_rad);
        beyond += r.r.beyond_ticks > 0 ? 1 : 0;
        beyond_ticks = std::max(beyond_ticks, static_cast<double>(r.r.beyond_ticks));
        residual_faults += r.r.residual_fault ? 1 : 0;
        worst_res = std::max(worst_res, r.r.worst_residual_rad);
        toggles.push_back(static_cast<double>(r.r.protect_toggles));
        saturated = std::max(saturated, static_cast<double>(r.r.saturated_ticks));
      }
      if (n == 0) continue;
      std::sort(toggles.begin(), toggles.end());
      md += "| " + gyros[static_cast<std::size_t>(gi)].name + " | " + mode_name(m) + fmt(" | %.0f", n) +
            fmt(" | %.1f", past * 1e3) + fmt(" | %.0f", beyond) + fmt(" | %.0f", beyond_ticks) +
            fmt(" | %.0f", residual_faults) + fmt(" | %.2f", worst_res * 1e3) +
            fmt(" | %.0f", toggles[toggles.size() / 2]) + fmt(" / %.0f", toggles.back()) + fmt(" | %.0f |\n", saturated);
    }
  }

  // Beyond authority: warned before contact?
  md += "\n## Beyond authority: warned before contact?\n\n";
  md += "For the cases that touched the stop: how many had `stop_beyond_authority` (and, for comparison, "
        "`gimbal_limit`) raised before the first contact, and how long before (ms; min / median / max).\n\n";
  md += "| gyro | authority | contacts | beyond_authority before contact | its lead (ms) | gimbal_limit before "
        "contact | its lead (ms) | fault latched |\n|---|---|---|---|---|---|---|---|\n";
  for (int gi = 0; gi < 2; ++gi) {
    for (int inside = 1; inside >= 0; --inside) {
      std::vector<double> lead_b, lead_l;
      int contacts = 0, faults = 0;
      for (const Row& r : rows) {
        if (r.gyro != gi || r.within() != (inside == 1) || r.r.contact_ticks == 0) continue;
        ++contacts;
        faults += r.r.fault ? 1 : 0;
        if (r.r.first_beyond_s >= 0 && r.r.first_beyond_s < r.r.first_contact_s) {
          lead_b.push_back(r.r.first_contact_s - r.r.first_beyond_s);
        }
        if (r.r.first_limit_s >= 0 && r.r.first_limit_s < r.r.first_contact_s) {
          lead_l.push_back(r.r.first_contact_s - r.r.first_limit_s);
        }
      }
      if (contacts == 0) continue;
      auto spread = [](std::vector<double> v) {
        if (v.empty()) return std::string("-");
        std::sort(v.begin(), v.end());
        return ms(v.front()) + " / " + ms(v[v.size() / 2]) + " / " + ms(v.back());
      };
      md += "| " + gyros[static_cast<std::size_t>(gi)].name + " | " + (inside == 1 ? "within" : "beyond") +
            fmt(" | %.0f", contacts) + fmt(" | %.0f", static_cast<double>(lead_b.size())) + " | " + spread(lead_b) +
            fmt(" | %.0f", static_cast<double>(lead_l.size())) + " | " + spread(lead_l) + fmt(" | %.0f |\n", faults);
    }
  }

  // The within-authority contacts, one by one.
  md += "\n## Contacts within authority\n\n";
  if (contacts_within == 0) {
    md += "None.\n";
  } else {
    md += fmt("%.0f cases (times from activation, s; cone in rad):\n\n", contacts_within);
    md += "| gyro | mode | turn | direction | roll | start cone | demand | contact at | contact ticks | cone past c_p at | "
          "stop_protect at | beyond_authority at | gimbal_limit at | safe mode at | flags before contact |\n"
          "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n";
    int listed = 0;
    for (const Row& r : rows) {
      if (!r.within() || r.r.contact_ticks == 0) continue;
      if (++listed > kMaxListed) continue;
      auto at = [](double s) { return s < 0 ? std::string("-") : fmt("%.3f", s); };
      md += "| " + gyros[static_cast<std::size_t>(r.gyro)].name + " | " + mode_name(r.k.mode) +
            fmt(" | %g", r.k.turn_rad_s) + " | " + direction_key(r.k.direction) + fmt(" | %g", r.k.roll_rad_s) +
            fmt(" | %.3f", r.r.start_cone_rad) + fmt(" | %.2f", r.a.demand) + " | " + at(r.r.first_contact_s) +
            fmt(" | %.0f", static_cast<double>(r.r.contact_ticks)) + " | " + at(r.r.first_beyond_cp_s) + " | " +
            at(r.r.first_protect_s) + " | " + at(r.r.first_beyond_s) + " | " + at(r.r.first_limit_s) + " | " +
            at(r.r.first_fault_s) + " | " + flag_names(r.r.flags_at_contact) + " |\n";
    }
    if (listed > kMaxListed) {
      md += fmt("\n... and %.0f more: `docs/stop-protection.csv`, rows with within_authority 1 and contact 1.\n",
                listed - kMaxListed);
    }
  }

  if (not_reached > 0) {
    md += fmt("\n**%.0f cases never flew their mode** (the `reached_mode` column of the CSV).\n", not_reached);
  }
  md += fmt("\n%.0f cases, ", static_cast<double>(rows.size())) + fmt("%.0f s of flight each", kFlightSeconds) +
        fmt(", measured in %.0f s of run time.\n", seconds);

  std::fputs(md.c_str(), stdout);
  if (!markdown.empty() && !gyro::tools::write_text_file(markdown, md)) return 1;
  if (!csv.empty()) {
    std::FILE* f = gyro::tools::open_for_writing(csv);
    if (f == nullptr) return 1;
    std::fputs("gyro,mode,turn_rad_s,direction,roll_rad_s,cone_deg,start_cone_rad,demand,within_authority,contact,"
               "contact_ticks,first_contact_s,max_cone_rad,closest_rad,first_cone_past_cp_s,first_stop_protect_s,"
               "first_beyond_authority_s,first_gimbal_limit_s,first_fault_s,final_mode,reached_mode,demand_turn_plus_u,"
               "protect_toggles,saturated_ticks,worst_residual_rad,residual_fault,beyond_authority_ticks,furthest_out_rad,"
               "flags_seen\n",
               f);
    for (const Row& r : rows) {
      std::fprintf(f, "%s,%s,%g,%s,%g,%g,%.5f,%.3f,%d,%d,%llu,%.4f,%.5f,%.5f,%.4f,%.4f,%.4f,%.4f,%.4f,%s,%d,%.3f,%llu,%llu,%.6f,%d,%llu,%.5f,%s\n",
                   gyros[static_cast<std::size_t>(r.gyro)].name.c_str(), mode_key(r.k.mode), r.k.turn_rad_s,
                   direction_key(r.k.direction), r.k.roll_rad_s, r.k.cone_deg, r.r.start_cone_rad, r.a.demand,
                   r.within() ? 1 : 0, r.r.contact_ticks > 0 ? 1 : 0, static_cast<unsigned long long>(r.r.contact_ticks),
                   r.r.first_contact_s, r.r.max_cone_rad, r.r.closest_rad, r.r.first_beyond_cp_s, r.r.first_protect_s,
                   r.r.first_beyond_s, r.r.first_limit_s, r.r.first_fault_s, gyro::enum_name(r.r.final_mode),
                   r.r.reached_mode ? 1 : 0, r.demand_turn_plus_u, static_cast<unsigned long long>(r.r.protect_toggles),
                   static_cast<unsigned long long>(r.r.saturated_ticks), r.r.worst_residual_rad, r.r.residual_fault ? 1 : 0,
                   static_cast<unsigned long long>(r.r.beyond_ticks), r.r.furthest_out_rad, flag_names(r.r.flags_seen, " ").c_str());
    }
    std::fclose(f);
  }
  std::fprintf(stderr, "%zu cases in %.1f s; %d contacts within authority\n", rows.size(), seconds, contacts_within);
  return 0;
}
