#!/usr/bin/env python3
"""The report's figures A-1 (gyro pitch gimbal angle) and A-2 (gyro yaw gimbal angle) from the
sample run (100 Hz spin, f = 5 slug ft^2/s): the rapid nutation riding on the slow precession.

    python3 examples/report_figures.py --output-dir figures/

Writes figure_a1_pitch.png and figure_a2_yaw.png (float64, with the float32 model overlaid).
Needs the module on PYTHONPATH (<build>/python, or installed) and matplotlib.
"""

import argparse
import math

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

import gyro  # noqa: E402
from figure_files import save_figure  # noqa: E402


def figure(t, angle_rad, angle32_rad, title, label):
    """One of the report's plots: the gimbal angle in degrees against time."""
    fig, ax = plt.subplots(figsize=(8, 5))
    ax.plot(t, [math.degrees(a) for a in angle_rad], lw=1.0, color="#1f4e9c", label="GyroModel (float64)")
    ax.plot(t, [math.degrees(a) for a in angle32_rad], lw=0.8, ls="--", color="#d62728", label="GyroModelF32")
    ax.set_xlabel("time (s)")
    ax.set_ylabel(f"{label} gimbal angle (deg)")
    ax.set_title(title)
    ax.grid(True, alpha=0.3)
    ax.legend()
    fig.tight_layout()
    return fig


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--output-dir", required=True, help="directory the PNG files are written to")
    args = parser.parse_args()
    t, pitch, yaw = gyro.report_sample.run()
    _, pitch32, yaw32 = gyro.report_sample.run(gyro.GyroModelF32)
    n = min(len(t), len(pitch32))
    for name, title, label, a, a32 in (
            ("figure_a1_pitch.png", "Figure A-1. Gyro pitch gimbal angle", "pitch", pitch, pitch32),
            ("figure_a2_yaw.png", "Figure A-2. Gyro yaw gimbal angle", "yaw", yaw, yaw32)):
        fig = figure(t[:n], a[:n], a32[:n], title, label)
        print(save_figure(fig, f"{args.output_dir}/{name}"))
        plt.close(fig)


if __name__ == "__main__":
    main()
