"""Shared fixtures: the C++ golden renders (mpr_python_golden) and the real-data folder."""

import os
import pathlib
import subprocess

import pytest


@pytest.fixture(scope="session")
def data_dir():
    root = os.environ.get("MPR_DATA_DIR", "")
    return pathlib.Path(root) if root else None


@pytest.fixture(scope="session")
def temple_par(data_dir):
    if data_dir is None:
        return None
    par = data_dir / "middlebury" / "templeSparseRing" / "templeSR_par.txt"
    return par if par.exists() else None


@pytest.fixture(scope="session")
def golden(tmp_path_factory, temple_par):
    """Runs the C++ golden program once; returns its output folder."""
    program = os.environ.get("MPR_GOLDEN")
    if not program:
        pytest.skip("MPR_GOLDEN (the mpr_python_golden program) not set: run through ctest")
    out = tmp_path_factory.mktemp("golden")
    args = [program, str(out)] + ([str(temple_par)] if temple_par else [])
    # Without LD_PRELOAD: a sanitizer build preloads its runtime into Python for the module
    # (python/CMakeLists.txt), and the golden program links its own.
    env = {k: v for k, v in os.environ.items() if k != "LD_PRELOAD"}
    subprocess.run(args, check=True, capture_output=True, env=env)
    return out
