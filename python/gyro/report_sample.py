"""The report's sample run (GYMAIN with INITG) driven through gyro.GyroModel from Python, as
examples/include/gyro/report_sample.hpp drives it in C++ (gyro_report_sample), with that
header's gyro, body rates, slew command, INITG step and step count. Its gimbal angles are the
report's figures A-1 and A-2."""

import numpy as np

from . import _gyro as gyro

# The sample's parameters are the C++ ones (gyro/report_sample.hpp), not retyped here.
_SAMPLE = gyro._report_sample  # pylint: disable=protected-access
SPIN_HZ = _SAMPLE["spin_hz"]
BODY_PITCH_RATE, BODY_YAW_RATE = _SAMPLE["body_rates"]
STEPS = _SAMPLE["steps"]
CONFIG = _SAMPLE["config"]
SLEW = _SAMPLE["slew"]


def initg_step():
    """INITG's step: 1/floor(20 x nutation Hz)."""
    return _SAMPLE["initg_step"]


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
