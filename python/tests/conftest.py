"""Shared helpers of the pytest suites: the CLI they compare with, the real data, CSV parsing.

ctest (python/tests/CMakeLists.txt) sets SURFSCATTER_CLI, SURFSCATTER_SHARED_DATA and SURFSCATTER_SOURCE_DIR and
puts the package of the build tree on PYTHONPATH.
"""

import csv
import io
import os
import subprocess
from pathlib import Path

import numpy as np
import pytest

CLI = os.environ.get("SURFSCATTER_CLI", "")
SHARED_DATA = Path(os.environ.get("SURFSCATTER_SHARED_DATA", "/nonexistent"))
SOURCE_DIR = Path(os.environ.get("SURFSCATTER_SOURCE_DIR", Path(__file__).resolve().parents[2]))

# The CLI prints numbers with 10 significant digits (apps/surfscatter/main.cpp format_number).
CLI_RTOL = 1e-9


def run_cli(*args):
    """Runs the surfscatter binary; returns stdout. A non-zero exit fails the test with its stderr."""
    if not CLI:
        pytest.fail("SURFSCATTER_CLI is not set: run the suites through ctest")
    done = subprocess.run([CLI, *map(str, args)], capture_output=True, text=True)
    assert done.returncode == 0, f"surfscatter {' '.join(map(str, args))}: {done.stderr}"
    return done.stdout


def cli_csv(*args):
    """The CSV the CLI prints, as {column: float array}."""
    rows = list(csv.DictReader(io.StringIO(run_cli(*args))))
    return {key: np.array([float(row[key]) for row in rows]) for key in rows[0]}


def cli_values(*args):
    """The numeric 'name = value' lines the CLI prints, as {name: float}."""
    values = {}
    for line in run_cli(*args).splitlines():
        name, _, value = line.partition(" = ")
        try:
            values[name] = float(value)
        except ValueError:
            pass  # text: format, reader, warnings
    return values


def shared(*parts):
    """A file of ../shared/data (the real data every suite of the project tests on)."""
    path = SHARED_DATA.joinpath(*parts)
    assert path.exists(), f"real data {path} missing (SURFSCATTER_SHARED_DATA)"
    return path


def numbers(text):
    """'1,2,3' for the CLI's comma-separated lists, with full precision."""
    return ",".join(repr(float(v)) for v in np.ravel(text))
