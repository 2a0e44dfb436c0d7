"""Energy Redistribution Path Tracing from Python.

    import erpt
    scene = erpt.load_scene("scenes/default/scene.xml", defaults={"spp": 16})
    result = erpt.render(scene, "erpt", spp=8, width=256, height=256, seed=1)
    result.image            # linear float32 array, shape (height, width, 3)
    result.stats            # the render's statistics, as numbers
    result.write("out.exr") # as the CLI writes it (and out.png beside it)
    erpt.diff(result.image, "reference.exr")

Every render option of `erpt render --help` is a keyword argument of render(), dashes as
underscores, validated by the integrator's own option table; errors raise erpt.Error (a
RuntimeError) with the CLI's one-line `file:line: cause` text, and a common option of the wrong
type or out of the CLI's range raises erpt.OptionTypeError (also a TypeError) or
erpt.OptionValueError (also a ValueError) naming it and its range. Without an integrator,
render() uses the scene's, as the CLI does. The image of render() is bit-identical to the CLI's
for the same scene, seed and options. The loader's warnings are Python warnings
(erpt.SceneWarning).
"""

import sys as _sys

from . import _build_info

__version__ = _build_info.version

try:
    from ._erpt import (Error, OptionTypeError, OptionValueError, Result, Scene, SceneWarning, diff, integrators,
                        load_scene, read_image, render, tonemap)
except ImportError as _error:
    if _sys.version_info[:2] != _build_info.python:
        raise ImportError(
            "erpt's compiled part was built for Python %d.%d (%s), and this is Python %d.%d (%s): run it with that "
            "interpreter, or build erpt for this one" % (*_build_info.python, _build_info.interpreter,
                                                         *_sys.version_info[:2], _sys.executable)) from _error
    raise

__all__ = ["Error", "OptionTypeError", "OptionValueError", "Result", "Scene", "SceneWarning", "compare", "diff",
           "integrators", "load_scene", "read_image", "render", "tonemap"]


def compare(scene, reference, integrators=("path", "erpt"), time=10.0, **options):
    """Renders `scene` with each integrator for the same wall-clock budget `time` (seconds) and
    measures it against `reference` (an image or a path), as `erpt compare` does.

    An entry of `integrators` is a name or a (name, {option: value}) pair whose options apply
    to that entry only; `options` apply to every entry. Returns one dict per entry, the fields
    of `erpt compare`'s compare.json: integrator, seconds, spp, passes, mutations, mse,
    rel_mse, eff = 1 / (T MSE), eff_rel = 1 / (T relMSE), nonfinite_pixels, and curve (the
    error after every pass: [{seconds, mse, rel_mse}, ...]). erpt.plot draws it.
    """
    if isinstance(reference, str) or hasattr(reference, "__fspath__"):
        reference = read_image(str(reference))
    rows = []
    for entry in integrators:
        if isinstance(entry, str):
            name, own, label = entry, {}, entry
        else:
            name, own = entry[0], dict(entry[1])
            label = name + "[" + " ".join(f"--{k.replace('_', '-')} {v}" for k, v in own.items()) + "]"
        result = render(scene, name, reference=reference, time=time, **{**options, **own})
        d = diff(result.image, reference)
        seconds = result.curve[-1]["seconds"] if result.curve else result.stats["seconds"]
        rows.append({
            "integrator": label,
            "seconds": seconds,
            "spp": result.stats["spp"],
            "passes": result.stats["passes"],
            "mutations": result.stats.get("mutations", 0),
            "mse": d["mse"],
            "rel_mse": d["rel_mse"],
            "eff": 1.0 / (seconds * d["mse"]) if seconds > 0 and d["mse"] > 0 else 0.0,
            "eff_rel": 1.0 / (seconds * d["rel_mse"]) if seconds > 0 and d["rel_mse"] > 0 else 0.0,
            "nonfinite_pixels": d["nonfinite_pixels"],
            "curve": list(result.curve),
        })
    return rows
