"""The XDMF index of a snapshot series (fluid.xmf, solid.xmf, interface.xmf): its times and HDF5 files.

The solvers rewrite the index after each complete snapshot, so it lists only snapshots that are whole.
"""
import xml.etree.ElementTree as ET
from pathlib import Path

from .errors import RunDirError


def read_index(path):
    """[(time, h5 path)] of the snapshots an XDMF temporal collection lists, in its order."""
    path = Path(path)
    try:
        root = ET.parse(path).getroot()
    except OSError as e:
        raise RunDirError(f"{path}: {e.strerror}") from e
    except ET.ParseError as e:
        raise RunDirError(f"{path}: not a readable XDMF file ({e})") from e
    entries = []
    for grid in root.iter("Grid"):
        if grid.get("GridType") == "Collection":
            continue
        name = grid.get("Name", "?")
        time = grid.find("Time")
        if time is None or time.get("Value") is None:
            raise RunDirError(f"{path}: grid {name} has no <Time Value=...>")
        try:
            t = float(time.get("Value"))
        except ValueError as e:
            raise RunDirError(f"{path}: grid {name}: time {time.get('Value')!r} is not a number") from e
        files = {item.text.strip().split(":", 1)[0] for item in grid.iter("DataItem")
                 if item.get("Format") == "HDF" and item.text and item.text.strip()}
        if len(files) != 1:
            raise RunDirError(f"{path}: grid {name} refers to {len(files)} HDF5 files, expected one")
        entries.append((t, path.parent / files.pop()))
    return entries
