"""The example scripts (examples/) run and write their figures: PNG files of a sane size."""

import subprocess
import sys

import pytest

PNG = b"\x89PNG\r\n\x1a\n"


def run_example(source_dir, script, out, *args):
    subprocess.run([sys.executable, str(source_dir / "examples" / script), "--output-dir", str(out), *args], check=True,
                   timeout=500)


def assert_png(path, min_bytes=10_000):
    assert path.is_file(), path
    data = path.read_bytes()
    assert data[:8] == PNG, path
    assert len(data) > min_bytes, (path, len(data))


def test_given_the_report_figures_example_when_run_then_figures_a1_and_a2_are_written(source_dir, tmp_path):
    run_example(source_dir, "report_figures.py", tmp_path)
    assert_png(tmp_path / "figure_a1_pitch.png")
    assert_png(tmp_path / "figure_a2_yaw.png")
    assert not list(tmp_path.glob(".*tmp*")), "temporary files left behind"


def test_given_the_dispersion_example_when_run_then_its_histogram_is_written(source_dir, tmp_path):
    run_example(source_dir, "dispersion_study.py", tmp_path, "--runs", "24")
    assert_png(tmp_path / "dispersion_slew_error.png")


def test_given_an_existing_figure_when_an_example_runs_then_it_is_replaced_whole(source_dir, tmp_path):
    old = tmp_path / "figure_a1_pitch.png"
    old.write_bytes(b"old")
    run_example(source_dir, "report_figures.py", tmp_path)
    assert_png(old)


@pytest.mark.parametrize("precision", ["double", "float"])
def test_given_the_seeker_track_example_when_run_then_the_track_is_held(source_dir, tmp_path, precision):
    # The example exits non-zero when the track is not held within 5 mrad.
    run_example(source_dir, "seeker_track.py", tmp_path, "--precision", precision)
    assert_png(tmp_path / "seeker_track.png")
