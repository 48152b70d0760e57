#!/usr/bin/python3
"""Writes scenarios/trajectory_spinning.csv: a projectile spinning at 12 rad/s that pulls up
and then turns left, for scenarios/trajectory_spinning.json (docs/scenarios.md).

The rates are analytic: roll p = 12 rad/s; pitch and yaw turns Q(t), R(t) of a non-rolling
frame (sin^2 bumps), seen in the rolling body as q = Q cos(phi) + R sin(phi),
r = -Q sin(phi) + R cos(phi), phi = p t. The attitude (a unit quaternion body to earth,
scalar first) is integrated from them with RK4 at 1e-5 s (global error about 1e-15 rad),
independently of gyro_sil's interpolation, and written every 2 ms. The specific force is
drag along -x and the lift that turns the body, V (Q, R) / g at V = 300 m/s, in body axes.

Usage: scripts/trajectory-spinning.py [OUT.csv]
"""
import sys

import numpy as np

SPIN = 12.0        # rad/s
SPEED = 300.0      # m/s
G = 9.80665        # m/s^2 (the scenario's gyro.gravity)
DRAG_G = -0.3      # fx, units of g
END_S = 1.6
OUT_STEP_S = 0.002
RK4_STEP_S = 1e-5
START_PITCH = 0.2  # rad, nose up (3-2-1 Euler, earth to body)


def bump(t, a, b):
    return np.where((t >= a) & (t <= b), np.sin(np.pi * (t - a) / (b - a)) ** 2, 0.0)


def turn(t):
    """Non-rolling (Q, R) in rad/s: a pull-up, then a turn to the left."""
    return 0.2 * bump(t, 0.3, 0.9), -0.15 * bump(t, 0.8, 1.4)


def body_rates(t):
    q_nr, r_nr = turn(t)
    phi = SPIN * t
    c, s = np.cos(phi), np.sin(phi)
    return np.array([SPIN, c * q_nr + s * r_nr, -s * q_nr + c * r_nr])


def specific_force(t):
    q_nr, r_nr = turn(t)
    fy_nr, fz_nr = SPEED * r_nr / G, -SPEED * q_nr / G
    phi = SPIN * t
    c, s = np.cos(phi), np.sin(phi)
    return np.array([DRAG_G, c * fy_nr + s * fz_nr, -s * fy_nr + c * fz_nr])


def quat_mul(a, b):
    w1, x1, y1, z1 = a
    w2, x2, y2, z2 = b
    return np.array([w1 * w2 - x1 * x2 - y1 * y2 - z1 * z2, w1 * x2 + x1 * w2 + y1 * z2 - z1 * y2,
                     w1 * y2 - x1 * z2 + y1 * w2 + z1 * x2, w1 * z2 + x1 * y2 - y1 * x2 + z1 * w2])


def q_dot(q, t):
    """d/dt q_body_to_earth = q (x) (0, w_body) / 2."""
    return 0.5 * quat_mul(q, np.concatenate(([0.0], body_rates(t))))


def main():
    out = sys.argv[1] if len(sys.argv) > 1 else "scenarios/trajectory_spinning.csv"
    # Body to earth at t = 0: the inverse of the pitch rotation, i.e. a rotation by +pitch about y.
    q = np.array([np.cos(START_PITCH / 2), 0.0, np.sin(START_PITCH / 2), 0.0])
    per_out = int(round(OUT_STEP_S / RK4_STEP_S))
    rows = []
    n_out = int(round(END_S / OUT_STEP_S))
    for k in range(n_out + 1):
        t = k * OUT_STEP_S
        rows.append((t, q.copy(), body_rates(t), specific_force(t)))
        if k == n_out:
            break
        for j in range(per_out):
            tj = t + j * RK4_STEP_S
            h = RK4_STEP_S
            k1 = q_dot(q, tj)
            k2 = q_dot(q + 0.5 * h * k1, tj + 0.5 * h)
            k3 = q_dot(q + 0.5 * h * k2, tj + 0.5 * h)
            k4 = q_dot(q + h * k3, tj + h)
            q = q + h / 6 * (k1 + 2 * k2 + 2 * k3 + k4)
            q /= np.linalg.norm(q)
    with open(out, "w", encoding="ascii") as f:
        f.write("t_s,qw,qx,qy,qz,p_rad_s,q_rad_s,r_rad_s,fx,fy,fz\n")
        for t, qq, w, fs in rows:
            f.write(",".join(f"{v:.15g}" for v in (t, *qq, *w, *fs)) + "\n")
    print(f"{out}: {len(rows)} rows, {END_S} s every {OUT_STEP_S} s")


if __name__ == "__main__":
    main()
