"""Every numeric input checked for kind, shape and range (docs/python.md, "Inputs"): an empty
batch gives an empty result, a complex, string, bool or object input is refused with a
TypeError naming the argument and what it got, a wrong shape with a ValueError naming both
shapes, a float32 call refuses a value float32 cannot hold."""

import numpy as np
import pytest

import gyro
from gyro import report_sample

REPORT = gyro.RotorParameters.from_spin(2.25, 2.0, 5.0, 100.0, 3.0)
# A value of each kind that is not a real number, with a word its message must hold.
NOT_REAL = [
    pytest.param(np.array([1e-3, 0.0, 0.5, 0.0]) + 1e-9j, "complex", id="complex-array"),
    pytest.param(np.array(["1e-3", "0", "0.5", "0"]), "str", id="string-array"),
    pytest.param(["1e-3", "0", "0.5", "0"], "str", id="list-of-strings"),
    pytest.param(np.array([True, False, True, False]), "bool", id="bool-array"),
    pytest.param([True, 0.0, 0.5, 0.0], "bool", id="list-with-a-bool"),
    pytest.param(np.array([1e-3, 0.0, 0.5, 0.0], dtype=object), "object", id="object-array"),
]


# Item 1: empty batches.

@pytest.mark.parametrize("dtype", [np.float64, np.float32])
def test_given_an_empty_batch_when_advanced_then_the_result_is_an_empty_batch(dtype):
    tr = gyro.make_transition(REPORT, 1e-3, dtype=dtype)
    for torque in (np.zeros(2, dtype), np.zeros((0, 2), dtype)):
        out = gyro.advance(tr, np.zeros((0, 4), dtype), torque)
        assert out.shape == (0, 4) and out.dtype == dtype
        states, status = gyro.advance(tr, np.zeros((0, 4), dtype), torque, return_status=True)
        assert states.shape == (0, 4) and states.dtype == dtype
        assert status.shape == (0,) and status.dtype == np.uint8


def test_given_an_empty_batch_when_propagated_then_the_result_is_an_empty_batch():
    out = gyro.propagate(REPORT, 1e-3, np.zeros((0, 4)), np.zeros(2))
    assert out.shape == (0, 4)
    out = gyro.propagate(np.zeros((0, 4)), np.zeros(0), np.zeros((0, 4)), np.zeros((0, 2)))
    assert out.shape == (0, 4)
    states, status = gyro.propagate(np.zeros((0, 4)), 1e-3, np.zeros((0, 4), np.float32), np.zeros(2, np.float32),
                                    return_status=True)
    assert states.shape == (0, 4) and states.dtype == np.float32 and status.shape == (0,)


def test_given_one_row_when_advanced_as_a_batch_then_the_result_keeps_the_batch_axis():
    tr = gyro.make_transition(REPORT, 1e-3)
    state = np.array([1e-3, -2e-3, 0.5, 0.25])
    single = gyro.advance(tr, state, [1.0, 2.0])
    batch = gyro.advance(tr, state[None, :], [1.0, 2.0])
    assert single.shape == (4,) and batch.shape == (1, 4)
    assert batch[0].tobytes() == single.tobytes()


# Item 2: kinds, shapes and ranges.

@pytest.mark.parametrize("bad, word", NOT_REAL)
def test_given_a_state_that_is_not_real_numbers_when_advanced_then_type_error_names_state(bad, word):
    tr = gyro.make_transition(REPORT, 1e-3)
    with pytest.raises(TypeError) as e:
        gyro.advance(tr, bad, np.zeros(2))
    msg = str(e.value)
    assert msg.startswith("state: ") and "expected real numbers" in msg and word in msg, msg


@pytest.mark.parametrize("bad, word", NOT_REAL)
def test_given_a_batch_that_is_not_real_numbers_when_propagated_then_type_error_names_the_argument(bad, word):
    good = np.zeros((1, 4))
    with pytest.raises(TypeError, match=r"^state: .*" + word):
        gyro.propagate(REPORT, 1e-3, np.array([bad]) if not isinstance(bad, list) else [bad], np.zeros(2))
    with pytest.raises(TypeError, match=r"^params: .*" + word):
        gyro.propagate(np.array([bad]) if not isinstance(bad, list) else [bad], 1e-3, good, np.zeros(2))
    with pytest.raises(TypeError, match=r"^torque: .*" + word):
        gyro.propagate(REPORT, 1e-3, good, np.asarray(bad)[:2] if not isinstance(bad, list) else bad[:2])


@pytest.mark.parametrize("bad", [1e-3 + 0j, np.complex128(1e-3), "1e-3", True, np.bool_(True), [1e-3], None])
def test_given_a_step_that_is_not_a_real_number_when_a_transition_is_made_then_type_error_names_dt(bad):
    with pytest.raises((TypeError, ValueError), match=r"^dt: expected"):
        gyro.make_transition(REPORT, bad)


def test_given_the_imaginary_part_of_a_complex_torque_when_advanced_then_it_is_refused_not_dropped():
    tr = gyro.make_transition(REPORT, 1e-3)
    with pytest.raises(TypeError, match=r"^torque: .*complex128 \(complex numbers\)"):
        gyro.advance(tr, np.zeros(4), np.array([1.0 + 5.0j, 0.0]))
    with pytest.raises(TypeError, match=r"^torque: .*complex"):
        gyro.steady_precession_rate(REPORT, [1.0 + 5.0j, 0.0])


@pytest.mark.parametrize("shape", [(3,), (4, 3), (2, 2, 4), ()])
def test_given_a_state_of_the_wrong_shape_when_advanced_then_value_error_names_both_shapes(shape):
    tr = gyro.make_transition(REPORT, 1e-3)
    with pytest.raises(ValueError) as e:
        gyro.advance(tr, np.zeros(shape), np.zeros(2))
    msg = str(e.value)
    assert msg.startswith("state: expected shape (4,) or (n, 4), got shape "), msg
    assert str(shape).replace(" ", "").replace(",)", ",)") in msg.replace(" ", ""), msg


def test_given_torques_not_one_per_state_when_advanced_then_value_error_names_torque():
    tr = gyro.make_transition(REPORT, 1e-3)
    with pytest.raises(ValueError, match=r"^torque: expected shape \(2,\) or \(3, 2\), one row per state, got 2 rows"):
        gyro.advance(tr, np.zeros((3, 4)), np.zeros((2, 2)))
    with pytest.raises(ValueError, match=r"^torque: a batch of 2 torques needs a batch of states"):
        gyro.advance(tr, np.zeros(4), np.zeros((2, 2)))
    with pytest.raises(ValueError, match=r"^dt: expected a number or shape \(3,\)"):
        gyro.propagate(REPORT, np.full(2, 1e-3), np.zeros((3, 4)), np.zeros(2))


def test_given_values_beyond_float32_when_a_float32_call_is_made_then_value_error_not_infinity():
    tr = gyro.make_transition(REPORT, 1e-3, dtype=np.float32)
    with pytest.raises(ValueError, match=r"^state: 1e\+300 is beyond float32's range"):
        gyro.advance(tr, np.array([1e300, 0.0, 0.0, 0.0]), np.zeros(2))
    with pytest.raises(ValueError, match=r"^dt: 1e\+40 is beyond float32's range"):
        gyro.make_transition(REPORT, 1e40, dtype=np.float32)


def test_given_integers_or_numpy_scalars_when_passed_then_they_are_taken_as_numbers():
    tr = gyro.make_transition(REPORT, np.float32(1e-3))
    a = gyro.advance(tr, np.array([0, 0, 1, 0], dtype=np.int64), (np.int32(1), 2))
    b = gyro.advance(tr, [0.0, 0.0, 1.0, 0.0], [1.0, 2.0])
    assert a.tobytes() == b.tobytes()


@pytest.mark.parametrize("cls", [gyro.GyroModel, gyro.GyroModelF32])
def test_given_bad_kinds_when_a_gyro_model_is_stepped_then_type_error_names_the_argument(cls):
    g = cls(report_sample.CONFIG)
    g.uncage()
    cases = [
        (dict(dt=True, torque=[0.0, 0.0]), "dt"),
        (dict(dt="1e-3", torque=[0.0, 0.0]), "dt"),
        (dict(dt=1e-3, torque=[1j, 0.0]), "torque"),
        (dict(dt=1e-3, torque=["1", "0"]), "torque"),
        (dict(dt=1e-3, torque=[0.0, 0.0], R_earth_to_body=np.eye(3, dtype=complex)), "R_earth_to_body"),
        (dict(dt=1e-3, torque=[0.0, 0.0], body_rate=np.array(["0", "0", "0"])), "body_rate"),
        (dict(dt=1e-3, torque=[0.0, 0.0], body_accel=[False, True]), "body_accel"),
    ]
    before = g.gimbal.tobytes()
    for kwargs, name in cases:
        dt = kwargs.pop("dt")
        torque = kwargs.pop("torque")
        with pytest.raises(TypeError, match="^" + name + ": expected real numbers"):
            g.step_torque(dt, torque, spin_hz=100.0, **kwargs)
    with pytest.raises(TypeError, match="^spin_hz: expected real numbers"):
        g.step_torque(1e-3, [0.0, 0.0], spin_hz=100 + 0j)
    with pytest.raises(ValueError, match=r"^R_earth_to_body: expected shape \(3, 3\), got shape \(3,\)"):
        g.step_torque(1e-3, [0.0, 0.0], spin_hz=100.0, R_earth_to_body=np.zeros(3))
    with pytest.raises(TypeError, match="^slew_rate: expected real numbers"):
        g.step_slew(1e-3, np.array([1j, 0]), spin_hz=100.0)
    assert g.gimbal.tobytes() == before  # nothing stepped


@pytest.mark.parametrize("value, word", [(1 + 2j, "complex"), (np.complex128(5.0), "complex128"), ("5.0", "str"),
                                         (np.bool_(True), "bool")])
def test_given_a_config_value_that_is_not_a_real_number_then_config_error_names_the_field(value, word):
    with pytest.raises(gyro.ConfigError) as e:
        gyro.GyroModel(report_sample.CONFIG, friction=value)
    assert e.value.field == "friction"
    assert "expected real numbers" in str(e.value) and word in str(e.value)


def test_given_bad_kinds_when_the_gimbal_plant_is_driven_then_type_error_names_the_argument():
    with pytest.raises(TypeError, match="^tick_s: expected real numbers"):
        gyro.GimbalPlant(1e-3 + 0j)
    with pytest.raises(TypeError, match="^pitch_inertia: expected real numbers"):
        gyro.RotorParameters("2.25", 2.0)
    p = gyro.RotorParameters(2.25, 2.0)
    with pytest.raises(TypeError, match="^friction: expected real numbers"):
        p.friction = 1j
    assert p.friction == 0.0
    with pytest.raises(TypeError, match="^angle: expected real numbers"):
        gyro.frame_rotation_y(True)
