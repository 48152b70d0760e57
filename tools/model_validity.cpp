// The validity envelope of the gyro models against the gimbal plant, measured over gimbal
// cone, body turn rate and roll (tools/validity_envelope.hpp runs each case): writes
// docs/model-validity.md and the data of its plot.
//
// Usage: gyro_model_validity [--markdown out.md] [--data out.dat]
#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <iterator>
#include <string>
#include <vector>

#include "text_file.hpp"
#include "validity_envelope.hpp"

namespace {

using gyro::validity::Case;
using gyro::validity::ClosedLoopResult;
using gyro::validity::kDeg;
using gyro::validity::OpenLoopResult;

constexpr double kCones[] = {0, 5, 10, 15, 20, 25};        // deg
constexpr double kTurns[] = {0, 0.5, 1, 1.5, 2};           // rad/s
constexpr double kRolls[] = {0, 1, 2, 5, 10, 15, 20};      // rad/s
constexpr double kScan = 0.3;                              // rad/s along the cone (0 at cone 0)
constexpr double kResidualGoal = 2e-4;                     // rad
constexpr double kSlewGoal = 0.01;                         // of the command

// The acceptance envelope: cone up to 20 deg, turn up to 1 rad/s, roll up to 10 rad/s.
bool in_envelope(double cone_deg, double turn, double roll) { return cone_deg <= 20 && turn <= 1 && roll <= 10; }

struct Row {
  double cone_deg, turn, roll;
  OpenLoopResult open;
  ClosedLoopResult closed;
};

std::string fmt(const char* f, double v) {
  char b[512];
  std::snprintf(b, sizeof b, f, v);
  return b;
}

// What the component did that a clean run does not: F safe mode (fault), S on the stop,
// L gimbal-limit flag, P stop protection withheld a command, T torquer saturated, R the
// slew-rate limit cut the command (each flagged by the component).
std::string marks(const ClosedLoopResult& c) {
  std::string m;
  if (c.fault) m += "F";
  if (c.contact_ticks > 0) m += "S";
  if ((c.flags_seen & gyro::kGimbalLimit) != 0u) m += "L";
  if ((c.flags_seen & gyro::kGimbalStopProtect) != 0u) m += "P";
  if (c.saturated_ticks > 0) m += "T";
  if ((c.flags_seen & gyro::kSlewRateLimited) != 0u) m += "R";
  return m.empty() ? "" : " " + m;
}

// One table: rows (cone, turn), columns roll; `cell` renders a row.
template <typename Cell>
std::string table(const std::vector<Row>& rows, Cell cell) {
  std::string t = "| cone | turn |";
  for (double p : kRolls) t += fmt(" roll %g |", p);
  t += "\n|---|---|";
  for (std::size_t i = 0; i < std::size(kRolls); ++i) t += "---|";
  t += "\n";
  for (std::size_t i = 0; i < rows.size(); i += std::size(kRolls)) {
    t += fmt("| %g deg ", rows[i].cone_deg) + fmt("| %g |", rows[i].turn);
    for (std::size_t j = 0; j < std::size(kRolls); ++j) {
      const Row& r = rows[i + j];
      const bool inside = in_envelope(r.cone_deg, r.turn, r.roll);
      t += inside ? " **" + cell(r) + "** |" : " " + cell(r) + " |";
    }
    t += "\n";
  }
  return t;
}

const char* kIntro = R"(# Model validity: the report's model, the corrected model and the component against the gimbal

Regenerate with `scripts/model-validity.sh` (`tools/model_validity.cpp`, the runs in
`tools/validity_envelope.hpp`; the acceptance corners are `tests/model_validity_test.cpp`).

The reference is the SIL stub's nonlinear gimbal plant (`docs/gimbal-plant.md`): the seeker
example (`SeekerExample`: H = 0.0754 N m s, 600 Hz nutation, 2 kHz tick, friction 4e-4 N m s
on each bearing, gimbal rings of a few e-6 kg m^2, spin held by a motor relative to the inner
gimbal, torquer limit 0.1 N m = 1.33 rad/s of precession, slew-rate limits 1 rad/s per axis).

## The motion of a case

A case is a gimbal cone c (spin axis to body x), a body turn rate b across body x (split
equally on pitch q and yaw r, b/sqrt2 each) and a body roll p, all constant. The body turns
about its fixed rate vector from the identity attitude (exact). The spin axis is kept on the
cone c, scanning round body x at 0.3 rad/s (nothing at c = 0): its inertial angular velocity
across itself is that of (s / sin c, q, r) in body axes, so it follows the body's pitch and
yaw but not its roll (the body rolls round it, as round a seeker's line of sight).

- **Open loop** (1 s): `GyroModel` as the report has it (`TorquerAxes::kGyro`: the torques as
  T1, T2 on the gyro's own axes, friction on its inertial rates) and as corrected
  (`TorquerAxes::kGimbal`, `docs/gimbal-geometry.md`), both started on the plant's state, are
  given the same torquer commands as the plant, held per tick: the feed-forward of the path
  at the middle of each tick (no feedback). Measured: the worst gimbal-angle difference,
  plant against model, either axis, over the second.
- **Closed loop**: `GyroComponent` (seeker configuration) against `SimulatedGyro` with the
  gimbal plant and ideal pickoffs (no noise, bias, lag or quantisation) and ideal torquers.
  The stub powers up with the gimbals at rest relative to the turning body; the component
  cages, and uncaging is requested after 0.2 s. While uncaging (0.2 s) the torquers are off
  and the gimbals drift with the body. Once free,
  guidance commands the path's rate plus a pull onto the cone (gain 4 1/s, at most
  0.5 rad/s), from the measured gimbal angles. Measured: the worst residual (either axis)
  from the uncaging request on, and in a 1 s window that opens 0.8 s after the component is
  free (cone acquired); in the window, the slew-rate error: the plant's spin-axis rate at
  each tick against the rate the component flew from the tick before (2-norms, relative to
  the command where it is at least 0.05 rad/s).

Cells in **bold** are inside the acceptance envelope (cone up to 20 deg, turn up to
1 rad/s, roll up to 10 rad/s). Letters after a closed-loop figure say what happened: F the
component went to safe mode, S the plant was on its stop, L the component flagged the gimbal
limit, P it withheld a command toward the stop (and flagged it), T it flagged its torquer
saturated, R it cut the command to its slew-rate limit and flagged it (guidance, or while
caged the body, asked more than the component may fly).

## Reading the tables

- The report's model is off by 1e-3 to 0.4 rad within a second without roll (friction on the
  inertial rates, torques on axes that are not the gimbal's), and by tenths of a radian as
  soon as the body rolls (its torquer axes never roll). The corrected model stays within
  2.8e-4 rad inside the envelope, and within 5e-5 rad without roll (1e-14 at a centred spin
  axis); over the whole grid the worst is 3.3e-3 rad, at a 25 deg cone and 20 rad/s of roll:
  what is left grows with roll and cone, the gimbal rings' inertia (which the model does not
  carry) and the torque held over a tick in which its axes turn.
- The component's residual stays under 1e-4 rad inside the envelope from the uncaging
  request on, transients included (worst 8.6e-5 rad at a 20 deg cone, 1 rad/s of turn,
  10 rad/s of roll, in the steady slew), and under 5e-4 rad over the whole grid wherever the
  gimbal stays off its stop. Two things make the transients as small as the steady state:
  the torque shaper (docs/component.md, "Torque shaping against nutation"), without which a
  step of torque into a slew left a nutation that drifted out of phase with the estimator's
  (4.1e-4 rad at a centred spin axis, 1 rad/s of turn, 5 rad/s of roll), and the estimator
  started afresh at uncaging from the body's rate, which the shaped cage loop now leaves
  true to within 2e-5 rad. Where the stop protection withholds commands near the stop (P)
  the withheld command switches the torque on and off; the slew-rate error there measures
  that, not a slew.
- The slew-rate error grows with roll and cone: 2.5 % at a 20 deg cone and 20 rad/s of roll,
  5.9 % at 25 deg. Most of it is the spin motor's reaction, which the torque law does not
  hold off (`docs/gimbal-geometry.md`, "Spin motor"); the rest is the gimbal rings' inertia.
- A change of command (the settling tables, after the grids): ramps over 10 ms and chirps to
  40 Hz excite little nutation and settle within 1 % in under a nutation period everywhere
  in the envelope. A step is within 1 % two nutation periods later in 51 of the 60 cases
  (with the body turning at 1 rad/s, or the gimbal within 10 deg of pitch and roll up to
  5 rad/s, everywhere). The torque shaper follows the nutation at the gimbal's pitch and the
  inner gimbal's roll (docs/component.md); what it does not know is the gimbal rings' share
  of the yaw inertia at a pitch angle (not configured: 1 % of beta at 18 deg of pitch), which
  lets 1-2 % of a step's nutation through, beyond 1 % of the command for up to 16 periods
  where the command is small (no body turn) and the gimbal beyond 12 deg of pitch, and the
  spin motor's reaction at 10 rad/s of roll. A shaper made for zero gimbal angles settled
  33 of the 60 within two periods, at worst after 74 (4.2 % off 50 ms after the step).
- Heavier gimbal rings (the last table) at the same effective inertias raise the steady
  residual, within 2e-4 rad up to half the effective inertia: the estimator's model carries
  none of the rings' change with the gimbal angles.
- The power-up on a turning body (last line of the first table): the rotor is released with
  the gimbals at rest on a body turning at up to 2 rad/s, with no torque: it nutates by
  |wb| / beta, and the estimator, started a tick later from the body's rate, misses it until
  friction damps it (alpha = 20 1/s); uncaging waits 0.2 s.
- Beyond the envelope, a body turning at 1.5-2 rad/s across body x asks 1.06-1.41 rad/s on
  each gimbal axis: more than the slew-rate limit (1 rad/s per axis) and, at 2 rad/s, more
  than the torquer's authority (1.33 rad/s). The component cuts the command to its limit and
  flags it (`slew_rate_limited`, R) from the first such tick; with little roll the gimbal
  then drifts onto the stop: the component flags the gimbal limit 90-1,030 ticks before the
  stop, never commands toward the stop (it withholds outward commands near it) and latches
  a residual fault 21-32 ticks after the plant hits it (the table below). Fast roll turns
  the body's rate across the spin axis round the gimbal axes and averages it out: from
  5 rad/s of roll on, these cases follow.
)";

// ---------------------------------------------------------------------------------------
// A change of command (validity_envelope.hpp, run_command_change) over the acceptance envelope.

using gyro::validity::CommandShape;
using gyro::validity::SettlingResult;

constexpr double kSettleCones[] = {0, 5, 10, 15, 20};  // deg
constexpr double kSettleTurns[] = {0, 0.5, 1};         // rad/s
constexpr double kSettleRolls[] = {0, 2, 5, 10};       // rad/s
constexpr CommandShape kShapes[] = {CommandShape::kStep, CommandShape::kRamp, CommandShape::kChirp};
constexpr double kSettleGoalPeriods = 2.0;

struct SettleRow {
  double cone_deg, turn, roll;
  SettlingResult shape[3];
};

// Rows (cone, turn), columns roll; `cell` renders a row's cell.
template <typename Cell>
std::string settle_grid(const std::vector<SettleRow>& rows, Cell cell) {
  std::string t = "| cone | turn |";
  for (double p : kSettleRolls) t += fmt(" roll %g |", p);
  t += "\n|---|---|";
  for (std::size_t i = 0; i < std::size(kSettleRolls); ++i) t += "---|";
  t += "\n";
  for (std::size_t i = 0; i < rows.size(); i += std::size(kSettleRolls)) {
    t += fmt("| %g deg ", rows[i].cone_deg) + fmt("| %g |", rows[i].turn);
    for (std::size_t j = 0; j < std::size(kSettleRolls); ++j) {
      t += " " + cell(rows[i + j]) + " |";
    }
    t += "\n";
  }
  return t;
}

// The three shapes' figures in one cell: step / ramp / chirp.
std::string settle_table(const std::vector<SettleRow>& rows, std::string (*cell)(const SettlingResult&)) {
  return settle_grid(rows, [cell](const SettleRow& r) {
    return cell(r.shape[0]) + " / " + cell(r.shape[1]) + " / " + cell(r.shape[2]);
  });
}

std::string periods(const SettlingResult& r) {
  return r.settled ? fmt("%.1f", r.settle_s / r.nutation_period_s) : std::string(">") + fmt("%.0f", r.settle_s / r.nutation_period_s);
}

std::string settling_section() {
  std::vector<SettleRow> rows;
  for (double c : kSettleCones) {
    for (double b : kSettleTurns) {
      for (double p : kSettleRolls) {
        SettleRow row{c, b, p, {}};
        const Case k{c * kDeg, b, p, c > 0 ? kScan : 0.0};
        for (std::size_t s = 0; s < std::size(kShapes); ++s) {
          row.shape[s] = gyro::validity::run_command_change(k, kShapes[s]);
          if (!row.shape[s].ok) {
            std::fprintf(stderr, "change of command, cone %g deg, turn %g, roll %g, %s: a call was refused\n", c, b,
                         p, gyro::validity::shape_name(kShapes[s]));
            std::exit(1);
          }
        }
        rows.push_back(row);
      }
    }
  }
  std::string md = "\n## A change of command: settling of the slew rate\n\n";
  md += fmt("The closed loop above; %.1f s after the component is free guidance adds ",
            gyro::validity::kChangeAfterSeconds) +
        fmt("(%.2f, ", gyro::validity::kChange(0)) + fmt("%.2f) rad/s on (y_I, z_I) to its command: ", gyro::validity::kChange(1)) +
        "with the path's rate up to the slew-rate limit (1 rad/s per axis, below the torquer's 1.33 rad/s). ";
  md += fmt("Shapes: a **step**; a **ramp** over %.0f ms; a **chirp**, a sine of that amplitude ",
            gyro::validity::kRampSeconds * 1e3) +
        fmt("swept from 0 to %.0f Hz ", gyro::validity::kChirpTopHz) +
        fmt("over %.0f ms, ending at zero. ", gyro::validity::kChirpSeconds * 1e3);
  md += "The rate error is the plant's true spin-axis rate at each tick against the rate the component flew "
        "from the tick before (2-norm), relative to that rate or to the size of the change where the rate is "
        "smaller (a chirp passes through zero). The settling time runs from the end of the change to the last "
        "tick the error is beyond 1 %, ";
  md += fmt("within %.0f ms (`>` when it is still beyond 1 %% then); ", gyro::validity::kAfterChangeSeconds * 1e3) +
        "the nutation period is the plant's at its gimbal angles when the change begins "
        "(H / sqrt(J1 J2), J2 growing as 1 / cos^2 of the pitch angle with the rings and rotor). Cells are "
        "step / ramp / chirp; the grid is the acceptance envelope (cone 0-20 deg, turn 0-1 rad/s, roll "
        "0-10 rad/s).\n\n";
  double worst_periods[3] = {0, 0, 0}, worst_50ms[3] = {0, 0, 0}, worst_peak[3] = {0, 0, 0};
  int met[3] = {0, 0, 0};
  double period_min = 1e300, period_max = 0;
  for (const SettleRow& r : rows) {
    for (int s = 0; s < 3; ++s) {
      const SettlingResult& x = r.shape[s];
      const double n = x.settle_s / x.nutation_period_s;
      worst_periods[s] = std::max(worst_periods[s], x.settled ? n : 1e9);
      worst_50ms[s] = std::max(worst_50ms[s], x.error_50ms_rel);
      worst_peak[s] = std::max(worst_peak[s], x.peak_error_rel);
      met[s] += x.settled && n <= kSettleGoalPeriods ? 1 : 0;
      period_min = std::min(period_min, x.nutation_period_s);
      period_max = std::max(period_max, x.nutation_period_s);
    }
  }
  md += fmt("Nutation period at the change: %.3f", period_min * 1e3) + fmt("-%.3f ms.\n\n", period_max * 1e3);
  md += "| shape | cases settled within 1 % in 2 nutation periods | worst settling (periods) | worst error 50 ms "
        "after the change | peak error |\n|---|---|---|---|---|\n";
  for (int s = 0; s < 3; ++s) {
    md += std::string("| ") + gyro::validity::shape_name(kShapes[s]) + fmt(" | %.0f", static_cast<double>(met[s])) +
          fmt(" of %.0f", static_cast<double>(rows.size())) +
          (worst_periods[s] >= 1e9 ? std::string(" | not settled in 150 ms") : fmt(" | %.1f", worst_periods[s])) +
          fmt(" | %.2f %%", 100 * worst_50ms[s]) + fmt(" | %.1f %% |\n", 100 * worst_peak[s]);
  }
  md += "\n### The plant's pitch gimbal angle when the change begins (deg)\n\n";
  md += settle_grid(rows, [](const SettleRow& r) { return fmt("%.1f", r.shape[0].pitch_at_change_rad / kDeg); });
  md += "\n### Settling time to 1 % (nutation periods; step / ramp / chirp)\n\n";
  md += settle_table(rows, periods);
  md += "\n### Settling time to 1 % (ms; step / ramp / chirp)\n\n";
  md += settle_table(rows, [](const SettlingResult& r) { return (r.settled ? "" : ">") + fmt("%.1f", r.settle_s * 1e3); });
  md += "\n### Peak rate error from the change on (% of the command; step / ramp / chirp)\n\n";
  md += settle_table(rows, [](const SettlingResult& r) { return fmt("%.1f", 100 * r.peak_error_rel); });
  md += "\n### Worst rate error from 50 ms after the change (% of the command; step / ramp / chirp)\n\n";
  md += settle_table(rows, [](const SettlingResult& r) { return fmt("%.2f", 100 * r.error_50ms_rel); });
  return md;
}

// ---------------------------------------------------------------------------------------
// Heavier gimbal rings at the same effective inertias (validity_envelope.hpp, heavy_ring_rig).

constexpr double kRingShares[] = {0, 0.1, 0.2, 0.25, 0.35, 0.5};
constexpr double kRingCones[] = {0, 10, 20};
constexpr double kRingTurns[] = {0, 1};
constexpr double kRingRolls[] = {0, 5, 10};

std::string heavy_ring_section() {
  std::string md = "\n## Heavier gimbal rings: the steady residual\n\n";
  md += "The closed loop above (steady slews along the cone) with the gimbal rings taking a share of the "
        "effective inertias J1 = J2 = 2e-5 kg m^2 at zero gimbal angles (thin rings; the seeker's is 0.2), the "
        "rotor the rest (A = (1 - share) J). Beyond a share of 0.25 the seeker's J0 = 3e-5 would exceed 2A "
        "(no rigid rotor): there J0 = 2A and the spin is raised for the same H = 0.0754 N m s (the component "
        "configured with that rotor). Worst over cone {0, 10, 20} deg, turn {0, 1} rad/s, roll {0, 5, 10} rad/s:\n\n";
  md += "| ring share | J0 (kg m^2) | spin (Hz) | worst residual in steady slews (rad) | at | worst residual from "
        "uncaging on (rad) | worst slew-rate error |\n|---|---|---|---|---|---|---|\n";
  for (double share : kRingShares) {
    const gyro::validity::Rig rig = gyro::validity::heavy_ring_rig(share);
    double window = 0, from_uncaging = 0, slew = 0;
    std::string at;
    for (double c : kRingCones) {
      for (double b : kRingTurns) {
        for (double p : kRingRolls) {
          const Case k{c * kDeg, b, p, c > 0 ? kScan : 0.0};
          const ClosedLoopResult r =
              gyro::validity::run_closed_loop(k, gyro::validity::kWindowSeconds, rig.stub, rig.component);
          if (!r.ok || r.fault) {
            std::fprintf(stderr, "ring share %g, cone %g deg, turn %g, roll %g: refused or safe mode\n", share, c, b, p);
            std::exit(1);
          }
          if (r.worst_residual_window_rad > window) {
            window = r.worst_residual_window_rad;
            at = fmt("cone %g deg, ", c) + fmt("turn %g, ", b) + fmt("roll %g", p);
          }
          from_uncaging = std::max(from_uncaging, r.worst_residual_rad);
          slew = std::max(slew, r.slew_error_rel);
        }
      }
    }
    md += fmt("| %g ", share) + fmt("| %.2g ", rig.component.spin_inertia) + fmt("| %.0f ", rig.component.nominal_spin_hz) +
          fmt("| %.2e ", window) + "| " + at + fmt(" | %.2e ", from_uncaging) + fmt("| %.2f %% |\n", 100 * slew);
  }
  return md;
}

}  // namespace

int main(int argc, char** argv) {
  std::string markdown, data;
  for (int i = 1; i < argc; ++i) {
    if (std::strcmp(argv[i], "--markdown") == 0 && i + 1 < argc) {
      markdown = argv[++i];
    } else if (std::strcmp(argv[i], "--data") == 0 && i + 1 < argc) {
      data = argv[++i];
    } else {
      std::fprintf(stderr, "usage: gyro_model_validity [--markdown out.md] [--data out.dat]\n");
      return 2;
    }
  }

  std::vector<Row> rows;
  for (double c : kCones) {
    for (double b : kTurns) {
      for (double p : kRolls) {
        const Case k{c * kDeg, b, p, c > 0 ? kScan : 0.0};
        Row r{c, b, p, gyro::validity::run_open_loop(k), gyro::validity::run_closed_loop(k)};
        if (!r.open.ok || !r.closed.ok) {
          std::fprintf(stderr, "case cone %g deg, turn %g, roll %g: a call was refused\n", c, b, p);
          return 1;
        }
        rows.push_back(r);
      }
    }
  }

  // The acceptance figures over its envelope.
  double worst_res = 0, worst_res_window = 0, worst_slew = 0, worst_caged = 0;
  const Row* at_res = nullptr;
  int faults_inside = 0, contacts_inside = 0, cases_inside = 0;
  for (const Row& r : rows) {
    if (!in_envelope(r.cone_deg, r.turn, r.roll)) continue;
    ++cases_inside;
    if (r.closed.worst_residual_rad > worst_res) {
      worst_res = r.closed.worst_residual_rad;
      at_res = &r;
    }
    worst_res_window = std::max(worst_res_window, r.closed.worst_residual_window_rad);
    worst_slew = std::max(worst_slew, r.closed.slew_error_rel);
    worst_caged = std::max(worst_caged, r.closed.worst_residual_caged_rad);
    faults_inside += r.closed.fault || r.closed.residual_fault ? 1 : 0;
    contacts_inside += r.closed.contact_ticks > 0 ? 1 : 0;
  }

  std::string md = kIntro;
  md += "\n## The acceptance envelope\n\n";
  md += fmt("%.0f cases (cone 0-20 deg, turn 0-1 rad/s, roll 0-10 rad/s of the grid below):\n\n", static_cast<double>(cases_inside));
  md += "| figure | measured | goal |\n|---|---|---|\n";
  md += fmt("| cases with a residual fault or safe mode | %.0f | 0 |\n", static_cast<double>(faults_inside));
  md += fmt("| cases on the stop | %.0f | 0 |\n", static_cast<double>(contacts_inside));
  md += fmt("| worst residual in steady slews (window) | %.2e rad |", worst_res_window) +
        fmt(" <= %.0e rad |\n", kResidualGoal);
  md += fmt("| worst residual from uncaging on | %.2e rad", worst_res);
  if (at_res != nullptr) {
    md += fmt(" (cone %g deg,", at_res->cone_deg) + fmt(" turn %g,", at_res->turn) + fmt(" roll %g,", at_res->roll) +
          fmt(" %.0f ms after the component went free)",
              (static_cast<double>(at_res->closed.worst_residual_tick) * gyro::validity::Seeker::kTick -
               at_res->closed.free_at_s) * 1e3);
  }
  md += fmt(" | <= %.0e rad |\n", kResidualGoal);
  md += fmt("| worst slew-rate error (window) | %.2f%% of the command |", 100 * worst_slew) +
        fmt(" <= %.0f%% |\n", 100 * kSlewGoal);
  md += fmt("| worst residual while caged (power-up on a turning body) | %.2e rad | - |\n", worst_caged);

  md += "\n## Open loop: the report's model against the gimbal (worst gimbal-angle error over 1 s, rad)\n\n";
  md += table(rows, [](const Row& r) { return fmt("%.1e", r.open.report_error_rad); });
  md += "\n## Open loop: the corrected model (`TorquerAxes::kGimbal`) against the gimbal (rad)\n\n";
  md += table(rows, [](const Row& r) { return fmt("%.1e", r.open.corrected_error_rad); });
  md += "\n## Closed loop: the component's worst residual from uncaging on (rad)\n\n";
  md += table(rows, [](const Row& r) { return fmt("%.1e", r.closed.worst_residual_rad) + marks(r.closed); });
  md += "\n## Closed loop: the component's worst residual in steady slews (the window, rad)\n\n";
  md += table(rows, [](const Row& r) { return fmt("%.1e", r.closed.worst_residual_window_rad) + marks(r.closed); });
  md += "\n## Closed loop: slew-rate error in the window (% of the command)\n\n";
  md += table(rows, [](const Row& r) {
    return r.closed.fault ? std::string("-") + marks(r.closed) : fmt("%.2f", 100 * r.closed.slew_error_rel) + marks(r.closed);
  });

  md += "\n## Where the torquer cannot keep up\n\n";
  md += "Cases where the plant reached its stop or the component went to safe mode, with the tick (from "
        "power-up, 0.5 ms) at which the component first flagged the gimbal limit, the plant first touched "
        "the stop and the component went to safe mode, and the flags it raised before safe mode:\n\n";
  md += "| cone | turn | roll | gimbal limit flagged | on the stop | safe mode | flags before safe mode |\n";
  md += "|---|---|---|---|---|---|---|\n";
  for (const Row& r : rows) {
    const ClosedLoopResult& c = r.closed;
    if (!c.fault && c.contact_ticks == 0) continue;
    auto at = [](std::uint64_t t) { return t == 0 ? std::string("never") : fmt("%.0f", static_cast<double>(t)); };
    std::string flags;
    for (int bit = 0; bit < gyro::kComponentFlagCount; ++bit) {
      if ((c.flags_before_fault & (1u << static_cast<unsigned>(bit))) != 0u) {
        flags += (flags.empty() ? "" : ", ") + std::string(gyro::flag_name(bit));
      }
    }
    md += fmt("| %g deg ", r.cone_deg) + fmt("| %g ", r.turn) + fmt("| %g ", r.roll) + "| " +
          at(c.first_limit_tick) + " | " + at(c.first_contact_tick) + " | " + at(c.first_fault_tick) + " | " +
          (flags.empty() ? "none" : flags) + " |\n";
  }

  md += settling_section();
  md += heavy_ring_section();

  std::fputs(md.c_str(), stdout);
  if (!markdown.empty() && !gyro::tools::write_text_file(markdown, md)) return 1;
  if (!data.empty()) {
    std::FILE* f = gyro::tools::open_for_writing(data);
    if (f == nullptr) return 1;
    std::fputs("# cone_deg turn_rad_s roll_rad_s report_err corrected_err residual residual_window slew_rel fault\n", f);
    for (const Row& r : rows) {
      std::fprintf(f, "%g %g %g %.6e %.6e %.6e %.6e %.6e %d\n", r.cone_deg, r.turn, r.roll, r.open.report_error_rad,
                   r.open.corrected_error_rad, r.closed.worst_residual_rad, r.closed.worst_residual_window_rad,
                   r.closed.slew_error_rel, r.closed.fault ? 1 : 0);
    }
    std::fclose(f);
  }
  return 0;
}
