"""Opens a coupled run's three series in ParaView (pvbatch) as a user would, and checks what it shows.

    pvbatch open_run.py RUN_DIR PNG

The fluid through both XDMF readers (XDMF3 and the legacy one), the solid and the interface through XDMF3: each
has cells, its named arrays and one time step per snapshot; a picture of the fluid's pressure is rendered.
Exits non-zero naming what is missing.
"""
import os
import sys
from pathlib import Path

import numpy as np
from matplotlib.image import imread

from paraview.simple import (ColorBy, GetActiveViewOrCreate, ResetCamera, SaveScreenshot, Show, XDMFReader,
                             Xdmf3ReaderS)

run, png = Path(sys.argv[1]), sys.argv[2]
failures = []


def check(label, reader, arrays, min_cells, steps):
    times = list(reader.TimestepValues) if reader.TimestepValues else []
    reader.UpdatePipeline(times[-1] if times else 0.0)
    info = reader.GetDataInformation()
    names = [reader.CellData.GetArray(i).GetName() for i in range(len(reader.CellData))]
    names += [reader.PointData.GetArray(i).GetName() for i in range(len(reader.PointData))]
    print(f"{label}: {info.GetNumberOfCells()} cells, {len(times)} time steps, arrays {sorted(names)}")
    if info.GetNumberOfCells() < min_cells:
        failures.append(f"{label}: {info.GetNumberOfCells()} cells, expected at least {min_cells}")
    if len(times) != steps:
        failures.append(f"{label}: {len(times)} time steps, expected {steps}")
    for a in arrays:
        if a not in names:
            failures.append(f"{label}: no array {a} (has {sorted(names)})")


def snapshots(series):
    return len(list((run / series).glob(f"{series}_*.h5"))) if series != "coupler" else len(
        list((run / series).glob("interface_*.h5")))


fluid_steps = snapshots("fluid")
fluid = Xdmf3ReaderS(FileName=[str(run / "fluid" / "fluid.xmf")])
check("fluid (XDMF3)", fluid, ["gas_pressure", "gas_density", "gas_velocity"], 1280, fluid_steps)
check("fluid (legacy XDMF)", XDMFReader(FileNames=[str(run / "fluid" / "fluid.xmf")]),
      ["gas_pressure", "gas_density", "gas_velocity"], 1280, fluid_steps)
check("solid", Xdmf3ReaderS(FileName=[str(run / "solid" / "solid.xmf")]), ["velocity"], 8, snapshots("solid"))
check("interface", Xdmf3ReaderS(FileName=[str(run / "coupler" / "interface.xmf")]), [], 1, snapshots("coupler"))

# The 2D fluid as a surface (a slab one cell thick, not a zero-volume sheet) shows the field.
view = GetActiveViewOrCreate("RenderView")
display = Show(fluid, view)
display.Representation = "Surface"
ColorBy(display, ("CELLS", "gas_pressure"))
ResetCamera(view)
SaveScreenshot(png, view, ImageResolution=[640, 240])
if not Path(png).is_file():
    failures.append(f"no picture rendered to {png}")
else:  # the field is in it: many colours of the map, not a blank background
    pixels = imread(png)[..., :3].reshape(-1, 3)
    colours = len(np.unique(np.round(pixels * 255).astype(int), axis=0))
    print(f"picture {png}: {colours} colours")
    if colours < 20:
        failures.append(f"the picture of the fluid has {colours} colours: the field is not shown")

for f in failures:
    print("FAILED:", f)
sys.stdout.flush()
# ParaView's teardown under Xvfb's software GL can raise an X error (GLXBadContext) after the work is done: the
# verdict is ours, not the teardown's.
os._exit(1 if failures else 0)
