"""Shared fixtures of the Python tests: where the sources and the host tools are.

ctest sets GYRO_SOURCE_DIR, GYRO_SIL, GYRO_CAMPAIGN and GYRO_REPORT_SAMPLE (tests/python/CMakeLists.txt)
and PYTHONPATH to the build's python directory.
"""

import os
import pathlib
import shutil

import pytest


def _path(var, default=None):
    value = os.environ.get(var, default)
    if value is None:
        pytest.skip(f"{var} not set (run through ctest)")
    return pathlib.Path(value)


@pytest.fixture(scope="session")
def source_dir():
    """The repository's top directory."""
    return _path("GYRO_SOURCE_DIR", str(pathlib.Path(__file__).resolve().parents[2]))


@pytest.fixture(scope="session")
def gyro_sil():
    """The gyro_sil executable."""
    return _path("GYRO_SIL", shutil.which("gyro_sil"))


@pytest.fixture(scope="session")
def gyro_campaign():
    """The gyro_campaign executable."""
    return _path("GYRO_CAMPAIGN", shutil.which("gyro_campaign"))


@pytest.fixture(scope="session")
def gyro_report_sample():
    """The gyro_report_sample executable."""
    return _path("GYRO_REPORT_SAMPLE", shutil.which("gyro_report_sample"))
