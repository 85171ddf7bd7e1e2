"""A run directory as one object: scene, summaries, snapshot series and CSV histories.

Layouts read (docs/output.md):

    cosim run SCENE --out DIR           DIR/scene.yaml, launch.json, run_summary.json, energy_account.json,
                                        fluid/ (fluid.xmf, fluid_NNNNNN.h5, fluid_interface_NNNNNN.csv,
                                        summary.json), solid/ (solid.xmf, solid_NNNNNN.h5, block_history.csv,
                                        summary.json; a Python piston's piston.csv), coupler/ (interface.xmf,
                                        interface_NNNNNN.h5, interface_history.csv, timing.csv,
                                        coupler_summary.json); a fluid-only run has fluid/ alone
    fluid_solver SCENE --out DIR        DIR/fluid.xmf, fluid_NNNNNN.h5, summary.json
    solid_solver SCENE --out DIR        DIR/solid.xmf, solid_NNNNNN.h5, block_history.csv, summary.json
"""
import json
from pathlib import Path

from .errors import RunDirError
from .scene import load_scene, lookup, parse_value
from .series import Series
from .tables import CsvFiles

_SKIPPED = ("checkpoints", "plots")  # subdirectories whose CSV files are not the run's own histories


def _load_json(path):
    try:
        with open(path) as f:
            return json.load(f)
    except OSError as e:
        raise RunDirError(f"{path}: {e.strerror}") from e
    except ValueError as e:
        raise RunDirError(f"{path}: not valid JSON ({e})") from e


def _json_if_file(path):
    return _load_json(path) if path.is_file() else None


def _overrides(launch):
    """{key: value} of the --set options the launcher gave its processes (launch.json)."""
    commands = (launch or {}).get("commands") or {}
    out = {}
    for argv in commands.values():
        for flag, arg in zip(argv, argv[1:]):
            if flag == "--set" and "=" in arg:
                key, text = arg.split("=", 1)
                out[key] = parse_value(text)
        break  # every process gets the same overrides
    return out


def _csv_files(directory):
    """{name: path} of every CSV file under directory (name: the file's stem; its path relative to the directory,
    without .csv, where two files share a stem)."""
    paths = sorted(p for p in directory.rglob("*.csv")
                   if p.is_file() and not set(p.relative_to(directory).parts[:-1]) & set(_SKIPPED))
    stems = [p.stem for p in paths]
    return {(p.stem if stems.count(p.stem) == 1 else p.relative_to(directory).with_suffix("").as_posix()): p
            for p in paths}


class Run:
    """A run directory (see the module's docstring for the layouts).

    directory; name (the scene's name, else the directory's); kind ("coupled", "fluid", "solid" or "empty":
    what ran, or what wrote output); scene (the parsed scene copy DIR/scene.yaml, as written, or None);
    overrides ({key: value} of the run's --set options, from launch.json); setting(key) (a scene value with the
    overrides applied); summary (run_summary.json of the launcher, or None); summaries ({"fluid", "solid",
    "coupler": parsed summary JSON} of the processes that wrote one); energy_account (or None); launch
    (launch.json or None); fluid, solid, interface (Series or None); histories (every CSV file in the run
    directory, read on first access: {name: {column: numpy array}}, name the file's stem such as
    "interface_history", "timing", "block_history", "piston", "fluid_interface_000003"); logs ({process: path}
    of the launcher's logs)."""

    def __init__(self, directory):
        d = Path(directory)
        if not d.exists():
            raise RunDirError(f"{d}: no such directory")
        if not d.is_dir():
            raise RunDirError(f"{d}: not a directory (expected a run directory)")
        self.directory = d
        self.scene_path = d / "scene.yaml"
        self.scene = load_scene(self.scene_path) if self.scene_path.is_file() else None
        self.launch = _json_if_file(d / "launch.json")
        self.summary = _json_if_file(d / "run_summary.json")
        self.energy_account = _json_if_file(d / "energy_account.json")
        self.overrides = _overrides(self.launch)
        self.summaries = {}
        self.fluid = self._series("fluid", [d / "fluid", d], "summary.json")
        self.solid = self._series("solid", [d / "solid", d], "summary.json")
        self.interface = self._series("interface", [d / "coupler"], None)
        coupler_summary = d / "coupler" / "coupler_summary.json"
        if coupler_summary.is_file():
            self.summaries["coupler"] = _load_json(coupler_summary)
        self.histories = CsvFiles(_csv_files(d))
        self.logs = {p.stem: p for p in sorted(d.glob("*.log"))}
        if not (self.scene is not None or self.summary or self.fluid or self.solid or self.interface
                or self.summaries):
            raise RunDirError(
                f"{d}: not a run directory: expected scene.yaml and run_summary.json (cosim run), or snapshots "
                f"with their index (fluid.xmf / fluid_NNNNNN.h5, solid.xmf / solid_NNNNNN.h5) in it or in its "
                f"fluid/ or solid/ folder")

    def _series(self, name, places, summary_name):
        """The series `name` in the first of `places` that holds it (None if none); its process's summary."""
        for place in places:
            if place.is_dir() and Series.holds(name, place):
                if summary_name and (place / summary_name).is_file():
                    self.summaries[name] = _load_json(place / summary_name)
                return Series(name, place)
        own = places[0] / summary_name if summary_name else None
        if own is not None and own != self.directory / summary_name and own.is_file():
            self.summaries[name] = _load_json(own)  # e.g. a failed process that wrote its summary, no snapshot
        return None

    @property
    def name(self):
        if self.scene and "name" in self.scene:
            return str(self.scene["name"])
        for summary in self.summaries.values():
            if "scene" in summary:
                return str(summary["scene"])
        return self.directory.resolve().name

    @property
    def kind(self):
        if self.launch is not None and "coupled" in self.launch:
            return "coupled" if self.launch["coupled"] else "fluid"
        if self.interface is not None or (self.fluid is not None and self.solid is not None):
            return "coupled"
        if self.fluid is not None:
            return "fluid"
        if self.solid is not None:
            return "solid"
        return "empty"

    def setting(self, key, default=None):
        """The scene's value at a dotted key ("coupling.time.end"), a --set override of the run first."""
        if key in self.overrides:
            return self.overrides[key]
        return lookup(self.scene or {}, key, default)

    def __repr__(self):
        parts = [f"{n}: {len(s)} snapshots" for n, s in (("fluid", self.fluid), ("solid", self.solid),
                                                          ("interface", self.interface)) if s is not None]
        return f"Run({self.directory}, {self.kind}, {', '.join(parts) or 'no snapshots'})"


def read_run(directory):
    """The Run of a run directory; RunDirError (naming the directory and what was expected) when it is not one."""
    return Run(directory)
