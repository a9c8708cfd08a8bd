"""JSON conversion of the values NumPy and pathlib add (used by the native module)."""

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
