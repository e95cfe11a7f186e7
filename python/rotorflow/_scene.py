"""The JSON of a scene run with its numbers as numpy arrays."""

import numpy as np


def arrays(value):
    """`value` (parsed JSON) with every rectangular list of numbers as a float64 array."""
    if isinstance(value, dict):
        return {key: arrays(v) for key, v in value.items()}
    if isinstance(value, list):
        if value and all(isinstance(v, (dict, str)) for v in value):
            return [arrays(v) for v in value]
        try:
            return np.asarray(value, dtype=np.float64)
        except (TypeError, ValueError):
            return [arrays(v) for v in value]
    return value


def scene(source, *, samples=None, times=None):
    """Runs a scene (a file path or a ``Scene``) and returns the keys of
    ``rotorflow scene --output`` with the numbers as arrays."""
    from ._rotorflow import Scene

    if not isinstance(source, Scene):
        source = Scene(source)
    return source.run(samples=samples, times=times).data()
