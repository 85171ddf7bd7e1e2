"""A snapshot series (fluid, solid or interface) of a run: its times and its snapshots."""
import glob
import re
from collections.abc import Sequence
from pathlib import Path

import numpy as np

from .errors import RunDirError
from .snapshot import Snapshot
from .xdmf import read_index


class Series(Sequence):
    """The snapshots <name>_NNNNNN.h5 of one directory, as its XDMF index <name>.xmf lists them.

    times: numpy array [s]; len(series); series[i] (negative i from the end) is a Snapshot, series[a:b] a list;
    series.at(t) the snapshot nearest t. Without an index (a series copied without it) the numbered files
    are taken in order, each one's time read from the file."""

    def __init__(self, name, directory):
        self.name, self.directory = name, Path(directory)
        self.index_path = self.directory / f"{name}.xmf"
        if self.index_path.is_file():
            entries = read_index(self.index_path)
        else:
            self.index_path = None
            pattern = re.compile(rf"^{re.escape(name)}_\d+\.h5$")
            files = sorted(p for p in self.directory.glob(f"{glob.escape(name)}_*.h5") if pattern.match(p.name))
            entries = [(Snapshot.open(p).time, p) for p in files]
        self.times = np.array([t for t, _ in entries], dtype=float)
        self.files = [p for _, p in entries]

    @staticmethod
    def holds(name, directory):
        """Whether directory holds a series `name` (its index or a numbered snapshot)."""
        directory = Path(directory)
        return (directory / f"{name}.xmf").is_file() or any(
            re.match(rf"^{re.escape(name)}_\d+\.h5$", p.name) for p in directory.glob(f"{glob.escape(name)}_*.h5"))

    def __len__(self):
        return len(self.files)

    def __getitem__(self, i):
        if isinstance(i, slice):
            return [self[k] for k in range(*i.indices(len(self)))]
        n = len(self)
        k = i + n if i < 0 else i
        if not 0 <= k < n:
            raise IndexError(f"{self.name} series of {self.directory}: snapshot {i} of {n}")
        if not self.files[k].is_file():
            raise RunDirError(f"{self.files[k]}: listed in {self.index_path} but missing")
        return Snapshot(self.files[k], float(self.times[k]))

    def at(self, time):
        """The snapshot whose time is nearest `time`."""
        if not len(self):
            raise IndexError(f"{self.name} series of {self.directory} is empty")
        return self[int(np.argmin(np.abs(self.times - time)))]

    def __repr__(self):
        span = f", t = {self.times[0]:g} .. {self.times[-1]:g} s" if len(self) else ""
        return f"Series({self.name}: {len(self)} snapshots in {self.directory}{span})"
