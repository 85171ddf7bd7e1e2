"""The rigid piston: its command line (module and script) and a coupled run in place of solid_solver."""
import subprocess

import numpy as np
import pytest

import cosim
from support import CONFIGS, COUPLED, PACKAGE_PARENT, PYTHON


@pytest.mark.parametrize("command", [["-m", "cosim.rigid_piston"], [str(PACKAGE_PARENT / "rigid_piston.py")]])
def test_help(command):
    done = subprocess.run([PYTHON, *command, "--help"], capture_output=True, text=True, timeout=60)
    assert done.returncode == 0, done.stderr
    assert "--coupler" in done.stdout and "--restart" in done.stdout and "rigid slab" in done.stdout


def test_missing_coupler_is_a_usage_error():
    done = subprocess.run([PYTHON, "-m", "cosim.rigid_piston", "scene.yaml"], capture_output=True, text=True,
                          timeout=60)
    assert done.returncode == 2 and "--coupler" in done.stderr


def test_python_piston_follows_solid_solver(coupled_dir, launcher, tmp_path):
    """The same coupled piston with the Python solid: the same trajectory (README: to 5e-6 of the amplitude)."""
    settings = dict(COUPLED[1], **{"launcher.solid": f"{PYTHON} -m cosim.rigid_piston"})
    run = cosim.run(CONFIGS / COUPLED[0], tmp_path / "python_piston", set=settings, exe=launcher)
    assert run.kind == "coupled" and run.solid is None  # the piston writes piston.csv, no snapshots
    track = run.histories["piston"]
    assert list(track) == ["time", "x", "v", "force"]
    np.testing.assert_allclose(track["time"], cosim.read_run(coupled_dir).interface.times, rtol=0, atol=1e-15)
    reference = cosim.read_run(coupled_dir).histories["interface_history"]
    travel = reference["centre_x"][-1] - reference["centre_x"][0]
    assert travel > 0.01
    assert abs(track["x"][-1] - travel) < 1e-4 * travel
    assert track["force"][0] == 0.0 and track["force"][-1] > 0.0
