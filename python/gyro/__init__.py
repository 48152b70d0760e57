"""gyro: exact two-axis gimballed gyro dynamics and the flight component's models, from Python.

Exact dynamics:   RotorParameters, make_transition, advance, propagate (one state or an
                  (n, 4) batch of states (theta, psi, theta', psi')), compute_modes.
Models:           GyroModel / GyroModelF32, GimbalPlant / GimbalPlantF32 (float64 / float32).
Flight loop:      SimulatedGyro, GyroComponent, SilLoop (and their F32 twins): the component
                  closed around a body and a guidance of one's own.
Runs:             run_sil (a scenario file or dict -> SilRun), run_campaign (-> CampaignRun);
                  read_scenario (a scenario as flown, its example or base expanded).
Examples:         examples.seeker(), examples.report(): the example gyros' configurations,
                  as each constructor takes them.
Report sample:    report_sample.run() (figures A-1, A-2 of the report).
Refusals:         ConfigError (.field), StatusError (.status), ScenarioError (.field, .file).

See docs/python.md.
"""

from . import errors, examples, report_sample
from ._gyro import (
    DEFAULT_MAX_OUTPUT_BYTES,
    FLAG_GIMBAL_LIMIT,
    FLAG_SMALL_ANGLE,
    GimbalPlant,
    GimbalPlantF32,
    GyroComponent,
    GyroComponentF32,
    GyroModel,
    GyroModelF32,
    MAX_THREADS,
    RotorParameters,
    SilLoop,
    SilLoopF32,
    SimulatedGyro,
    SimulatedGyroF32,
    Status,
    Transition,
    TransitionF32,
    advance,
    angular_momentum,
    component_flag_names,
    compute_modes,
    frame_rotation_y,
    frame_rotation_z,
    make_transition,
    propagate,
    read_scenario,
    sil_columns,
    status_text,
    steady_precession_rate,
)
from ._gyro import _run_campaign, _run_sil
from .errors import ConfigError, GyroError, RunError, ScenarioError, StatusError
from .results import CampaignRun, SilRun

__all__ = [
    "DEFAULT_MAX_OUTPUT_BYTES", "MAX_THREADS", "FLAG_GIMBAL_LIMIT", "FLAG_SMALL_ANGLE", "GimbalPlant", "GimbalPlantF32", "GyroComponent", "GyroComponentF32", "GyroModel", "GyroModelF32",
    "SilLoop", "SilLoopF32", "SimulatedGyro", "SimulatedGyroF32",
    "RotorParameters", "Status", "Transition", "TransitionF32", "advance", "angular_momentum",
    "component_flag_names", "compute_modes", "frame_rotation_y", "frame_rotation_z", "make_transition",
    "propagate", "read_scenario", "sil_columns", "status_text", "steady_precession_rate", "run_sil", "run_campaign",
    "ConfigError", "GyroError", "RunError", "ScenarioError", "StatusError", "CampaignRun", "SilRun", "errors", "examples", "report_sample",
]


def run_sil(scenario, *, precision=None, ticks=None, max_output_bytes=DEFAULT_MAX_OUTPUT_BYTES, trajectory=None):
    """Runs a SIL scenario as gyro_sil does and returns its time history.

    scenario: a scenario file (str or os.PathLike) or a dict with a scenario's contents
    (docs/scenarios.md). precision: 'float' or 'double' overrides run.precision; ticks
    overrides the run's length. trajectory: the body's recorded motion as a dict of column
    name to a 1-D array (the columns of a body.trajectory file: t_s, qw, qx, qy, qz or
    roll_rad, pitch_rad, yaw_rad, p_rad_s, q_rad_s, r_rad_s, fx, fy, fz), for a scenario whose
    body.trajectory has no file; checked as a file's rows are (a refusal names column[index]).
    max_output_bytes: a run whose output could be larger (gyro_sil's
    bound of its CSV, (ticks + 1) rows at their widest) is refused with a ValueError before it
    starts; the default is gyro_sil's --max-output-bytes default, DEFAULT_MAX_OUTPUT_BYTES (1 GiB).
    Returns a SilRun (columns keyed by the CSV's names, and the component's telemetry).
    Raises ScenarioError (naming the JSON field) or RunError. Ctrl-C raises KeyboardInterrupt
    within about 20 ms (and one tick).
    """
    columns, telemetry = _run_sil(scenario, precision, ticks, max_output_bytes, trajectory)
    return SilRun(columns=columns, telemetry=telemetry)


def run_campaign(campaign, *, runs=None, threads=1, base_dir=None):
    """Runs a Monte Carlo campaign as gyro_campaign does and returns its per-run table.

    campaign: a campaign file or a dict (docs/campaigns.md); a dict's base scenario path is
    read relative to base_dir (default: the current directory). runs: run only the first
    `runs` runs (their rows are those of the full campaign). threads: worker threads, 1 to
    MAX_THREADS (1024, gyro_campaign -j's bound). Returns a CampaignRun. Raises ScenarioError
    for a refused campaign. Ctrl-C raises KeyboardInterrupt once the runs under way have
    finished (a run's work at most); no new run starts.
    """
    header, columns = _run_campaign(campaign, runs, threads, None if base_dir is None else str(base_dir))
    return CampaignRun(header=list(header), columns=columns)
