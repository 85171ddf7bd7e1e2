"""plot_run.py (beside the package) on the three kinds of run; plot_paper_scenes.py on short paper scenes."""
import subprocess

import pytest

import cosim
from support import CONFIGS, PACKAGE_PARENT, PYTHON

PNG = b"\x89PNG\r\n\x1a\n"


def plot_run(*args):
    return subprocess.run([PYTHON, str(PACKAGE_PARENT / "plot_run.py"), *map(str, args)], capture_output=True,
                          text=True, timeout=120)


def assert_pngs(directory, names):
    assert sorted(p.name for p in directory.iterdir()) == sorted(names)
    for name in names:
        data = (directory / name).read_bytes()
        assert data.startswith(PNG) and len(data) > 10_000, name


def test_coupled_run_plots(coupled_dir, solid_dir, tmp_path):
    done = plot_run(coupled_dir, "--out", tmp_path, "--reference", solid_dir)
    assert done.returncode == 0, done.stderr
    assert_pngs(tmp_path, ["motion.png", "interface.png", "fields.png", "timing.png"])
    assert "max deviation of the coupled run from the conforming all-Lagrangian run" in done.stdout
    assert "turning points 0.0000 .. 0.7177 m" in done.stdout  # the ODE of docs/methods.md §8.2


def test_fluid_only_run_plots(fluid_dir, tmp_path):
    done = plot_run(fluid_dir, "--out", tmp_path)
    assert done.returncode == 0, done.stderr
    assert_pngs(tmp_path, ["fields.png"])


def test_solid_only_run_plots(solid_dir, tmp_path):
    done = plot_run(solid_dir, "--out", tmp_path)
    assert done.returncode == 0, done.stderr
    assert_pngs(tmp_path, ["fields.png", "blocks.png"])


def test_default_output_is_the_run_plots_folder(fluid_dir, tmp_path):
    copy = tmp_path / "sod"
    subprocess.run(["cp", "-r", str(fluid_dir), str(copy)], check=True)
    assert plot_run(copy).returncode == 0
    assert (copy / "plots" / "fields.png").is_file()


def test_not_a_run_directory_exits_2(tmp_path):
    done = plot_run(tmp_path)
    assert done.returncode == 2
    assert f"plot_run.py: error: {tmp_path}: not a run directory" in done.stderr


def paper(*args):
    return subprocess.run([PYTHON, str(PACKAGE_PARENT / "plot_paper_scenes.py"), *map(str, args)],
                          capture_output=True, text=True, timeout=120)


def test_paper_scene_plots(launcher, bin_dir, tmp_path):
    sod = cosim.run(CONFIGS / "modified_sod_2d.yaml", tmp_path / "sod", exe=launcher,
                    set={"fluid.mesh.cells": [32, 32], "solid.mesh.cells": [8, 8], "coupling.time.end": 0.02,
                         "coupling.output.interval": 0.01})
    assert len(sod.solid) == 3
    done = paper("sod", sod.directory, "--out", tmp_path / "sod_plots")
    assert done.returncode == 0, done.stderr
    assert_pngs(tmp_path / "sod_plots", ["modified_sod_profiles.png", "modified_sod_meshes.png"])

    short = {"coupling.time.end": 2e-5, "coupling.output.interval": 1e-5, "coupling.output.times": [1e-5]}
    panel = cosim.run(CONFIGS / "shock_panel_2d.yaml", tmp_path / "panel", exe=launcher, set=short)
    conforming = tmp_path / "conforming"
    subprocess.run([str(bin_dir / "solid_solver"), str(CONFIGS / "shock_panel_2d_conforming.yaml"), "--out",
                    str(conforming), "--set", "solid.time.end=2e-5", "--set", "solid.output.interval=1e-5"],
                   check=True, capture_output=True, timeout=120)
    done = paper("panel", panel.directory, conforming, "--out", tmp_path / "panel_plots")
    assert done.returncode == 0, done.stderr
    assert_pngs(tmp_path / "panel_plots", ["shock_panel_fields.png", "shock_panel_velocity.png"])


@pytest.mark.parametrize("script", ["plot_run.py", "plot_paper_scenes.py"])
def test_scripts_answer_help(script):
    done = subprocess.run([PYTHON, str(PACKAGE_PARENT / script), "--help"], capture_output=True, text=True,
                          timeout=60)
    assert done.returncode == 0 and "usage:" in done.stdout
