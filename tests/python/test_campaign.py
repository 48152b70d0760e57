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
    verdicts = {"true": True, "false": False, "": None}
    for i, row in enumerate(rows[:8]):
        for j, name in enumerate(header):
            col = result[name]
            if name in ("run", "seed"):
                assert col.dtype == np.uint64 and int(col[i]) == int(row[j]), (i, name)
            elif name in ("pass", "detected", "false_alarm", "safe_mode_after_stop"):
                assert col[i] is verdicts[row[j]], (i, name)
            elif isinstance(col, np.ndarray):
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


@pytest.mark.parametrize("threads, error", [(100_000, ValueError), (1025, ValueError), (0, ValueError),
                                            (-1, ValueError), (2**40, ValueError), (True, TypeError),
                                            (2.0, TypeError), ("2", TypeError)])
def test_given_a_thread_count_out_of_bounds_when_run_then_error_names_threads_and_the_bound(source_dir, threads,
                                                                                           error):
    assert gyro.MAX_THREADS == 1024  # gyro_campaign -j's bound
    with pytest.raises(error) as e:
        gyro.run_campaign({"base": "scenarios/seeker_slew.json", "runs": 2, "seed": 1}, threads=threads,
                          base_dir=source_dir)
    msg = str(e.value)
    assert msg.startswith("threads: expected a whole number from 1 to 1024, got ") and msg.endswith(repr(threads)), msg


def test_given_the_largest_thread_count_when_run_then_the_runs_are_done(source_dir):
    result = gyro.run_campaign({"base": "scenarios/seeker_slew.json", "runs": 3, "seed": 1}, threads=1024,
                               base_dir=source_dir)
    assert list(result["run"]) == [0, 1, 2]


def test_given_a_run_count_out_of_bounds_when_run_then_error_names_runs(source_dir):
    doc = {"base": "scenarios/seeker_slew.json", "runs": 4, "seed": 1}
    with pytest.raises(ValueError,
                       match=r"^runs: expected a whole number from 1 to the campaign's run count 4, got 5$"):
        gyro.run_campaign(doc, runs=5, base_dir=source_dir)
    with pytest.raises(TypeError, match=r"^runs: expected a whole number from 1 to 1000000, got bool True$"):
        gyro.run_campaign(doc, runs=True, base_dir=source_dir)


def test_given_a_campaign_when_run_then_seeds_are_exact_and_verdicts_are_booleans(source_dir):
    # Seeds are drawn over 64 bits: most are above 2**53, where float64 would round them.
    result = gyro.run_campaign({"base": "scenarios/seeker_slew.json", "runs": 4, "seed": 1}, base_dir=source_dir)
    seeds = result["seed"]
    assert seeds.dtype == np.uint64
    assert any(int(s) > 2**53 and int(s) % 2 == 1 for s in seeds), seeds
    assert all(isinstance(v, bool) for v in result["pass"]), result["pass"]


def test_given_a_campaign_run_when_shown_then_its_repr_is_one_short_line(source_dir):
    result = gyro.run_campaign({"base": "scenarios/seeker_slew.json", "runs": 3, "seed": 1}, base_dir=source_dir)
    text = repr(result)
    assert "\n" not in text and len(text) < 200, text
    s = result.summary()
    assert text == (f"CampaignRun(3 runs, {len(result.header)} columns; status: ok 3; "
                    f"passed {s['passed']}, failed {s['failed']})")
    assert s["runs"] == 3 and s["passed"] + s["failed"] + s["not_judged"] == 3
