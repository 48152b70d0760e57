"""SimulatedGyro, GyroComponent and SilLoop from Python: the loop a simulation author writes
is gyro_sil's loop (the same time history), their keywords are a scenario's sections, and the
example gyros construct them."""

import numpy as np
import pytest

import gyro


def scenario(source_dir, name):
    return gyro.read_scenario(source_dir / "scenarios" / name)


def at_rest(doc):
    """The scenario with the body at rest: its attitude stays the identity, exactly."""
    doc = dict(doc)
    doc["body"] = {"rate_rad_s": [0.0, 0.0, 0.0]}
    return doc


def fly(doc, precision):
    """The scenario's guidance flown by a loop written here; the gimbal angles, torques and
    modes of every tick."""
    tick_s = 1.0 / doc["run"]["rate_hz"]
    f32 = precision == "float"
    stub = (gyro.SimulatedGyroF32 if f32 else gyro.SimulatedGyro)(tick_s, **doc["gyro"])
    component = (gyro.GyroComponentF32 if f32 else gyro.GyroComponent)(stub, tick_s, **doc["component"])
    loop = (gyro.SilLoopF32 if f32 else gyro.SilLoop)(stub, component)
    assert loop.start() == gyro.Status.OK
    events = {round(e["t_s"] / tick_s): e for e in doc["guidance"]["schedule"]}
    slew = [0.0, 0.0]
    out = {"gimbal_pitch": [], "gimbal_yaw": [], "torque_pitch": [], "mode": []}
    for k in range(round(doc["run"]["duration_s"] / tick_s) + 1):
        e = events.get(k, {})
        slew = e.get("slew_rate_rad_s", slew)
        loop.tick(k, request=e.get("request"), slew_rate=slew)
        out["gimbal_pitch"].append(float(stub.gimbal_angle[0]))
        out["gimbal_yaw"].append(float(stub.gimbal_angle[1]))
        out["torque_pitch"].append(float(component.telemetry["torque_cmd"][0]))
        out["mode"].append(component.mode)
    return out


@pytest.mark.parametrize("precision", ["double", "float"])
def test_given_a_scenario_when_flown_by_a_python_loop_then_its_history_is_gyro_sils(source_dir, precision):
    doc = at_rest(scenario(source_dir, "fault_dead_torquer.json"))
    mine = fly(doc, precision)
    run = gyro.run_sil(doc, precision=precision)
    # The CSV's values: %.9e of the same numbers.
    for name in ("gimbal_pitch", "gimbal_yaw", "torque_pitch"):
        np.testing.assert_allclose(mine[name], run[name], rtol=1e-9, atol=1e-15, err_msg=name)
    assert mine["mode"] == list(run["mode"])
    assert "fault" in mine["mode"]  # the dead torquer is found in the Python loop too


def test_given_every_shipped_scenario_then_its_sections_are_the_keywords(source_dir):
    for path in sorted((source_dir / "scenarios").glob("*.json")):
        doc = gyro.read_scenario(path)
        run = doc["run"]
        tick_s = run["tick_s"] if "tick_s" in run else 1.0 / run["rate_hz"]
        for stub_class, component_class in ((gyro.SimulatedGyro, gyro.GyroComponent),
                                            (gyro.SimulatedGyroF32, gyro.GyroComponentF32)):
            stub = stub_class(tick_s, **doc["gyro"])
            component_class(stub, tick_s, doc["component"])  # a dict works as keywords do


def test_given_a_missing_or_bad_field_then_it_is_named_as_the_scenario_names_it(source_dir):
    doc = scenario(source_dir, "seeker_slew.json")
    rotor = dict(doc["gyro"]["rotor"])
    del rotor["pitch_inertia"]
    with pytest.raises(gyro.ConfigError) as e:
        gyro.SimulatedGyro(1e-3, **{**doc["gyro"], "rotor": rotor})
    assert e.value.field == "rotor.pitch_inertia" and "missing required field" in str(e.value)
    with pytest.raises(gyro.ConfigError) as e:
        gyro.SimulatedGyro(1e-3, **{**doc["gyro"], "limits": {**doc["gyro"]["limits"], "gimbal_stop_rad": 2.0}})
    assert e.value.field == "limits.gimbal_stop_rad"
    with pytest.raises(gyro.ConfigError) as e:
        gyro.SimulatedGyro(1e-3, **doc["gyro"], spin_hz=400.0)
    assert e.value.field == "spin_hz" and "unknown" in str(e.value)
    stub = gyro.SimulatedGyro(1e-3, **doc["gyro"])
    # Beyond what the torquer electronics drive (0.05 / 1.02): the pairing rule of gyro_sil.
    with pytest.raises(gyro.ConfigError) as e:
        gyro.GyroComponent(stub, 1e-3, **{**doc["component"], "max_torque": 0.06})
    assert e.value.field == "max_torque" and "torquer electronics" in str(e.value)


def test_given_the_optional_sections_left_out_then_the_scenario_defaults_hold(source_dir):
    # pickoff, torquer and seed are optional in docs/scenarios.md: an ideal pickoff and torquer.
    doc = scenario(source_dir, "seeker_slew.json")
    bare = {k: v for k, v in doc["gyro"].items() if k not in ("pickoff", "torquer", "seed")}
    stub = gyro.SimulatedGyro(1e-3, **bare)
    stub.start()
    stub.write_torquer([0.02, -0.01])
    assert list(stub.applied_torque) == [0.02, -0.01]  # scale factor 1, no saturation


def test_given_a_torque_above_the_torquers_limit_then_the_stub_saturates_it_and_the_plant_refuses(source_dir):
    doc = scenario(source_dir, "seeker_slew.json")
    stub = gyro.SimulatedGyro(1e-3, **doc["gyro"])
    stub.start()
    stub.write_torquer([1.0, -1.0])
    assert list(stub.applied_torque) == [0.05, -0.05]  # the electronics saturate, as the hardware does
    stub.advance(1)
    ex = gyro.examples.seeker()
    plant = gyro.GimbalPlant(ex.tick_s, **ex.gimbal_plant)
    plant.start(spin_hz=ex.spin_hz)
    with pytest.raises(gyro.StatusError, match=r"torque \(2, 0\) is beyond max_torque 1"):
        plant.step([2.0, 0.0])


def test_given_the_examples_then_each_configuration_builds_its_class():
    ex = gyro.examples.seeker()
    stub = gyro.SimulatedGyro(ex.tick_s, **ex.gyro)
    component = gyro.GyroComponent(stub, ex.tick_s, **ex.component)
    assert component.config["tick_s"] == ex.tick_s
    assert gyro.GimbalPlant(ex.tick_s, **ex.gimbal_plant).config["stop_cone_rad"] == ex.gyro["limits"]["gimbal_stop_rad"]
    gyro.GyroModel(**ex.model)
    report = gyro.examples.report()
    model = gyro.GyroModel(**report.model)
    assert model.config["friction"] == 5.0
    ex.component["max_torque"] = 0.0  # a copy: the next call is whole again
    assert gyro.examples.seeker().component["max_torque"] > 0


def test_given_a_component_then_step_returns_the_status_and_telemetry_names_the_flags(source_dir):
    ex = gyro.examples.seeker()
    stub = gyro.SimulatedGyroF32(ex.tick_s, **ex.gyro)
    component = gyro.GyroComponentF32(stub, ex.tick_s, **ex.component)
    # Before activate(): refused, flagged, nothing else changes.
    assert component.step(1) == gyro.Status.NOT_CONFIGURED
    assert component.telemetry["flag_names"] == ["not_active"] and component.mode == "idle"
    loop = gyro.SilLoopF32(stub, component)
    assert loop.start() == gyro.Status.OK
    assert loop.tick(0, slew_rate=[float("nan"), 0.0]) == gyro.Status.INPUT_IGNORED
    assert "command_rejected" in component.telemetry["flag_names"]
    assert component.telemetry["residual_rad"].dtype == np.float32
    with pytest.raises(ValueError, match="request"):
        loop.tick(1, request="fire")
    other = gyro.SimulatedGyroF32(ex.tick_s, **ex.gyro)
    with pytest.raises(ValueError, match="does not fly"):
        gyro.SilLoopF32(other, component)
