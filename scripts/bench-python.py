#!/usr/bin/env python3
"""Speed of the Python module (docs/performance.md, "Python"): the vectorised exact step in
states per second next to the same step written in NumPy, and the cost per call of a Python
loop over GyroModel.step_torque. Prints the figures; asserts nothing.

    PYTHONPATH=build/host/python /usr/bin/python3 scripts/bench-python.py [--repeat 7]
"""

import argparse
import time

import numpy as np

import gyro

REPORT = gyro.RotorParameters.from_spin(2.25, 2.0, 5.0, 100.0, 3.0)
DT = 1.0 / 2828.0


def best_of(repeat, f):
    """The shortest of `repeat` timings of f() (s)."""
    best = float("inf")
    for _ in range(repeat):
        t0 = time.perf_counter()
        f()
        best = min(best, time.perf_counter() - t0)
    return best


def numpy_step(tr):
    """The same exact step in NumPy: x' = A x + B T with the transition's four blocks."""
    a = np.eye(4)
    a[0:2, 2:4] = tr.angle_from_rate
    a[2:4, 2:4] = tr.rate_from_rate
    b = np.vstack([tr.angle_from_torque, tr.rate_from_torque])
    return lambda s, t: s @ a.T + t @ b.T


def vectorised(repeat):
    for dtype in (np.float64, np.float32):
        tr = gyro.make_transition(REPORT, DT, dtype=dtype)
        step = numpy_step(tr)
        for n in (10_000, 1_000_000):
            rng = np.random.default_rng(1)
            s = rng.normal(size=(n, 4)).astype(dtype)
            t = rng.normal(size=(n, 2)).astype(dtype)
            g = best_of(repeat, lambda: gyro.advance(tr, s, t))
            p = best_of(repeat, lambda: step(s, t))
            print(f"advance {np.dtype(dtype).name:7s} n = {n:>9,d}: gyro {n / g / 1e6:7.1f} M states/s, "
                  f"numpy {n / p / 1e6:6.1f} M states/s ({p / g:.1f}x)")


def per_call(repeat, n=20_000):
    cfg = dict(gyro.report_sample.CONFIG)
    for cls in (gyro.GyroModel, gyro.GyroModelF32):
        g = cls(cfg)
        g.uncage(body_rate=[0.4, 0.3])
        torque = np.array([1.0, -2.0])
        r = np.eye(3)

        def loop_torque():
            for _ in range(n):
                g.step_torque(DT, torque, spin_hz=100.0)

        def loop_full():
            for _ in range(n):
                g.step_torque(DT, torque, spin_hz=100.0, R_earth_to_body=r)

        def loop_read():
            for _ in range(n):
                g.flags

        def loop_empty():
            for _ in range(n):
                pass

        e = best_of(repeat, loop_empty)
        a = best_of(repeat, loop_torque) - e
        b = best_of(repeat, loop_full) - e
        c = best_of(repeat, loop_read) - e
        print(f"{cls.__name__:12s} step_torque(dt, torque, spin_hz=) {a / n * 1e6:5.2f} us/call; "
              f"with R_earth_to_body= {b / n * 1e6:5.2f} us/call; a property read {c / n * 1e6:5.2f} us")


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeat", type=int, default=7)
    args = parser.parse_args()
    vectorised(args.repeat)
    per_call(args.repeat)


if __name__ == "__main__":
    main()
