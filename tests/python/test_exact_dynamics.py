"""The exact rotor step from Python: one state against a batch, and against an independent
reference (a fine fourth-order Runge-Kutta integration of eqs 1a/1b written in NumPy)."""

import numpy as np
import pytest

import gyro

REPORT = gyro.RotorParameters.from_spin(2.25, 2.0, 5.0, 100.0, 3.0)  # the report's sample gyro
REGIMES = {
    "underdamped": REPORT,
    "overdamped": gyro.RotorParameters(2.25, 0.0225, 400.0, 10.0),  # J2 = J1/100, f far above critical
    "free": gyro.RotorParameters(1.0, 2.0, 0.0, 0.0),  # f = H = 0: the torque accelerates the gimbals
}


def rk4_reference(p, dt, states, torques, substeps=2000):
    """theta' = w1, psi' = w2, J1 w1' = T1 - f w1 - H w2, J2 w2' = T2 - f w2 + H w1, by RK4."""
    j1, j2, f, h = p.pitch_inertia, p.yaw_inertia, p.friction, p.angular_momentum

    def rhs(x):
        w1, w2 = x[:, 2], x[:, 3]
        return np.stack([w1, w2, (torques[:, 0] - f * w1 - h * w2) / j1, (torques[:, 1] - f * w2 + h * w1) / j2], axis=1)

    x = states.copy()
    step = dt / substeps
    for _ in range(substeps):
        k1 = rhs(x)
        k2 = rhs(x + 0.5 * step * k1)
        k3 = rhs(x + 0.5 * step * k2)
        k4 = rhs(x + step * k3)
        x = x + step / 6.0 * (k1 + 2 * k2 + 2 * k3 + k4)
    return x


def random_batch(n, dtype=np.float64, seed=3):
    rng = np.random.default_rng(seed)
    states = rng.normal(scale=[1e-3, 1e-3, 0.5, 0.5], size=(n, 4)).astype(dtype)
    torques = rng.normal(scale=10.0, size=(n, 2)).astype(dtype)
    return states, torques


@pytest.mark.parametrize("dtype", [np.float64, np.float32])
def test_given_a_batch_when_advanced_then_each_row_equals_the_single_state_step_bit_for_bit(dtype):
    tr = gyro.make_transition(REPORT, 1.0 / 2828.0, dtype=dtype)
    states, torques = random_batch(257, dtype)
    batch = gyro.advance(tr, states, torques)
    assert batch.dtype == dtype and batch.shape == (257, 4)
    for i in range(len(states)):
        single = gyro.advance(tr, states[i], torques[i])
        assert single.dtype == dtype
        assert single.tobytes() == batch[i].tobytes(), f"row {i}"


@pytest.mark.parametrize("regime", sorted(REGIMES))
def test_given_each_damping_regime_when_a_batch_is_advanced_then_it_matches_a_fine_rk4_reference(regime):
    p = REGIMES[regime]
    dt = 1.0 / 2828.0
    assert gyro.compute_modes(p)["regime"] == regime
    states, torques = random_batch(64)
    got = gyro.advance(gyro.make_transition(p, dt), states, torques)
    want = rk4_reference(p, dt, states, torques)
    scale = np.abs(want).max(axis=0) + 1e-300
    assert np.max(np.abs(got - want) / scale) < 1e-11


def test_given_a_batch_in_float32_when_advanced_then_it_agrees_with_float64_to_float_precision():
    dt = 1.0 / 2828.0
    states, torques = random_batch(100)
    f64 = gyro.advance(gyro.make_transition(REPORT, dt), states, torques)
    f32 = gyro.advance(gyro.make_transition(REPORT, dt, dtype=np.float32), states.astype(np.float32),
                       torques.astype(np.float32))
    scale = np.abs(f64).max(axis=0)
    err = np.max(np.abs(f32 - f64) / scale)
    assert 0 < err < 1e-5  # float32 computes in float: not the float64 result rounded after the fact


def test_given_one_torque_for_a_batch_when_advanced_then_every_row_gets_it():
    tr = gyro.make_transition(REPORT, 1e-3)
    states, _ = random_batch(10)
    torque = np.array([3.0, -1.0])
    got = gyro.advance(tr, states, torque)
    want = gyro.advance(tr, states, np.tile(torque, (10, 1)))
    assert np.array_equal(got, want)


def test_given_per_row_parameters_when_propagated_then_each_row_equals_its_own_transition():
    states, torques = random_batch(5)
    spins = np.array([100.0, 80.0, 60.0, 40.0, 0.0])  # a spin-down, to a stopped rotor
    params = np.array([[2.25, 2.0, 5.0, gyro.angular_momentum(s, 3.0)] for s in spins])
    dts = np.array([1e-3, 2e-3, 3e-3, 4e-3, 5e-3])
    got = gyro.propagate(params, dts, states, torques)
    for i in range(5):
        p = gyro.RotorParameters(*params[i])
        want = gyro.advance(gyro.make_transition(p, dts[i]), states[i], torques[i])
        assert want.tobytes() == got[i].tobytes()


def test_given_the_steady_precession_rate_when_advanced_then_the_rates_stay():
    torque = np.array([1.5, -0.7])
    w = gyro.steady_precession_rate(REPORT, torque)
    state = np.array([0.0, 0.0, w[0], w[1]])
    out = gyro.advance(gyro.make_transition(REPORT, 0.01), state, torque)
    assert np.allclose(out[2:], w, rtol=1e-12, atol=0)
    assert np.allclose(out[:2], 0.01 * w, rtol=1e-9, atol=0)


def test_given_a_non_positive_step_when_making_a_transition_then_status_error_names_it():
    with pytest.raises(gyro.StatusError) as e:
        gyro.make_transition(REPORT, 0.0)
    assert e.value.status == gyro.Status.NON_POSITIVE_STEP
    assert "time step" in str(e.value)
    with pytest.raises(gyro.StatusError) as e:
        gyro.make_transition(gyro.RotorParameters(-1.0, 2.0, 0.0, 1.0), 1e-3)
    assert e.value.status == gyro.Status.NON_POSITIVE_INERTIA


def test_given_a_nan_row_when_advanced_then_the_error_names_the_row_and_status_keeps_it_unchanged():
    tr = gyro.make_transition(REPORT, 1e-3)
    states, torques = random_batch(6)
    states[3, 2] = np.nan
    with pytest.raises(gyro.StatusError, match="row 3") as e:
        gyro.advance(tr, states, torques)
    assert e.value.status == gyro.Status.NON_FINITE_INPUT
    out, status = gyro.advance(tr, states, torques, return_status=True)
    assert list(status) == [0, 0, 0, int(gyro.Status.NON_FINITE_INPUT), 0, 0]
    assert np.array_equal(out[3], states[3], equal_nan=True)
    assert np.array_equal(out[[0, 1, 2, 4, 5]], gyro.advance(tr, states[[0, 1, 2, 4, 5]], torques[[0, 1, 2, 4, 5]]))


def test_given_a_wrong_shape_when_advanced_then_value_error():
    tr = gyro.make_transition(REPORT, 1e-3)
    with pytest.raises(ValueError, match="state"):
        gyro.advance(tr, np.zeros((3, 5)), np.zeros(2))
    with pytest.raises(ValueError, match="torque"):
        gyro.advance(tr, np.zeros((3, 4)), np.zeros((2, 2)))
