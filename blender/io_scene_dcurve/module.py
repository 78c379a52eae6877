"""Finds the compiled dcurve module: the copy `cmake --install` ships inside this add-on,
else one installed for Blender's python (site-packages or PYTHONPATH)."""

import importlib


class ModuleMissing(RuntimeError):
    pass


def load():
    try:
        return importlib.import_module(__package__ + ".dcurve")
    except ImportError:
        pass
    try:
        return importlib.import_module("dcurve")
    except ImportError as e:
        raise ModuleMissing(
            "the dcurve Python module was not found: install the add-on from the folder or zip "
            "that `cmake --install` writes (it ships the module), or put dcurve on Blender's "
            "python path (" + str(e) + ")"
        ) from e
