"""One HDF5 snapshot (format cosim-snapshot-1, docs/output.md "HDF5 schema"): metadata, geometry and lazily read fields.

Nothing is read before it is asked for; each array is read once per Snapshot object and kept, so keep the object
to reuse what it has read (a Series makes a new one at each indexing).
"""
import re
from collections.abc import Mapping
from pathlib import Path

import h5py
import numpy as np

from .errors import RunDirError
from .tables import read_csv
from .units import unit

_NUMBER = re.compile(r"_(\d+)\.h5$")


def _plain(value):
    """An HDF5 attribute as a Python value (bytes -> str, 1-element arrays stay arrays)."""
    if isinstance(value, bytes):
        return value.decode()
    if isinstance(value, np.generic):
        return value.item()
    return value


class Fields(Mapping):
    """name -> numpy array of one group (/cell or /node) of a snapshot, each read on first access."""

    def __init__(self, snapshot, group, names):
        self._snapshot, self._group, self._names, self._arrays = snapshot, group, list(names), {}

    def __getitem__(self, name):
        if name not in self._arrays:
            if name not in self._names:
                raise KeyError(f"{self._snapshot.path}: no {self._group} field {name!r}; "
                               f"there are: {', '.join(self._names) or 'none'}")
            self._arrays[name] = self._snapshot._read(f"{self._group}/{name}")
        return self._arrays[name]

    def __iter__(self):
        return iter(self._names)

    def __len__(self):
        return len(self._names)

    def __repr__(self):
        return f"Fields({self._group}: {', '.join(self._names)})"


class Grid:
    """Geometry of a snapshot.

    type "uniform" (the fluid's Cartesian grid): dim, cells (nx[, ny[, nz]]), origin and spacing [m] (dim
    values), lower / upper corners, shape (that of a cell field: (nx,), (ny, nx) or (nz, ny, nx)), axes (the cell
    centres along x, y, z) and cell_centres() ([*shape, dim] array).
    type "unstructured" (solid mesh, interface faces): dim, cell_type ("quadrilateral", "hexahedron", "line",
    ...), coordinates [num_nodes, 3] m (z = 0 in 2D), connectivity [num_cells, nodes_per_cell] (0-based, VTK
    order), num_cells, num_nodes and cell_centres() ([num_cells, 3], the mean of each cell's nodes)."""

    def __init__(self, snapshot, attrs):
        self._snapshot = snapshot
        self.type = attrs.get("type")
        self.dim = int(attrs.get("dim", 0))
        if self.type == "uniform":
            try:
                self.cells = tuple(int(c) for c in attrs["cells"][:self.dim])
                self.origin = np.asarray(attrs["origin"], float)[:self.dim]
                self.spacing = np.asarray(attrs["spacing"], float)[:self.dim]
            except KeyError as e:
                raise RunDirError(f"{snapshot.path}: uniform /grid lacks the attribute {e}") from e
            self.lower = self.origin
            self.upper = self.origin + self.spacing * np.array(self.cells)
            self.shape = tuple(reversed(self.cells))
            self.axes = [self.origin[d] + (np.arange(self.cells[d]) + 0.5) * self.spacing[d] for d in range(self.dim)]
        elif self.type == "unstructured":
            self.cell_type = attrs.get("cell_type")
        else:
            raise RunDirError(f"{snapshot.path}: /grid type {self.type!r}, expected uniform or unstructured")
        self._coordinates = self._connectivity = None

    @property
    def coordinates(self):
        self._need("unstructured", "coordinates")
        if self._coordinates is None:
            self._coordinates = self._snapshot._read("grid/coordinates")
        return self._coordinates

    @property
    def connectivity(self):
        self._need("unstructured", "connectivity")
        if self._connectivity is None:
            self._connectivity = self._snapshot._read("grid/connectivity")
        return self._connectivity

    @property
    def num_cells(self):
        return int(np.prod(self.cells)) if self.type == "uniform" else len(self.connectivity)

    @property
    def num_nodes(self):
        self._need("unstructured", "num_nodes")
        return len(self.coordinates)

    def cell_centres(self):
        if self.type == "uniform":
            mesh = np.meshgrid(*reversed(self.axes), indexing="ij")  # z y x order, as the fields
            return np.stack(list(reversed(mesh)), axis=-1)
        return self.coordinates[self.connectivity].mean(axis=1)

    def _need(self, kind, what):
        if self.type != kind:
            raise AttributeError(f"{what}: only an {kind} grid has it ({self._snapshot.path} is {self.type})")

    def __repr__(self):
        if self.type == "uniform":
            return f"Grid(uniform, cells={self.cells}, origin={self.origin.tolist()}, spacing={self.spacing.tolist()})"
        return f"Grid(unstructured {self.cell_type}, dim={self.dim})"


class Snapshot:
    """A snapshot file: time, index, attrs (file attributes: time, step, format), grid, cell / node fields.

    snap["name"] looks a field up among the cell fields, then the node fields; snap.unit(name) is its SI unit;
    snap.embedded_faces the fluid's embedded interface segments written with it (fluid_interface_NNNNNN.csv), or
    None."""

    def __init__(self, path, time=None):
        self.path = Path(path)
        m = _NUMBER.search(self.path.name)
        self.index = int(m.group(1)) if m else None
        self._time = time
        self._meta = None

    @classmethod
    def open(cls, path):
        """The snapshot at path, its time read from the file."""
        return cls(path)

    # --- metadata ---------------------------------------------------------------------------------------
    def _load_meta(self):
        if self._meta is None:
            try:
                with h5py.File(self.path, "r") as f:
                    attrs = {k: _plain(v) for k, v in f.attrs.items()}
                    grid = {k: _plain(v) for k, v in f["grid"].attrs.items()} if "grid" in f else {}
                    cell = list(f["cell"].keys()) if "cell" in f else []
                    node = list(f["node"].keys()) if "node" in f else []
            except OSError as e:
                raise RunDirError(f"{self.path}: not a readable HDF5 snapshot ({e})") from e
            if not grid:
                raise RunDirError(f"{self.path}: no /grid group: not a cosim snapshot")
            self._meta = {"attrs": attrs, "grid": Grid(self, grid), "cell": Fields(self, "cell", cell),
                          "node": Fields(self, "node", node)}
        return self._meta

    def _read(self, name):
        try:
            with h5py.File(self.path, "r") as f:
                return f[name][()]
        except (OSError, KeyError) as e:
            raise RunDirError(f"{self.path}: cannot read {name} ({e})") from e

    @property
    def attrs(self):
        return self._load_meta()["attrs"]

    @property
    def time(self):
        """Simulated time [s] (from the series' index, else the file's attribute)."""
        return self._time if self._time is not None else float(self.attrs["time"])

    @property
    def step(self):
        return self.attrs.get("step")

    @property
    def grid(self):
        return self._load_meta()["grid"]

    @property
    def cell(self):
        return self._load_meta()["cell"]

    @property
    def node(self):
        return self._load_meta()["node"]

    @property
    def names(self):
        return list(self.cell) + [n for n in self.node if n not in self.cell]

    def __getitem__(self, name):
        if name in self.cell:
            return self.cell[name]
        if name in self.node:
            return self.node[name]
        raise KeyError(f"{self.path}: no field {name!r}; there are: {', '.join(self.names) or 'none'}")

    def __contains__(self, name):
        return name in self.cell or name in self.node

    @staticmethod
    def unit(name):
        return unit(name)

    @property
    def embedded_faces(self):
        """{column: array} of fluid_interface_NNNNNN.csv beside a fluid snapshot (i j k, cx cy cz, nx ny nz,
        area, vx vy vz), or None when there is none or it is empty."""
        csv_path = self.path.with_name(self.path.name.replace("fluid_", "fluid_interface_", 1)).with_suffix(".csv")
        if not self.path.name.startswith("fluid_") or not csv_path.is_file():
            return None
        table = read_csv(csv_path)
        return table or None

    def __repr__(self):
        t = f"{self._time:g}" if self._time is not None else "?"
        return f"Snapshot({self.path.name}, t={t})"
