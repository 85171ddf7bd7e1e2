"""Opens a fluid run written by several MPI ranks in ParaView (pvbatch) and checks it shows one grid.

    pvbatch open_ranks_run.py RUN_DIR CELLS_X CELLS_Y

The series through the XDMF3 reader: one grid of CELLS_X x CELLS_Y cells with the phases' arrays, one time step per
snapshot, and a pressure range that is not constant (each rank's block arrived, not only rank 0's). Exits non-zero
naming what is wrong.
"""
import os
import sys
from pathlib import Path

from paraview.simple import Xdmf3ReaderS

run, nx, ny = Path(sys.argv[1]), int(sys.argv[2]), int(sys.argv[3])
failures = []
reader = Xdmf3ReaderS(FileName=[str(run / "fluid.xmf")])
times = list(reader.TimestepValues) if reader.TimestepValues else []
reader.UpdatePipeline(times[-1] if times else 0.0)
info = reader.GetDataInformation()
snapshots = len(list(run.glob("fluid_*.h5")))
print(f"ranks run: {info.GetNumberOfCells()} cells, {len(times)} time steps")
if info.GetNumberOfCells() != nx * ny:
    failures.append(f"{info.GetNumberOfCells()} cells, expected one grid of {nx} x {ny}")
if len(times) != snapshots:
    failures.append(f"{len(times)} time steps, expected {snapshots}")
names = [reader.CellData.GetArray(i).GetName() for i in range(len(reader.CellData))]
if "air_pressure" not in names:
    failures.append(f"no array air_pressure (has {sorted(names)})")
else:
    lo, hi = reader.CellData["air_pressure"].GetRange()
    print(f"air_pressure from {lo:.6g} to {hi:.6g} Pa")
    if not hi > 1.01 * lo:
        failures.append(f"air_pressure is constant ({lo} to {hi}): the blast is missing")
for f in failures:
    print("FAILED:", f)
sys.stdout.flush()
os._exit(1 if failures else 0)
