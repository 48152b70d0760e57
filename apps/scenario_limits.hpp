// What a scenario's run can represent, checked before anything runs, beyond what the
// component's and the stub's configure() check on their own. A scenario accepted here does
// not fail on its first tick (a refusal of the stub, a non-finite value in the CSV).
//
// - A float run: every number of the file within float's range (the component, the stub and
//   the guidance inputs are cast to float).
// - The body: it turns by at most pi per tick at its peak rates (constant plus weave); a
//   faster body is aliased by the tick, and at absurd rates its attitude is no longer a
//   rotation. The weave's frequency is below the tick's Nyquist rate, 0.5 / tick. A recorded
//   trajectory: its largest row's rates, and it lasts as long as the run.
// - The torque on the emulated rotor: the largest that can act (commands up to
//   component.max_torque times the torquer scale, saturated-torquer faults, torquer
//   cross-coupling, the error sources' drifts at the gimbal's extremes and the body's
//   accelerations, at the start spin), held over one tick from rest and from the steady
//   precession it drives, must give a representable step.
//
// A refusal is a ScenarioError naming the field; when several values make up the quantity
// that overflows, the one furthest from 1 in magnitude.
#pragma once

#include "scenario.hpp"

namespace gyro::sil {

// Every number within the range of the scenario's run.precision (before configure(), so
// that the refusal names the field that does not fit rather than what it became).
void check_precision_range(const Scenario& s);

// The body and the torque on the emulated rotor, in the scenario's run.precision (after
// configure() accepted both configurations).
void check_run_limits(const Scenario& s);

// A body trajectory lasts at least as long as the run (checked again after the run's length
// is overridden: gyro_sil --ticks, the Python module's ticks).
void check_trajectory_covers_run(const Scenario& s);

}  // namespace gyro::sil
