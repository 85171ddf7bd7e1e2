"""The generated protocol module coupling_pb2 (protoc output of proto/coupling.proto), as `coupling_pb2`.

Where it is taken from, in this order:
  1. cosim/coupling_pb2.py, beside this file (a build's <build>/python/cosim/, an installed package);
  2. for the package of a source checkout (<repo>/python/cosim): the build's, <repo>/build/python/cosim/.
Else ImportError: build first. Load it only through this module (a second copy imported under another name
would register coupling.proto twice).
"""
import importlib
import importlib.util
import sys
from pathlib import Path

_HERE = Path(__file__).resolve().parent
_NAME = f"{__package__}.coupling_pb2"


def source_tree_root():
    """The repository root when this package is <repo>/python/cosim of a source checkout, else None."""
    root = _HERE.parent.parent
    if _HERE.parent.name == "python" and (root / "proto" / "coupling.proto").is_file():
        return root
    return None


def fallback_paths():
    """The files tried, in order, when cosim/coupling_pb2.py is not beside this file."""
    root = source_tree_root()
    return [] if root is None else [root / "build" / "python" / "cosim" / "coupling_pb2.py"]


def _load_file(path):
    spec = importlib.util.spec_from_file_location(_NAME, path)
    module = importlib.util.module_from_spec(spec)
    sys.modules[_NAME] = module
    try:
        spec.loader.exec_module(module)
    except BaseException:
        del sys.modules[_NAME]
        raise
    return module


def load():
    """The coupling_pb2 module (see the module's docstring for where it comes from)."""
    if _NAME in sys.modules:
        return sys.modules[_NAME]
    if importlib.util.find_spec(_NAME) is not None:
        from . import coupling_pb2
        return coupling_pb2
    tried = fallback_paths()
    for path in tried:
        if path.is_file():
            return _load_file(path)
    raise ImportError(
        f"cosim.client needs the generated protocol module coupling_pb2.py, which the build makes from "
        f"proto/coupling.proto with protoc: build first (scripts/build.sh), or put it in {_HERE}; looked in "
        + ", ".join(str(p) for p in [_HERE / "coupling_pb2.py"] + tried), name=_NAME)


coupling_pb2 = load()
