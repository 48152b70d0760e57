#!/usr/bin/env python3
"""A small dispersion study: the seeker slew scenario with the rotor's friction, the torquer
scale factors and the pickoff bias dispersed, run as a campaign (gyro.run_campaign, the same
runs gyro_campaign makes), and the histogram of the slew-rate error of the closed loop.

    python3 examples/dispersion_study.py --output-dir figures/ [--runs 200] [--threads 2]

Writes dispersion_slew_error.png and prints the error's percentiles.
"""

import argparse
import pathlib

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

import gyro  # noqa: E402
from figure_files import save_figure  # noqa: E402

SCENARIOS = pathlib.Path(__file__).resolve().parents[1] / "scenarios"


def campaign(runs):
    """The campaign as a dict (docs/campaigns.md): a short slew of the seeker example."""
    return {
        "description": "dispersion study of the Python example",
        "base": str(SCENARIOS / "seeker_slew.json"),
        "set": {
            "run.duration_s": 0.5,
            "guidance.schedule": [
                {"t_s": 0.0, "request": "none", "slew_rate_rad_s": [0.0, 0.0]},
                {"t_s": 0.05, "request": "uncage"},
                {"t_s": 0.15, "slew_rate_rad_s": [0.3, -0.2]},
            ],
        },
        "runs": runs,
        "seed": 11,
        "dispersions": [
            {"path": "gyro.rotor.friction", "distribution": "uniform", "min": 0.7, "max": 1.3, "apply": "scale"},
            {"path": "gyro.torquer.scale_factor[0]", "distribution": "normal", "mean": 1.0, "sd": 0.02},
            {"path": "gyro.torquer.scale_factor[1]", "distribution": "normal", "mean": 1.0, "sd": 0.02},
            {"path": "gyro.pickoff.bias_rad[0]", "distribution": "normal", "mean": 0.0, "sd": 1e-4},
        ],
        "metrics": {"slew_rate_error": {"from_s": 0.3, "to_s": 0.5}, "final_mode": True},
    }


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--output-dir", required=True, help="directory the PNG file is written to")
    parser.add_argument("--runs", type=int, default=200)
    parser.add_argument("--threads", type=int, default=2)
    args = parser.parse_args()
    result = gyro.run_campaign(campaign(args.runs), threads=args.threads)
    ok = np.array([s == "ok" for s in result["status"]])
    err = result["slew_rate_error_rad_s"][ok]
    scale = result["gyro.torquer.scale_factor[0]"][ok]
    p50, p95, p99 = np.percentile(err, [50, 95, 99])
    print(f"{ok.sum()} of {len(result)} runs ran; slew-rate error median {p50:.3e}, 95 % {p95:.3e}, "
          f"99 % {p99:.3e} rad/s")

    fig, (ax1, ax2) = plt.subplots(1, 2, figsize=(11, 4.5))
    ax1.hist(err * 1e3, bins=max(10, len(err) // 8), color="#1f4e9c")
    ax1.axvline(p95 * 1e3, color="#d62728", ls="--", label="95th percentile")
    ax1.set_xlabel("slew-rate error (mrad/s)")
    ax1.set_ylabel("runs")
    ax1.legend()
    ax2.scatter(scale, err * 1e3, s=10, color="#1f4e9c")
    ax2.set_xlabel("pitch torquer scale factor")
    ax2.set_ylabel("slew-rate error (mrad/s)")
    fig.suptitle(f"Seeker slew, {ok.sum()} dispersed runs (friction, torquer scale, pickoff bias)")
    for ax in (ax1, ax2):
        ax.grid(True, alpha=0.3)
    fig.tight_layout()
    print(save_figure(fig, pathlib.Path(args.output_dir) / "dispersion_slew_error.png"))
    plt.close(fig)


if __name__ == "__main__":
    main()
