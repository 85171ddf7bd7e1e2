"""cosim.read_run on real small runs: coupled (piston_2d), fluid-only (sod) and solid-only (solid_piston_1d)."""
import re
import shutil

import numpy as np
import pytest

import cosim
from cosim import piston
from support import COUPLED, FLUID, SOLID


def xdmf_times(path):
    """The times and HDF5 files an XDMF index lists, read with a plain regular expression."""
    text = path.read_text()
    times = [float(t) for t in re.findall(r'<Time Value="([^"]+)"', text)]
    files = list(dict.fromkeys(re.findall(r">\s*([\w.]+\.h5):/", text)))
    return times, files


def scene_cells(run, section):
    return [int(c) for c in run.setting(f"{section}.mesh.cells")]


# ------------------------------------------------------------------------------------------------- coupled


def test_coupled_run_has_every_part(coupled_dir):
    run = cosim.read_run(coupled_dir)
    assert run.kind == "coupled"
    assert run.name == "piston_2d"
    assert run.fluid is not None and run.solid is not None and run.interface is not None
    assert set(run.summaries) == {"fluid", "solid", "coupler"}
    assert run.summary["status"] == "completed"
    assert run.energy_account is not None
    assert set(run.logs) == {"coupler", "fluid", "solid"}


def test_series_times_follow_the_xdmf_index(coupled_dir):
    run = cosim.read_run(coupled_dir)
    end, interval = COUPLED[1]["coupling.time.end"], COUPLED[1]["coupling.output.interval"]
    expected = sorted(set(np.arange(0.0, end, interval).tolist() + [end]))
    for series, index in ((run.fluid, "fluid/fluid.xmf"), (run.solid, "solid/solid.xmf"),
                          (run.interface, "coupler/interface.xmf")):
        times, files = xdmf_times(coupled_dir / index)
        assert series.times.tolist() == times
        assert [p.name for p in series.files] == files
        np.testing.assert_allclose(series.times, expected, rtol=0, atol=1e-15)
        assert len(series) == len(times)
        for snap in series:
            assert snap.attrs["time"] == snap.time  # the file agrees with its index
            assert snap.attrs["format"] == "cosim-snapshot-1"
        assert series[-1].time == end and series.at(0.0021).time == pytest.approx(0.002)


def test_coupled_shapes_match_the_scene(coupled_dir):
    run = cosim.read_run(coupled_dir)
    nx, ny = scene_cells(run, "fluid")
    snap = run.fluid[-1]
    assert snap.grid.type == "uniform" and snap.grid.dim == 2
    assert snap.grid.cells == (nx, ny) and snap.grid.shape == (ny, nx)
    np.testing.assert_allclose(snap.grid.lower, run.scene["fluid"]["mesh"]["lower"])
    np.testing.assert_allclose(snap.grid.upper, run.scene["fluid"]["mesh"]["upper"])
    assert snap["gas_pressure"].shape == (ny, nx)
    assert snap["gas_velocity"].shape == (ny, nx, 3)
    assert snap.grid.cell_centres().shape == (ny, nx, 2)
    np.testing.assert_allclose(snap.grid.cell_centres()[0, :, 0], snap.grid.axes[0])

    ex, ey = scene_cells(run, "solid")
    solid = run.solid[0]
    assert solid.grid.type == "unstructured" and solid.grid.cell_type == "quadrilateral"
    assert solid.grid.num_cells == ex * ey and solid.grid.num_nodes == (ex + 1) * (ey + 1)
    assert solid.grid.connectivity.shape == (ex * ey, 4)
    assert solid["velocity"].shape == ((ex + 1) * (ey + 1), 3)  # a node field
    assert solid["stress"].shape == (ex * ey, 6)

    faces = run.interface[0]
    assert faces.grid.num_cells == 2 * (ex + ey)  # the exterior segments of the box mesh
    assert faces["pressure"].shape == (2 * (ex + ey),)


def test_coupled_initial_state_and_force(coupled_dir):
    run = cosim.read_run(coupled_dir)
    first = run.fluid[0]
    x = first.grid.cell_centres()[..., 0]
    flow = first["embedded_category"] <= 1
    p = first["gas_pressure"]
    left, right = run.scene["fluid"]["initial"]["regions"][0]["state"]["p"], run.scene["fluid"]["initial"]["state"]["p"]
    assert np.all(p[flow & (x < -1.0)] == left) and np.all(p[flow & (x > 0.0)] == right)
    assert np.all(run.fluid[0]["gas_velocity"] == 0.0)

    hist = run.histories["interface_history"]
    assert hist["cycle"][0] == 0 and hist["time"][0] == 0.0
    assert hist["force_x"][0] == pytest.approx(piston.force(piston.parameters(run.scene), 0.0), rel=1e-12)
    assert hist["cycle"][-1] == run.summaries["coupler"]["cycles"] == run.summary["cycle"]
    assert hist["time"][-1] == run.setting("coupling.time.end")
    # the piston moves to the right (the left chamber has the higher pressure)
    assert np.all(np.diff(hist["centre_x"]) >= 0) and hist["centre_x"][-1] > hist["centre_x"][0]


def test_coupled_histories_and_overrides(coupled_dir):
    run = cosim.read_run(coupled_dir)
    assert {"interface_history", "timing", "block_history"} <= set(run.histories)
    assert list(run.histories["interface_history"]) == [
        "cycle", "time", "dt", "force_x", "force_y", "force_z", "velocity_x", "velocity_y", "velocity_z",
        "centre_x", "centre_y", "centre_z", "pressure"]
    assert list(run.histories["timing"]) == ["cycle", "wall", "solid", "fluid", "coupler", "output", "comm"]
    blocks = run.histories["block_history"]
    assert blocks["block"].dtype.kind == "U" and set(blocks["block"]) == {"piston"}
    assert len(run.histories["timing"]["cycle"]) == len(run.histories["interface_history"]["cycle"])
    # the scene as written, and the run's --set values beside it
    assert run.scene["coupling"]["time"]["end"] == 0.37
    assert run.overrides == COUPLED[1]
    assert run.setting("coupling.time.end") == COUPLED[1]["coupling.time.end"]
    assert run.setting("solid.blocks.0.density") == 100.0
    assert run.setting("no.such.key", "absent") == "absent"


def test_fluid_snapshot_carries_its_embedded_faces(coupled_dir):
    run = cosim.read_run(coupled_dir)
    faces = run.fluid[1].embedded_faces
    assert faces is not None and {"cx", "nx", "area", "vx"} <= set(faces)
    assert sorted(set(faces["nx"])) == [-1.0, 1.0]  # the piston's two ends
    assert run.histories["fluid_interface_000001"]["cx"].tolist() == faces["cx"].tolist()


def test_every_name_has_a_unit(coupled_dir, fluid_dir, solid_dir):
    unknown = []
    for d in (coupled_dir, fluid_dir, solid_dir):
        run = cosim.read_run(d)
        for series in (run.fluid, run.solid, run.interface):
            if series is not None:
                unknown += [n for n in series[-1].names if cosim.unit(n) is None]
        for table in run.histories.values():
            unknown += [c for c in table if cosim.unit(c) is None]
    assert unknown == []
    assert cosim.unit("gas_pressure") == "Pa" and cosim.unit("air_alpha") == "-"
    assert cosim.unit("tungsten_granular_temperature") == "m^2/s^2"
    assert cosim.unit("force_y") == "N" and cosim.unit("stress") == "Pa" and cosim.unit("energy") == "J/kg"
    assert cosim.unit("no_such_thing") is None


# ---------------------------------------------------------------------------------------------- fluid-only


def test_fluid_only_run(fluid_dir):
    run = cosim.read_run(fluid_dir)
    assert run.kind == "fluid" and run.name == "sod"
    assert run.solid is None and run.interface is None
    assert set(run.summaries) == {"fluid"} and run.summary["status"] == "completed"
    assert dict(run.histories) == {}
    times, _ = xdmf_times(fluid_dir / "fluid" / "fluid.xmf")
    assert run.fluid.times.tolist() == times and times[-1] == FLUID[1]["fluid.time.end"]
    (n,) = scene_cells(run, "fluid")
    assert n == FLUID[1]["fluid.mesh.cells"][0]  # a list value passed through --set
    snap = run.fluid[-1]
    assert snap.grid.shape == (n,) and snap["gas_density"].shape == (n,) and snap["gas_velocity"].shape == (n, 3)


def test_fluid_only_run_conserves_mass_and_energy(fluid_dir):
    """Transmissive ends at rest until the waves reach them: mass and energy stay those of the start."""
    run = cosim.read_run(fluid_dir)
    gamma = run.scene["fluid"]["phases"][0]["eos"]["gamma"]
    start = run.summaries["fluid"]["totals"]["start"][0]
    for snap in run.fluid:
        dx = snap.grid.spacing[0]
        rho, u, p = snap["gas_density"], snap["gas_velocity"][:, 0], snap["gas_pressure"]
        assert np.sum(rho) * dx == pytest.approx(start["mass"], rel=1e-12)
        assert np.sum(p / (gamma - 1) + 0.5 * rho * u * u) * dx == pytest.approx(start["energy"], rel=1e-12)
    first = run.fluid[0]
    x = first.grid.axes[0]
    assert np.all(first["gas_density"][x < 0.5] == 1.0) and np.all(first["gas_density"][x > 0.5] == 0.125)


# ---------------------------------------------------------------------------------------------- solid-only


def test_solid_only_run(solid_dir):
    run = cosim.read_run(solid_dir)
    assert run.kind == "solid" and run.name == "solid_piston_1d"
    assert run.fluid is None and run.interface is None and run.scene is None and run.summary is None
    assert set(run.summaries) == {"solid"}
    times, _ = xdmf_times(solid_dir / "solid.xmf")
    assert run.solid.times.tolist() == times and times[-1] == SOLID[1]["solid.time.end"]
    ex, ey = run.summaries["solid"]["elements"], run.summaries["solid"]["nodes"]
    snap = run.solid[-1]
    assert snap.grid.num_cells == ex == 160 and snap.grid.num_nodes == ey == 161 * 2
    assert snap["pressure"].shape == (160,)


def test_solid_only_blocks_keep_their_mass(solid_dir):
    run = cosim.read_run(solid_dir)
    blocks = cosim.tables.split_by(run.histories["block_history"], "block")
    assert list(blocks) == ["gas_left", "piston", "gas_right"]
    assert np.all(blocks["piston"]["mass"] == pytest.approx(100.0 * 1.0 * 0.025, rel=1e-12))
    first = run.solid[0]
    x = first.grid.cell_centres()[:, 0]
    np.testing.assert_allclose(first["pressure"][x < -1.0], 2.0e5, rtol=1e-12)  # from rho and e: round-off
    np.testing.assert_allclose(first["pressure"][x > 0.0], 1.0e5, rtol=1e-12)


# ------------------------------------------------------------------------------------------------- errors


def test_not_a_run_directory(tmp_path):
    (tmp_path / "notes.txt").write_text("nothing here")
    with pytest.raises(cosim.RunDirError, match=re.escape(str(tmp_path)) + ".*not a run directory.*scene.yaml"):
        cosim.read_run(tmp_path)
    with pytest.raises(cosim.RunDirError, match="no such directory"):
        cosim.read_run(tmp_path / "missing")
    with pytest.raises(cosim.RunDirError, match="not a directory"):
        cosim.read_run(tmp_path / "notes.txt")


def test_broken_index_is_named(coupled_dir, tmp_path):
    copy = tmp_path / "run"
    shutil.copytree(coupled_dir, copy)
    (copy / "fluid" / "fluid.xmf").write_text("<Xdmf><Domain>")
    with pytest.raises(cosim.RunDirError, match=re.escape(str(copy / "fluid" / "fluid.xmf"))):
        cosim.read_run(copy)


def test_index_decides_which_snapshots_exist(coupled_dir, tmp_path):
    """A snapshot the index does not list yet (being written) is not part of the series; without an index the
    numbered files are taken, their times from the files."""
    copy = tmp_path / "run"
    shutil.copytree(coupled_dir, copy)
    index = copy / "fluid" / "fluid.xmf"
    text = index.read_text()
    last = text.rindex('<Grid Name="fluid_')
    index.write_text(text[:last] + text[text.index("</Grid>", last) + len("</Grid>"):])
    run = cosim.read_run(copy)
    assert len(run.fluid) == len(run.solid) - 1
    index.unlink()
    run = cosim.read_run(copy)
    assert run.fluid.index_path is None and run.fluid.times.tolist() == run.solid.times.tolist()
    with pytest.raises(KeyError, match="no field 'gas_enthalpy'"):
        run.fluid[0]["gas_enthalpy"]
