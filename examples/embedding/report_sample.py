"""The report's sample run (its driver GYMAIN, every error fixed) from Python: gyro.GyroModel.
Prints the gimbal angles after the last step.
    PYTHONPATH=<build>/python python3 report_sample.py"""
import gyro
import numpy as np

sample = gyro.report_sample
model = gyro.GyroModel(sample.CONFIG)
dt = sample.initg_step()
# The body turns about its own pitch axis, then its yaw axis, every step.
pitch_rate, yaw_rate = sample.BODY_PITCH_RATE, sample.BODY_YAW_RATE
turn = gyro.frame_rotation_z(yaw_rate * dt) @ gyro.frame_rotation_y(pitch_rate * dt)
body = np.eye(3)
model.uncage(body, [pitch_rate, yaw_rate])
steps = 0
while steps < sample.STEPS and not model.flags:
    body = turn @ body  # the body's attitude at the step's end
    model.step_slew(dt, sample.SLEW, spin_hz=sample.SPIN_HZ, R_earth_to_body=body)  # raises if refused
    steps += 1
pitch, yaw = model.gimbal
print(f"report sample: {steps} steps, gimbal pitch {pitch:.12e} yaw {yaw:.12e} rad")
