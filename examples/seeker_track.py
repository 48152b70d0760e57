#!/usr/bin/env python3
"""The flight component closed around a body and a guidance of one's own: a rolling, coning
airframe whose seeker gyro tracks a target crossing the sky.

The body (attitude integrated here, tick by tick) rolls at 4 rad/s and cones at 2 Hz; the
guidance points the spin axis at the target from the component's own estimate of the gimbal
angles: the target's line-of-sight rate as a feed-forward plus a gain on the pointing error,
both on the inner gimbal axes (docs/conventions.md). gyro.SimulatedGyro, gyro.GyroComponent and
gyro.SilLoop are the loop gyro_sil runs (docs/python.md), configured with the seeker example
(gyro.examples.seeker()).

    python3 examples/seeker_track.py --output-dir figures/ [--precision float]

Writes seeker_track.png and prints the pointing error; exits with status 1 if the track is
not held within 5 mrad after it settles.
"""

import argparse
import math
import pathlib

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

import gyro  # noqa: E402
from figure_files import save_figure  # noqa: E402

DURATION_S = 2.0
UNCAGE_S = 0.2
ROLL_RAD_S = 4.0
CONING_RAD_S, CONING_HZ = 0.2, 2.0
LOS_RATE_RAD_S = np.array([0.0, 0.05, 0.12])  # the target's line of sight turns about this (earth axes)
TARGET_EARTH = np.array([math.cos(0.08), 0.0, -math.sin(0.08)])  # 80 mrad above the body's x at t = 0
TRACK_GAIN_1_S = 12.0
SETTLED_S = 0.6  # after uncaging, the pointing error is judged from here
LIMIT_RAD = 5e-3


def rotation(vector):
    """The matrix of the active rotation by a rotation vector (Rodrigues)."""
    angle = float(np.linalg.norm(vector))
    if angle == 0.0:
        return np.eye(3)
    k = vector / angle
    kx = np.array([[0.0, -k[2], k[1]], [k[2], 0.0, -k[0]], [-k[1], k[0], 0.0]])
    return np.eye(3) + math.sin(angle) * kx + (1.0 - math.cos(angle)) * kx @ kx


class Body:
    """A rolling, coning airframe: body rates (p, q, r), attitude R_earth_to_body."""

    def __init__(self, tick_s):
        self.tick_s = tick_s
        self.t = 0.0
        self.R_earth_to_body = np.eye(3)

    def rate(self, t):
        a = 2.0 * math.pi * CONING_HZ * t
        return np.array([ROLL_RAD_S, CONING_RAD_S * math.sin(a), CONING_RAD_S * math.cos(a)])

    def advance(self):
        mean = self.rate(self.t + 0.5 * self.tick_s)  # the mid-tick rate
        self.t += self.tick_s
        # The body turns by +w dt: body components of fixed vectors turn by -w dt.
        self.R_earth_to_body = rotation(mean * self.tick_s).T @ self.R_earth_to_body


def inner_gimbal_axes(gimbal):
    """The spin axis x and the inner gimbal axes y_I, z_I in body axes at gimbal (pitch, yaw)."""
    cp, sp, cy, sy = math.cos(gimbal[0]), math.sin(gimbal[0]), math.cos(gimbal[1]), math.sin(gimbal[1])
    return (np.array([cp * cy, cp * sy, -sp]), np.array([-sy, cy, 0.0]), np.array([sp * cy, sp * sy, cp]))


def guidance(t, body, gimbal_estimate):
    """The slew command (pitch, yaw) rad/s: line-of-sight rate plus a gain on the pointing error."""
    target_earth = rotation(LOS_RATE_RAD_S * t) @ TARGET_EARTH
    target = body.R_earth_to_body @ target_earth
    los_rate = body.R_earth_to_body @ LOS_RATE_RAD_S
    _, y_i, z_i = inner_gimbal_axes(gimbal_estimate)
    # A rate about y_I moves the spin axis toward -z_I, one about z_I toward +y_I.
    return np.array([los_rate @ y_i - TRACK_GAIN_1_S * (target @ z_i), los_rate @ z_i + TRACK_GAIN_1_S * (target @ y_i)])


def pointing_error(t, body, gimbal):
    """The true angle between the spin axis and the target (rad)."""
    x, _, _ = inner_gimbal_axes(gimbal)
    target = body.R_earth_to_body @ rotation(LOS_RATE_RAD_S * t) @ TARGET_EARTH
    return math.acos(min(1.0, float(x @ target)))


def fly(precision):
    example = gyro.examples.seeker()
    f32 = precision == "float"
    stub = (gyro.SimulatedGyroF32 if f32 else gyro.SimulatedGyro)(example.tick_s, **example.gyro)
    component = (gyro.GyroComponentF32 if f32 else gyro.GyroComponent)(stub, example.tick_s, **example.component)
    loop = (gyro.SilLoopF32 if f32 else gyro.SilLoop)(stub, component)
    body = Body(example.tick_s)
    assert loop.start(R_earth_to_body=body.R_earth_to_body, body_rate=body.rate(0.0)) == gyro.Status.OK
    ticks = round(DURATION_S / example.tick_s)
    history = {"t": [], "error": [], "pitch": [], "yaw": [], "mode": []}
    slew = np.zeros(2)
    for k in range(ticks + 1):
        if k > 0:
            body.advance()
        status = loop.tick(k, R_earth_to_body=body.R_earth_to_body, body_rate=body.rate(body.t),
                           request="uncage" if k == round(UNCAGE_S / example.tick_s) else None, slew_rate=slew)
        assert status in (gyro.Status.OK, gyro.Status.INPUT_IGNORED), status
        tm = component.telemetry
        slew = guidance(body.t, body, tm["gimbal_predicted_rad"]) if tm["mode"] == "free" else np.zeros(2)
        history["t"].append(body.t)
        history["error"].append(pointing_error(body.t, body, stub.gimbal_angle))
        history["pitch"].append(stub.gimbal_angle[0])
        history["yaw"].append(stub.gimbal_angle[1])
        history["mode"].append(tm["mode"])
    return {k: np.array(v) for k, v in history.items()}


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--output-dir", required=True, help="directory the PNG file is written to")
    parser.add_argument("--precision", choices=("double", "float"), default="double")
    args = parser.parse_args()
    h = fly(args.precision)
    settled = h["t"] >= UNCAGE_S + SETTLED_S
    worst = float(h["error"][settled].max())
    print(f"pointing error after {UNCAGE_S + SETTLED_S:.1f} s: largest {worst * 1e3:.3f} mrad, "
          f"mean {h['error'][settled].mean() * 1e3:.3f} mrad; final mode {h['mode'][-1]}")

    fig, (a1, a2) = plt.subplots(2, 1, figsize=(9, 6), sharex=True)
    a1.semilogy(h["t"], np.maximum(h["error"], 1e-7), lw=1)
    a1.axhline(LIMIT_RAD, color="r", ls="--", label=f"{LIMIT_RAD * 1e3:g} mrad")
    a1.axvline(UNCAGE_S, color="g", ls=":", label="uncage")
    a1.set_ylabel("pointing error (rad)")
    a1.legend()
    a2.plot(h["t"], h["pitch"], label="gimbal pitch")
    a2.plot(h["t"], h["yaw"], label="gimbal yaw")
    a2.set_xlabel("t (s)")
    a2.set_ylabel("rad")
    a2.legend()
    fig.suptitle(f"Seeker gyro tracking a crossing target from a body rolling at {ROLL_RAD_S:g} rad/s ({args.precision})")
    print(save_figure(fig, pathlib.Path(args.output_dir) / "seeker_track.png"))
    plt.close(fig)
    return 0 if worst <= LIMIT_RAD and h["mode"][-1] == "free" else 1


if __name__ == "__main__":
    raise SystemExit(main())
