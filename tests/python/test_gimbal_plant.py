"""The gimbal plant from Python: configuration refusals naming the field, and the energy
balance of the nonlinear plant (kinetic energy change = work of the torquers and friction)."""

import math

import numpy as np
import pytest

import gyro

# The seeker example's device (examples/include/gyro/seeker_example.hpp), in SI units.
SEEKER = dict(spin_inertia=3e-5, rotor_transverse_inertia=1.6e-5, inner_gimbal_inertia=[2e-6, 4e-6, 2e-6],
              outer_gimbal_inertia=[4e-6, 2e-6, 2e-6], inner_friction=4e-4, outer_friction=4e-4, spin_drive="motor",
              max_spin_hz=400.0, motor_torque_limit=0.01, spin_servo_bandwidth_rad_s=5.0, spin_down_time_s=60.0,
              stop_cone_rad=0.55, stop_restitution=0.2, torquer_axes="gimbal", max_body_rate_rad_s=40.0, max_torque=1.0,
              max_specific_force=1e4)


def torqued_run(cls, ticks=200):
    """A free-spinning plant (no motor, no drag) torqued about both axes, away from its stop."""
    plant = cls(1e-3, SEEKER, spin_drive="free", spin_down_time_s=0.0)
    plant.start([0.05, -0.02], [0.3, -0.1], spin_hz=20.0)
    e0 = plant.kinetic_energy
    angles = []
    for k in range(ticks):
        plant.step([2e-4 * math.sin(0.05 * k), -1e-4])
        angles.append(plant.gimbal_angle.astype(np.float64))
        assert not plant.in_contact
    return plant, e0, np.array(angles)


def test_given_a_free_spin_plant_when_torqued_then_the_energy_change_equals_the_work():
    plant, e0, _ = torqued_run(gyro.GimbalPlant)
    w = plant.work
    assert w["torquer"] != 0 and w["friction"] < 0 and w["spin"] == 0
    de = plant.kinetic_energy - e0
    assert abs(de - (w["torquer"] + w["friction"])) < 1e-8 * abs(w["friction"])
    assert plant.substeps >= 1


def test_given_the_float32_plant_when_torqued_then_it_follows_float64():
    _, _, a64 = torqued_run(gyro.GimbalPlant)
    _, _, a32 = torqued_run(gyro.GimbalPlantF32)
    err = np.abs(a32 - a64).max()
    assert 0 < err < 1e-5 * np.abs(a64).max()


def test_given_the_config_when_read_back_then_it_holds_the_keywords():
    plant = gyro.GimbalPlant(1e-3, **SEEKER)
    assert plant.config["inner_gimbal_inertia"] == SEEKER["inner_gimbal_inertia"]
    assert plant.config["spin_drive"] == "motor"
    assert set(gyro.GimbalPlant.config_fields) == set(plant.config)


@pytest.mark.parametrize("tick, override, field", [
    (0.0, {}, "tick_s"),
    (1e-3, {"stop_cone_rad": 1.5}, "stop_cone_rad"),
    (1e-3, {"rotor_transverse_inertia": 1e-5}, "rotor_transverse_inertia"),  # J0 > 2A: no rigid rotor
    (1e-3, {"inner_gimbal_inertia": [1.0, 0.0, 0.0]}, "inner_gimbal_inertia"),
    (1e-3, {"inner_gimbal_inertia": [1.0, 0.0]}, "inner_gimbal_inertia"),
    (1e-3, {"spin_drive": "turbine"}, "spin_drive"),
])
def test_given_a_bad_field_when_the_plant_is_configured_then_config_error_names_it(tick, override, field):
    with pytest.raises(gyro.ConfigError) as e:
        gyro.GimbalPlant(tick, {**SEEKER, **override})
    assert e.value.field == field


def test_given_a_torque_beyond_the_envelope_when_stepped_then_refused_and_unchanged():
    plant = gyro.GimbalPlant(1e-3, SEEKER)
    plant.start(spin_hz=400.0)
    plant.step([1e-3, 0.0])
    before = (plant.gimbal_angle.copy(), plant.gimbal_rate.copy())
    with pytest.raises(gyro.StatusError) as e:
        plant.step([2.0, 0.0])
    assert e.value.status == gyro.Status.OUT_OF_RANGE
    assert "torque (2, 0) is beyond max_torque" in str(e.value), str(e.value)
    assert np.array_equal(before[0], plant.gimbal_angle) and np.array_equal(before[1], plant.gimbal_rate)
    with pytest.raises(gyro.StatusError, match=r"body_rate of norm 1e\+06 is beyond max_body_rate_rad_s"):
        plant.step([1e-3, 0.0], body_rate=[1e6, 0.0, 0.0])
