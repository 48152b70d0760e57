"""SIL runs from Python against gyro_sil: the same scenario gives the same CSV columns (every
cell formatted as gyro_sil formats it), from a file or a dict, in double and float."""

import csv
import json
import subprocess
import time

import numpy as np
import pytest

import gyro


def gyro_sil_csv(gyro_sil, scenario, tmp_path, *extra):
    out = tmp_path / "run.csv"
    subprocess.run([str(gyro_sil), str(scenario), "-o", str(out), "--quiet", *extra], check=True)
    with open(out, newline="") as f:
        reader = csv.reader(f)
        header = next(reader)
        rows = list(reader)
    return header, rows


def cell_text(v):
    """A value as gyro_sil writes it (%.9e for numbers, integers and names as they are)."""
    if isinstance(v, (float, np.floating)):
        return "%.9e" % v
    return str(v)


def assert_same_as_csv(run, header, rows):
    assert list(run.keys()) == header == gyro.sil_columns()
    assert len(run) == len(rows)
    for j, name in enumerate(header):
        col = run[name]
        got = [cell_text(v) for v in col.tolist()]
        want = [r[j] for r in rows]
        assert got == want, name


@pytest.mark.parametrize("scenario, precision", [
    ("report_sample.json", "double"),
    ("seeker_slew.json", "float"),
    ("fault_stuck_pickoff.json", "double"),
])
def test_given_a_scenario_file_when_run_then_the_columns_equal_gyro_sil_csv(source_dir, gyro_sil, tmp_path, scenario,
                                                                             precision):
    path = source_dir / "scenarios" / scenario
    header, rows = gyro_sil_csv(gyro_sil, path, tmp_path, "--precision", precision)
    run = gyro.run_sil(path, precision=precision)
    assert run.telemetry["precision"] == precision
    assert run["t"].dtype == np.float64 and run["flags"].dtype == np.uint64
    assert_same_as_csv(run, header, rows)


def test_given_a_dict_when_run_then_it_equals_the_file_run(source_dir):
    path = source_dir / "scenarios" / "seeker_slew.json"
    with open(path) as f:
        doc = json.load(f)
    a = gyro.run_sil(str(path), ticks=200)
    b = gyro.run_sil(doc, ticks=200)
    assert len(a) == len(b) == 201
    for name in a.keys():
        assert np.array_equal(a[name], b[name]), name


def test_given_a_run_when_its_telemetry_is_read_then_the_counters_count_the_flag_column(source_dir):
    run = gyro.run_sil(source_dir / "scenarios" / "fault_stuck_pickoff.json")
    tel = run.telemetry
    names = gyro.component_flag_names()
    flags = run["flags"]
    assert tel["rows"] == len(run) and tel["ticks"] == len(run) - 1
    assert tel["final_mode"] == run["mode"][-1]
    assert tel["flags_seen"] == int(np.bitwise_or.reduce(flags))
    assert "residual_fault" in tel["flags_seen_names"]
    for bit, name in enumerate(names):
        raised = int(np.count_nonzero(flags & np.uint64(1 << bit)))
        assert tel["counters"][name] == raised, name


def test_given_a_refused_field_in_a_dict_when_run_then_scenario_error_names_its_json_path(source_dir):
    with open(source_dir / "scenarios" / "seeker_slew.json") as f:
        doc = json.load(f)
    doc["component"]["max_torque"] = -1.0
    with pytest.raises(gyro.ScenarioError) as e:
        gyro.run_sil(doc)
    assert e.value.field == "component.max_torque"
    assert e.value.file == "<dict>"
    assert isinstance(e.value, gyro.ConfigError)


def test_given_a_missing_file_when_run_then_scenario_error(tmp_path):
    with pytest.raises(gyro.ScenarioError) as e:
        gyro.run_sil(tmp_path / "none.json")
    assert e.value.field == "(file)"


def test_given_a_run_past_the_output_bound_when_run_then_value_error_before_any_work(source_dir):
    assert gyro.DEFAULT_MAX_OUTPUT_BYTES == 1 << 30  # gyro_sil's --max-output-bytes default
    path = source_dir / "scenarios" / "seeker_slew.json"
    start = time.monotonic()
    with pytest.raises(ValueError) as e:
        gyro.run_sil(path, ticks=100_000_000)  # 58 GB of CSV; the arrays would need about 34 GB
    assert time.monotonic() - start < 1.0  # refused up front, not after a run
    msg = str(e.value)
    assert msg.startswith("max_output_bytes: the run's output could take up to "), msg
    assert "(100000001 rows of " in msg and "more than the limit of 1073741824" in msg, msg
    assert "raise it with max_output_bytes=" in msg, msg
    with pytest.raises(ValueError, match=r"more than the limit of 100000 \(raise it"):
        gyro.run_sil(path, ticks=1000, max_output_bytes=100_000)
    assert len(gyro.run_sil(path, ticks=1000, max_output_bytes=1_000_000)) == 1001  # raised: it runs


@pytest.mark.parametrize("value, error", [(0, ValueError), (-1, ValueError), (1.5e9, TypeError), (True, TypeError),
                                          (None, TypeError), ("1GiB", TypeError)])
def test_given_a_bad_output_bound_when_run_then_it_is_refused_not_switched_off(source_dir, value, error):
    with pytest.raises(error, match=r"^max_output_bytes: expected a whole number from 1 to 18446744073709551615, got"):
        gyro.run_sil(source_dir / "scenarios" / "seeker_slew.json", ticks=10, max_output_bytes=value)


@pytest.mark.parametrize("value, error", [(0, ValueError), (-5, ValueError), (10.0, TypeError), (True, TypeError),
                                          ("10", TypeError)])
def test_given_a_bad_tick_count_when_run_then_error_names_ticks(source_dir, value, error):
    with pytest.raises(error, match=r"^ticks: expected a whole number from 1 to "):
        gyro.run_sil(source_dir / "scenarios" / "seeker_slew.json", ticks=value)


def test_given_the_same_run_then_gyro_sil_refuses_it_at_the_same_bound(source_dir, gyro_sil, tmp_path):
    path = source_dir / "scenarios" / "seeker_slew.json"
    r = subprocess.run([str(gyro_sil), str(path), "-o", str(tmp_path / "out.csv"), "--ticks", "100000000", "--quiet"],
                       capture_output=True, text=True)
    assert r.returncode != 0
    with pytest.raises(ValueError) as e:
        gyro.run_sil(path, ticks=100_000_000)
    bound = str(e.value).split("could take up to ")[1].split(" bytes")[0]
    assert f"could take up to {bound} bytes" in r.stderr and "limit of 1073741824" in r.stderr, r.stderr
    assert not (tmp_path / "out.csv").exists()


def test_given_a_tracking_scenario_when_run_then_it_has_the_tracking_columns_last(source_dir, gyro_sil, tmp_path):
    path = source_dir / "scenarios" / "track_crossing.json"
    header, rows = gyro_sil_csv(gyro_sil, path, tmp_path)
    run = gyro.run_sil(str(path))
    assert list(run.keys()) == header == gyro.sil_columns(tracking=True)
    assert header[-2:] == ["pointing_error_true", "los_rate_error"]
    assert gyro.sil_columns(tracking=True)[:-2] == gyro.sil_columns()
    for j, name in enumerate(header[-2:], start=len(header) - 2):
        assert [cell_text(v) for v in run[name].tolist()] == [r[j] for r in rows], name
    # Acquired by 0.8 s: the true spin axis within 0.3 mrad of the line of sight from then on.
    t = run["t"]
    assert run["pointing_error_true"][t < 0.3].min() > 0.19
    assert run["pointing_error_true"][t >= 0.8].max() < 3e-4


def trajectory_columns(source_dir):
    """The shipped trajectory file's columns as NumPy arrays."""
    path = source_dir / "scenarios" / "trajectory_spinning.csv"
    table = np.genfromtxt(path, delimiter=",", names=True)
    return {name: np.asarray(table[name]) for name in table.dtype.names}


def test_given_trajectory_arrays_then_the_run_equals_the_file_run(source_dir, gyro_sil, tmp_path):
    path = source_dir / "scenarios" / "trajectory_spinning.json"
    header, rows = gyro_sil_csv(gyro_sil, path, tmp_path)
    doc = gyro.read_scenario(path)
    del doc["body"]["trajectory"]["file"]
    run = gyro.run_sil(doc, trajectory=trajectory_columns(source_dir))
    assert_same_as_csv(run, header, rows)
    assert run.telemetry["gimbal_stop_hits"] == 0


def test_given_bad_trajectory_arrays_then_the_refusal_names_column_and_index(source_dir):
    doc = gyro.read_scenario(source_dir / "scenarios" / "trajectory_spinning.json")
    del doc["body"]["trajectory"]["file"]
    cols = trajectory_columns(source_dir)
    bad = dict(cols, t_s=cols["t_s"].copy())
    bad["t_s"][5] = bad["t_s"][4]
    with pytest.raises(gyro.ScenarioError) as e:
        gyro.run_sil(doc, trajectory=bad)
    assert e.value.field == "t_s[5]" and "is not after the previous" in str(e.value)
    bad = dict(cols, qw=cols["qw"] * 1.01)
    with pytest.raises(gyro.ScenarioError) as e:
        gyro.run_sil(doc, trajectory=bad)
    assert e.value.field == "qw[0]" and "not 1 within 1e-06" in str(e.value)
    missing = {k: v for k, v in cols.items() if k != "fz"}
    with pytest.raises(gyro.ScenarioError) as e:
        gyro.run_sil(doc, trajectory=missing)
    assert e.value.field == "fz" and "missing column" in str(e.value)
    with pytest.raises(gyro.ScenarioError) as e:
        gyro.run_sil(doc, trajectory=cols, ticks=1700)
    assert "past the end of the body's trajectory at 1.6 s" in str(e.value)
    with pytest.raises(ValueError):
        gyro.run_sil(doc, trajectory=dict(cols, t_s=np.zeros((2, 2))))
    with_file = json.loads(json.dumps(doc))
    with_file["body"]["trajectory"]["file"] = str(source_dir / "scenarios" / "trajectory_spinning.csv")
    with pytest.raises(gyro.ScenarioError) as e:
        gyro.run_sil(with_file, trajectory=cols)
    assert e.value.field == "body.trajectory.file"
