"""CSV files of a run (histories, timing, interface segments) as dicts of column name -> numpy array."""
import csv
from collections.abc import Mapping

import numpy as np

from .errors import RunDirError


def read_csv(path):
    """{column: array} of a CSV file with a header line.

    Columns whose every value is a number are float64 arrays, others (block names) arrays of str. A last line
    with the wrong number of values (a run still writing it) is left out; a file with only a header gives
    empty arrays, an empty file an empty dict."""
    try:
        with open(path, newline="") as f:
            rows = list(csv.reader(f))
    except OSError as e:
        raise RunDirError(f"{path}: {e.strerror}") from e
    if not rows:
        return {}
    header = rows[0]
    body = [r for r in rows[1:] if len(r) == len(header)]
    if len(body) < len(rows) - 2:  # only the last line may be incomplete
        bad = next(i for i, r in enumerate(rows[1:], start=2) if len(r) != len(header))
        raise RunDirError(f"{path}:{bad}: {len(rows[bad - 1])} values, the header has {len(header)}")
    table = {}
    for i, name in enumerate(header):
        values = [r[i] for r in body]
        try:
            table[name] = np.array([float(v) for v in values], dtype=float)
        except ValueError:
            table[name] = np.array(values, dtype=str)
    return table


def split_by(table, column):
    """{value: sub-table} of the rows of each value of `column`, in order of first appearance
    (block_history.csv has one row per block and output: split_by(h, "block")["piston"]["velocity_x"])."""
    if column not in table:
        raise KeyError(f"no column {column!r}; columns: {', '.join(table)}")
    keys = table[column]
    out = {}
    for value in dict.fromkeys(keys.tolist()):
        rows = keys == value
        out[value] = {name: a[rows] for name, a in table.items()}
    return out


class CsvFiles(Mapping):
    """Read-only mapping name -> table of a set of CSV files, each read on first access and kept."""

    def __init__(self, paths):
        self.paths = dict(paths)  # name -> path
        self._tables = {}

    def __getitem__(self, name):
        if name not in self._tables:
            if name not in self.paths:
                raise KeyError(f"no CSV file {name!r}; there are: {', '.join(self.paths) or 'none'}")
            self._tables[name] = read_csv(self.paths[name])
        return self._tables[name]

    def __iter__(self):
        return iter(self.paths)

    def __len__(self):
        return len(self.paths)

    def __repr__(self):
        return f"CsvFiles({sorted(self.paths)})"
