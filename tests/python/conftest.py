"""Fixtures of the Python tests: small simulated scans (with truth) and the CLI for comparisons.

Run by ctest (tests/CMakeLists.txt) with PYTHONPATH at the build's python/ folder, or against an
installed package (scripts/check-package.sh).
"""

import os
import shutil
from pathlib import Path

import numpy as np
import pytest

import surfgrow

ROOT = Path(__file__).resolve().parents[2]


@pytest.fixture(scope="session")
def corner():
    """A room corner, one pose: three large planes at known places (floor z = 0, walls)."""
    return surfgrow.simulate("room-corner", poses=1, seed=1)


@pytest.fixture(scope="session")
def corner_result(corner):
    return surfgrow.grow(corner.cloud, mu=0.012, seed=1)


@pytest.fixture(scope="session")
def channel():
    """The paper's I-beam channel, one pose (about 233k points)."""
    return surfgrow.simulate("ibeam-channel", poses=1, seed=1)


@pytest.fixture(scope="session")
def cli():
    """The surfgrow command line of the same build, or a skip."""
    path = os.environ.get("SURFGROW_CLI") or shutil.which("surfgrow")
    if not path:
        pytest.skip("no surfgrow CLI (set SURFGROW_CLI)")
    return path


def angle_deg(a, b):
    """Angle between unit vectors as lines, degrees."""
    c = np.clip(np.abs(np.sum(np.asarray(a) * np.asarray(b), axis=-1)), 0.0, 1.0)
    return np.degrees(np.arccos(c))
