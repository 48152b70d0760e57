"""The report's sample run (GYMAIN with INITG) driven through gyro.GyroModel from Python, as
examples/include/gyro/report_sample.hpp drives it in C++ (gyro_report_sample): spin 100 Hz,
f = 5, J0 = 3, J1 = 2.25, J2 = 2 slug ft^2, the body turning at 2.3 and 1.8 times 10 deg/s in
pitch and yaw, slew command (-0.19, 0.013) rad/s limited to 10 deg/s, step 1/floor(20 x
nutation Hz), 801 steps. Its gimbal angles are the report's figures A-1 and A-2."""

import math

import numpy as np

from . import _gyro as gyro

DEG_PER_SECOND = 0.1745329  # the listing's 10 deg/s
SPIN_HZ = 100.0
BODY_PITCH_RATE = 2.3 * DEG_PER_SECOND
BODY_YAW_RATE = 1.8 * DEG_PER_SECOND
STEPS = 801
CONFIG = dict(pitch_inertia=2.25, yaw_inertia=2.0, spin_inertia=3.0, friction=5.0, gimbal_cone_limit_rad=0.4363323,
              max_pitch_rate_rad_s=DEG_PER_SECOND, max_yaw_rate_rad_s=DEG_PER_SECOND, gravity=32.1725)
SLEW = (-0.19, 0.013)


def initg_step():
    """INITG's step: 1/floor(20 x nutation Hz)."""
    p = gyro.RotorParameters.from_spin(2.25, 2.0, 5.0, SPIN_HZ, 3.0)
    return 1.0 / math.floor(20.0 * gyro.compute_modes(p)["nutation_hz"])


def run(model_class=None, steps=STEPS):
    """Time t, gimbal pitch and yaw (rad) after each step, as arrays; stops on a flag as the
    report's driver does. model_class: gyro.GyroModel (default) or gyro.GyroModelF32."""
    model_class = model_class or gyro.GyroModel
    dt = initg_step()
    g = model_class(CONFIG)
    r_eb = np.eye(3)
    g.uncage(r_eb, [BODY_PITCH_RATE, BODY_YAW_RATE])
    turn = gyro.frame_rotation_z(BODY_YAW_RATE * dt) @ gyro.frame_rotation_y(BODY_PITCH_RATE * dt)
    t, pitch, yaw = [], [], []
    for k in range(steps):
        r_eb = turn @ r_eb
        g.step_slew(dt, SLEW, spin_hz=SPIN_HZ, R_earth_to_body=r_eb)
        t.append((k + 1) * dt)
        pitch.append(g.gimbal_pitch)
        yaw.append(g.gimbal_yaw)
        if g.flags:
            break
    return np.array(t), np.array(pitch), np.array(yaw)
