"""Scene files (YAML) and their dotted keys ("coupling.time.end", "solid.blocks.0.density").

Numbers are read as the C++ programs read them: "2e5" is a float here too (plain PyYAML, which follows YAML 1.1,
would leave it a string).
"""
import re

import yaml

from .errors import RunDirError

_FLOAT = re.compile(r"^[-+]?(\.[0-9]+|[0-9]+(\.[0-9]*)?)([eE][-+]?[0-9]+)?$"
                    r"|^[-+]?\.(inf|Inf|INF)$|^\.(nan|NaN|NAN)$")


class _SceneLoader(yaml.SafeLoader):
    """SafeLoader that reads YAML 1.2 floats ("1e-3", "2E5")."""


_SceneLoader.add_implicit_resolver("tag:yaml.org,2002:float", _FLOAT, list("-+0123456789."))


def parse_scene(text, name="<scene>"):
    """The parsed mapping of a scene's text; RunDirError naming `name` when it is not a YAML mapping."""
    try:
        data = yaml.load(text, Loader=_SceneLoader)
    except yaml.YAMLError as e:
        raise RunDirError(f"{name}: not valid YAML ({e})") from e
    if data is None:
        return {}
    if not isinstance(data, dict):
        raise RunDirError(f"{name}: expected a mapping of sections (fluid:, solid:, coupling:), "
                          f"got {type(data).__name__}")
    return data


def load_scene(path):
    """The parsed scene file at `path`."""
    try:
        with open(path) as f:
            text = f.read()
    except OSError as e:
        raise RunDirError(f"{path}: {e.strerror}") from e
    return parse_scene(text, str(path))


def parse_value(text):
    """An override's value as the scene would hold it: "1e-3" -> 0.001, "[160, 8]" -> [160, 8], "robin" -> "robin"."""
    try:
        return yaml.load(text, Loader=_SceneLoader)
    except yaml.YAMLError:
        return text


def format_value(value):
    """A Python value as the text of `--set key=value`: 1e-3 -> "0.001", [160, 8] -> "[160, 8]", True -> "true"."""
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, (list, tuple)):
        return "[" + ", ".join(format_value(v) for v in value) + "]"
    if isinstance(value, float):
        return repr(value)
    return str(value)


_MISSING = object()


def lookup(scene, key, default=_MISSING):
    """The value at a dotted key of a parsed scene (list items by index); `default`, else KeyError, when absent."""
    node = scene
    for part in key.split("."):
        if isinstance(node, dict) and part in node:
            node = node[part]
        elif isinstance(node, list) and part.isdigit() and int(part) < len(node):
            node = node[int(part)]
        else:
            if default is _MISSING:
                raise KeyError(key)
            return default
    return node
