"""cosim: read, run and plot the runs of the cosim co-simulation (fluid_solver, solid_solver, coupler).

    import cosim
    run = cosim.run("configs/piston_2d.yaml", "/tmp/piston", set={"coupling.time.end": 1e-3})
    run = cosim.read_run("/tmp/piston")          # the same, for a run directory that exists
    last = run.fluid[-1]
    p = last["gas_pressure"]                       # numpy array, [ny, nx], Pa (cosim.unit("gas_pressure"))

Modules: cosim.runs (run directories), cosim.series and cosim.snapshot (HDF5 snapshots through their XDMF
index), cosim.tables (CSV files), cosim.scene (scene files and keys), cosim.units (SI units of the quantities),
cosim.launch (the `cosim run` launcher), cosim.client (the coupling protocol client), cosim.rigid_piston
(a solid solver in Python), cosim.piston (the two-chamber piston ODE) and cosim.plot (figures of a run).
cosim.client and cosim.rigid_piston need the generated coupling_pb2 (docs/python.md); nothing here imports them.
"""
from .errors import RunDirError, RunFailed
from .launch import find_executable, run
from .runs import Run, read_run
from .series import Series
from .snapshot import Grid, Snapshot
from .units import UNITS, unit

__version__ = "0.9.0"

__all__ = ["Grid", "Run", "RunDirError", "RunFailed", "Series", "Snapshot", "UNITS", "find_executable", "read_run",
           "run", "unit"]
