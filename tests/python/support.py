"""What the tests share: paths, the interpreter, and short versions of scenes of configs/ (a few hundred steps
each) as (file name, --set values)."""
from pathlib import Path

import cosim

REPO = Path(__file__).resolve().parents[2]
CONFIGS = REPO / "configs"
PYTHON = "/usr/bin/python3"
PACKAGE_PARENT = Path(cosim.__file__).resolve().parent.parent  # the package under test and the entry scripts

COUPLED = ("piston_2d.yaml", {"coupling.time.end": 5e-3, "coupling.output.interval": 2e-3})
FLUID = ("sod.yaml", {"fluid.time.end": 0.05, "fluid.output.interval": 0.02, "fluid.mesh.cells": [200]})
SOLID = ("solid_piston_1d.yaml", {"solid.time.end": 5e-3, "solid.output.interval": 2e-3})
