"""JSON conversion of the values NumPy and pathlib add (used by the native module)."""

import math
import os


def plain(obj):
    """`json.dumps` default: NumPy scalars and arrays, paths, and rodnet scenes."""
    if hasattr(obj, "tolist"):
        return obj.tolist()
    if isinstance(obj, os.PathLike):
        return os.fspath(obj)
    if hasattr(obj, "to_dict") and type(obj).__name__ == "Scene":
        return obj.to_dict()
    raise TypeError(f"{type(obj).__name__} is not a number, string, list or dict")


def locate(obj, path=""):
    """The first value of `obj` that JSON cannot carry (a NaN or infinite number, a type
    `plain` does not convert): `(path, message)` with `path` written as scene fields are
    (`rods[0].points[1][2]`), or None. Run only after a conversion failed, to name the field."""
    if obj is None or isinstance(obj, (bool, int, str)):
        return None
    if isinstance(obj, float):
        if math.isfinite(obj):
            return None
        return path, f"must be a finite number, got {obj!r}"
    if isinstance(obj, dict):
        for key, value in obj.items():
            if not isinstance(key, str):
                return path, f"keys must be strings, got {type(key).__name__} {key!r}"
            found = locate(value, f"{path}.{key}" if path else key)
            if found:
                return found
        return None
    if isinstance(obj, (list, tuple)):
        for i, value in enumerate(obj):
            found = locate(value, f"{path}[{i}]")
            if found:
                return found
        return None
    try:
        converted = plain(obj)
    except TypeError as e:
        return path, f"expected a number, string, list or dict, got {type(obj).__name__}: {e}"
    if converted is obj:
        return None
    return locate(converted, path)
