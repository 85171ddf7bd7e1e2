"""Exit 0 when two runs' fluid snapshot series hold the same times and bit-for-bit equal fields, else name the
first difference. Usage: same_snapshots.py RUN_A/fluid RUN_B/fluid"""
import pathlib
import sys

import h5py
import numpy as np


def datasets(path):
    found = {}
    with h5py.File(path, "r") as f:
        f.visititems(lambda name, item: found.__setitem__(name, item[()]) if isinstance(item, h5py.Dataset) else None)
    return found


def main(a, b):
    files_a = sorted(p.name for p in pathlib.Path(a).glob("*.h5"))
    files_b = sorted(p.name for p in pathlib.Path(b).glob("*.h5"))
    if not files_a:
        return f"{a}: no snapshots"
    if files_a != files_b:
        return f"snapshot files differ: {files_a} against {files_b}"
    for name in files_a:
        da, db = datasets(pathlib.Path(a) / name), datasets(pathlib.Path(b) / name)
        if sorted(da) != sorted(db):
            return f"{name}: datasets {sorted(da)} against {sorted(db)}"
        for key, value in da.items():
            other = db[key]
            if value.shape != other.shape or value.dtype != other.dtype:
                return f"{name}:{key}: shape {value.shape} {value.dtype} against {other.shape} {other.dtype}"
            if value.tobytes() != other.tobytes():
                where = np.argwhere(value != other)
                return f"{name}:{key}: {len(where)} values differ, first at {where[0].tolist() if len(where) else '?'}"
    print(f"{len(files_a)} snapshots equal bit for bit")
    return None


if __name__ == "__main__":
    problem = main(sys.argv[1], sys.argv[2])
    if problem:
        print(problem)
        sys.exit(1)
