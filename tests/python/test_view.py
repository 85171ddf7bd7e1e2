"""RUN/view.py, the ParaView state every run gets, names the run's series and arrays (read here without ParaView),
and `cosim view` opens it with ParaView or says why it cannot."""
import ast
import os
import subprocess

import h5py
import pytest

import cosim
from support import CONFIGS


def settings(run):
    """The run's values at the top of RUN/view.py (FLUID, SOLID, INTERFACE), read as Python literals."""
    text = (run / "view.py").read_text()
    compile(text, str(run / "view.py"), "exec")  # the whole script is Python
    values = {}
    for node in ast.parse(text).body:
        name = getattr(node.targets[0], "id", None) if isinstance(node, ast.Assign) else None
        if name in ("FLUID", "SOLID", "INTERFACE"):
            values[name] = ast.literal_eval(node.value)
    return values


def cell_arrays(run, index):
    """The cell arrays of the newest snapshot of the series RUN/INDEX."""
    series = run / index
    newest = sorted(series.parent.glob(f"{series.stem}_[0-9]*.h5"))[-1]
    with h5py.File(newest, "r") as h5:
        return set(h5["cell"])


def view(launcher, run, *args, env=None):
    return subprocess.run([str(launcher), "view", str(run), *args], capture_output=True, text=True, timeout=60,
                          env=env)


def test_a_coupled_run_shows_the_pressure_the_stress_and_the_interface(coupled_dir):
    v = settings(coupled_dir)
    assert v["FLUID"]["file"] == "fluid/fluid.xmf" and v["FLUID"]["dimension"] == 2
    assert v["FLUID"]["pressure"] == "gas_pressure" and v["FLUID"]["flow_cells"] is True  # embedded piston
    assert v["SOLID"] == {"file": "solid/solid.xmf", "stress": "von_mises"}
    assert v["INTERFACE"] == "coupler/interface.xmf"
    for index in (v["FLUID"]["file"], v["SOLID"]["file"], v["INTERFACE"]):
        assert (coupled_dir / index).is_file(), index
    assert {"gas_pressure", "embedded_category"} <= cell_arrays(coupled_dir, "fluid/fluid.xmf")
    assert "von_mises" in cell_arrays(coupled_dir, "solid/solid.xmf")


def test_a_fluid_only_run_shows_its_phase_pressure_alone(fluid_dir):
    v = settings(fluid_dir)
    assert v["FLUID"] == {"file": "fluid/fluid.xmf", "dimension": 1, "pressure": "gas_pressure", "flow_cells": False}
    assert v["SOLID"] is None and v["INTERFACE"] is None
    assert "gas_pressure" in cell_arrays(fluid_dir, "fluid/fluid.xmf")


def test_two_phases_show_the_mixture_pressure(launcher, tmp_path):
    run = tmp_path / "water_air"
    cosim.run(CONFIGS / "water_air_shock_tube.yaml", run, set={"fluid.time.end": 1e-5}, exe=launcher)
    assert settings(run)["FLUID"]["pressure"] == "mixture_pressure"
    assert "mixture_pressure" in cell_arrays(run, "fluid/fluid.xmf")


def test_a_3d_fluid_is_sliced_through_the_middle_of_its_centre_cells(launcher, tmp_path):
    run = tmp_path / "piston_3d"
    cosim.run(CONFIGS / "piston_3d.yaml", run, set={"coupling.time.end": 2e-3, "coupling.output.interval": 1e-3},
              exe=launcher)
    fluid = settings(run)["FLUID"]
    assert fluid["dimension"] == 3
    # [-2, 2] x [0, 0.8] x [0, 0.8] in 40 x 8 x 8 cells: the centre in x and y, z in the middle of layer 4
    assert fluid["slice_origin"] == pytest.approx([0.0, 0.4, 0.45], abs=1e-12)


def test_view_write_makes_the_state_of_a_solver_run_alone(launcher, solid_dir):
    (solid_dir / "view.py").unlink(missing_ok=True)
    done = view(launcher, solid_dir, "--write")
    assert done.returncode == 0, done.stderr
    assert done.stdout.strip() == str(solid_dir / "view.py")
    v = settings(solid_dir)
    assert v["FLUID"] is None and v["SOLID"] == {"file": "solid.xmf", "stress": "von_mises"}


def test_view_of_a_directory_without_a_run_says_so(launcher, tmp_path):
    done = view(launcher, tmp_path)
    assert done.returncode == 2
    assert f"cosim view: {tmp_path} holds no run" in done.stderr
    assert not (tmp_path / "view.py").exists()
    done = view(launcher, tmp_path / "missing")
    assert done.returncode == 2 and "is not a directory" in done.stderr


def test_view_without_paraview_names_the_package(launcher, coupled_dir, tmp_path):
    env = dict(os.environ, PATH=str(tmp_path))  # no paraview on it
    done = view(launcher, coupled_dir, env=env)
    assert done.returncode == 127
    assert "paraview is not installed (on Debian: apt-get install paraview)" in done.stderr
    assert str(coupled_dir / "view.py") in done.stderr


def test_view_starts_paraview_with_the_state(launcher, coupled_dir, tmp_path):
    fake = tmp_path / "paraview"  # records its arguments in place of ParaView
    fake.write_text(f'#!/bin/sh\necho "$@" > {tmp_path}/args\n')
    fake.chmod(0o755)
    env = dict(os.environ, PATH=f"{tmp_path}:{os.environ['PATH']}", DISPLAY=":0")
    done = view(launcher, coupled_dir, env=env)
    assert done.returncode == 0, done.stderr
    assert (tmp_path / "args").read_text().split() == [f"--state={coupled_dir / 'view.py'}"]
    # without a display, what to do instead
    env = {k: v for k, v in env.items() if k not in ("DISPLAY", "WAYLAND_DISPLAY", "QT_QPA_PLATFORM")}
    done = view(launcher, coupled_dir, env=env)
    assert done.returncode == 2 and "no display" in done.stderr and "pvbatch" in done.stderr
