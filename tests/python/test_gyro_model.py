"""GyroModel from Python: configuration from keywords or a dict, refusals naming the field,
the report's sample run against the C++ driver's CSV, float32 against float64."""

import csv
import math
import subprocess

import numpy as np
import pytest

import gyro
from gyro import report_sample


def report_model(cls=gyro.GyroModel, **override):
    return cls({**report_sample.CONFIG, **override})


def test_given_keywords_or_a_dict_when_configured_then_the_configuration_reads_back():
    a = gyro.GyroModel(**report_sample.CONFIG)
    b = gyro.GyroModel(report_sample.CONFIG, friction=4.0, errors={"pitch": {"static_drift_rad_s": 1e-4}})
    assert a.config["friction"] == 5.0 and b.config["friction"] == 4.0
    assert b.config["errors"]["pitch"]["static_drift_rad_s"] == 1e-4
    assert b.config["torquer_axes"] == "gyro"
    assert set(gyro.GyroModel.config_fields) == set(a.config)
    assert gyro.GyroModel.dtype == np.float64 and gyro.GyroModelF32.dtype == np.float32


@pytest.mark.parametrize("field, value, status", [
    ("pitch_inertia", 0.0, gyro.Status.NON_POSITIVE_INERTIA),
    ("spin_inertia", -3.0, gyro.Status.NON_POSITIVE_INERTIA),
    ("friction", -1.0, gyro.Status.NEGATIVE_FRICTION),
    ("gimbal_cone_limit_rad", 4.0, gyro.Status.OUT_OF_RANGE),
    ("max_yaw_rate_rad_s", math.nan, gyro.Status.NON_FINITE_INPUT),
    ("yaw_gimbal_limit_rad", -0.1, gyro.Status.OUT_OF_RANGE),
])
@pytest.mark.parametrize("cls", [gyro.GyroModel, gyro.GyroModelF32])
def test_given_a_bad_field_when_configured_then_config_error_names_it(cls, field, value, status):
    with pytest.raises(gyro.ConfigError) as e:
        report_model(cls, **{field: value})
    assert e.value.field == field
    assert e.value.status == status
    assert field in str(e.value)
    assert isinstance(e.value, ValueError)


def test_given_a_bad_error_source_when_configured_then_the_field_is_errors():
    with pytest.raises(gyro.ConfigError) as e:
        report_model(errors={"yaw": {"coulomb_friction_rad_s": math.inf}})
    assert e.value.field == "errors"


@pytest.mark.parametrize("kwargs, field", [
    ({"pitch_inertai": 1.0}, "pitch_inertai"),
    ({"friction": "high"}, "friction"),
    ({"torquer_axes": "body"}, "torquer_axes"),
    ({"errors": {"roll": {}}}, "errors.roll"),
])
def test_given_an_unknown_key_or_wrong_kind_when_configured_then_config_error_names_it(kwargs, field):
    with pytest.raises(gyro.ConfigError) as e:
        report_model(**kwargs)
    assert e.value.field == field


def test_given_a_misspelt_key_when_configured_then_the_message_suggests_the_field():
    with pytest.raises(gyro.ConfigError, match="did you mean pitch_inertia"):
        report_model(pitch_inertai=1.0)


def test_given_a_refused_step_when_stepped_then_status_error_and_the_state_is_unchanged():
    g = report_model()
    with pytest.raises(gyro.StatusError) as e:
        g.step_torque(1e-3, [0.0, 0.0], spin_hz=100.0)
    assert e.value.status == gyro.Status.NOT_CONFIGURED
    g.uncage(body_rate=[0.1, 0.2])
    g.step_torque(1e-3, [1.0, 2.0], spin_hz=100.0)
    before = (g.rate.copy(), g.gimbal.copy(), g.attitude.copy())
    for bad in (dict(dt=0.0, torque=[0.0, 0.0]), dict(dt=1e-3, torque=[math.nan, 0.0])):
        with pytest.raises(gyro.StatusError):
            g.step_torque(spin_hz=100.0, **bad)
    with pytest.raises(gyro.StatusError) as e:
        g.step_torque(1e-3, [0.0, 0.0], spin_hz=100.0, R_earth_to_body=2 * np.eye(3))
    assert e.value.status == gyro.Status.INVALID_ROTATION
    after = (g.rate, g.gimbal, g.attitude)
    for x, y in zip(before, after):
        assert np.array_equal(x, y)


def test_given_the_report_sample_when_run_from_python_then_it_equals_the_cpp_driver(gyro_report_sample, tmp_path):
    out = tmp_path / "sample.csv"
    subprocess.run([str(gyro_report_sample), str(out)], check=True, capture_output=True)
    with open(out, newline="") as f:
        rows = list(csv.DictReader(f))
    t, pitch, yaw = report_sample.run()
    assert len(rows) == len(t) == report_sample.STEPS
    cpp = np.array([[float(r["t"]), float(r["gimbal_pitch"]), float(r["gimbal_yaw"])] for r in rows])
    assert np.allclose(cpp[:, 0], t, rtol=0, atol=1e-9)
    # The CSV holds 13 significant digits; the same model stepped through the same inputs.
    assert np.allclose(cpp[:, 1], pitch, rtol=1e-11, atol=1e-15)
    assert np.allclose(cpp[:, 2], yaw, rtol=1e-11, atol=1e-15)


def test_given_the_report_sample_when_run_in_float32_then_it_follows_float64():
    _, p64, y64 = report_sample.run(gyro.GyroModel)
    _, p32, y32 = report_sample.run(gyro.GyroModelF32)
    assert len(p32) == len(p64)
    err = max(np.abs(p32 - p64).max(), np.abs(y32 - y64).max())
    assert 0 < err < 1e-4 * max(np.abs(p64).max(), np.abs(y64).max())
