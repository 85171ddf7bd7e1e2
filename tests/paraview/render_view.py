"""Runs a run's ParaView state, RUN/view.py, in pvbatch as `COSIM_VIEW_SCREENSHOT=PNG pvbatch RUN/view.py` does, and
checks what it shows.

    pvbatch render_view.py RUN_DIR PNG

The view is at the time of the newest snapshot; the fluid's colour range is the range of its pressure array over
its flow cells in that snapshot (read with h5py; a 3D fluid's over its middle layer of cells in z, the mid-plane),
the solid's that of von_mises; the picture holds the fields'
colours: in its middle, away from the colour bars, at least 20 distinct (of 10 pixels or more) colours, not a blank
background. Exits non-zero naming what is wrong.
"""
import os
import runpy
import sys
from pathlib import Path

import h5py
import numpy as np
from matplotlib.image import imread

from paraview.simple import GetColorTransferFunction

run, png = Path(sys.argv[1]), sys.argv[2]
MIN_COLOURS = 20
failures = []


def newest(series):
    """The newest snapshot of SERIES/SERIES.xmf's series, or None."""
    files = sorted((run / series).glob(f"{series}_[0-9]*.h5"))
    return h5py.File(files[-1], "r") if files else None


def expect_range(label, array, values):
    lo, hi = float(np.min(values)), float(np.max(values))
    points = list(GetColorTransferFunction(array).RGBPoints)
    shown = (points[0], points[-4])
    print(f"{label} {array}: colour range {shown[0]:.9g} to {shown[1]:.9g}, data {lo:.9g} to {hi:.9g}")
    if hi - lo > 1e-9 * max(abs(hi), 1.0) and not np.allclose(shown, (lo, hi), rtol=1e-6, atol=0.0):
        failures.append(f"{label}: the colour range {shown} is not the data's ({lo}, {hi}) at the last time")


os.environ["COSIM_VIEW_SCREENSHOT"] = png
state = runpy.run_path(str(run / "view.py"), run_name="__main__")
view, fluid, solid = state["view"], state["FLUID"], state["SOLID"]

last = max(float(h.attrs["time"]) for h in (newest("fluid"), newest("solid")) if h is not None)
print(f"view time {view.ViewTime:.9g} s, newest snapshot {last:.9g} s")
if abs(view.ViewTime - last) > 1e-12 * max(1.0, last):
    failures.append(f"the view is at t = {view.ViewTime}, the newest snapshot at t = {last}")
if fluid:
    cells = newest("fluid")["cell"]
    pressure, shown = cells[fluid["pressure"]][()], np.ones(cells[fluid["pressure"]].shape, bool)
    if "embedded_category" in cells:
        shown &= cells["embedded_category"][()] <= 1
    if fluid["dimension"] == 3:  # the mid-plane: the layer of cells at the domain's centre ([nz, ny, nx])
        shown[np.arange(len(shown)) != len(shown) // 2] = False
    pressure = pressure[shown]
    expect_range("fluid", fluid["pressure"], pressure)
if solid and solid["stress"]:
    expect_range("solid", solid["stress"], newest("solid")["cell"][solid["stress"]][()])

if not Path(png).is_file():
    failures.append(f"no picture saved to {png}")
else:  # the fields in the middle of the picture, away from the colour bars, the time and the axes
    pixels = imread(png)[..., :3]
    h, w = pixels.shape[:2]
    middle = np.round(pixels[int(0.15 * h):int(0.85 * h), int(0.12 * w):int(0.88 * w)] * 255).astype(int)
    _, counts = np.unique(middle.reshape(-1, 3), axis=0, return_counts=True)
    colours = int(np.sum(counts >= 10))  # not the edges' antialiasing
    print(f"picture {png}: {colours} colours of 10 pixels or more in its middle ({len(counts)} in all)")
    if colours < MIN_COLOURS:
        failures.append(f"the middle of the picture has {colours} colours of 10 pixels or more, expected at least "
                        f"{MIN_COLOURS}: the fields are not shown")

for f in failures:
    print("FAILED:", f)
sys.stdout.flush()
# ParaView's teardown under Xvfb's software GL can raise an X error (GLXBadContext) after the work is done.
os._exit(1 if failures else 0)
