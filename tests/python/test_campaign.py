"""Campaign runs from Python against gyro_campaign: the per-run table holds the same rows."""

import csv
import subprocess

import numpy as np
import pytest

import gyro


def test_given_a_campaign_when_run_from_python_then_its_rows_equal_gyro_campaign_runs_csv(source_dir, gyro_campaign,
                                                                                        tmp_path):
    campaign = source_dir / "tests" / "data" / "campaigns" / "small.json"
    out = tmp_path / "out"
    subprocess.run([str(gyro_campaign), "run", str(campaign), "-o", str(out), "-j", "2", "--no-plots", "--quiet"],
                   check=True)
    with open(out / "runs.csv", newline="") as f:
        reader = csv.reader(f)
        header = next(reader)
        rows = list(reader)
    result = gyro.run_campaign(campaign, runs=8, threads=2)
    assert result.header == header
    assert len(result) == 8
    assert list(result["run"]) == list(range(8))
    for i, row in enumerate(rows[:8]):
        for j, name in enumerate(header):
            col = result[name]
            if isinstance(col, np.ndarray):
                want = float(row[j]) if row[j] else np.nan
                assert np.array_equal(col[i], want, equal_nan=True), (i, name)
            else:
                assert col[i] == row[j], (i, name)
    as_dicts = result.rows()
    assert as_dicts[3]["status"] == rows[3][header.index("status")]
    assert {"ok", "refused"} >= set(result["status"])


def test_given_a_bad_campaign_dict_when_run_then_scenario_error_names_the_field(source_dir):
    with pytest.raises(gyro.ScenarioError) as e:
        gyro.run_campaign({"base": "scenarios/seeker_slew.json", "runs": 0, "seed": 1}, base_dir=source_dir)
    assert e.value.field == "runs"
