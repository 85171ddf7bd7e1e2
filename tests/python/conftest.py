"""Fixtures: the programs ($COSIM_BIN, default <repo>/build/bin) and small runs of real scenes, made once per
session under a temporary directory. The package under test comes from PYTHONPATH (<build>/python or python/)."""
import os
import subprocess
from pathlib import Path

import pytest

try:
    import cosim
except ImportError as e:  # a setup error, not a test failure
    raise pytest.UsageError(f"cannot import cosim ({e}): run with PYTHONPATH=<build>/python (or python/)") from e

from support import CONFIGS, COUPLED, FLUID, REPO, SOLID


def _require(path):
    if not path.is_file():
        pytest.fail(f"{path} does not exist: build first, or set COSIM_BIN to the directory of the programs")


@pytest.fixture(scope="session")
def bin_dir():
    d = Path(os.environ.get("COSIM_BIN") or REPO / "build" / "bin")
    for name in ("cosim", "fluid_solver", "solid_solver", "coupler"):
        _require(d / name)
    return d


@pytest.fixture(scope="session")
def launcher(bin_dir):
    return bin_dir / "cosim"


def _launch(launcher, tmp_path_factory, scene):
    out = tmp_path_factory.mktemp("runs") / Path(scene[0]).stem
    cosim.run(CONFIGS / scene[0], out, set=scene[1], exe=launcher)
    return out


@pytest.fixture(scope="session")
def coupled_dir(launcher, tmp_path_factory):
    return _launch(launcher, tmp_path_factory, COUPLED)


@pytest.fixture(scope="session")
def fluid_dir(launcher, tmp_path_factory):
    return _launch(launcher, tmp_path_factory, FLUID)


@pytest.fixture(scope="session")
def solid_dir(bin_dir, tmp_path_factory):
    """solid_solver alone (the launcher runs scenes that have a fluid: section)."""
    out = tmp_path_factory.mktemp("runs") / Path(SOLID[0]).stem
    command = [str(bin_dir / "solid_solver"), str(CONFIGS / SOLID[0]), "--out", str(out)]
    for key, value in SOLID[1].items():
        command += ["--set", f"{key}={cosim.scene.format_value(value)}"]
    done = subprocess.run(command, capture_output=True, text=True, timeout=120)
    assert done.returncode == 0, done.stderr
    return out
