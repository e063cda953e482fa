"""lfsp: light-field superpixels for lenslet (Lytro) cameras, on numpy arrays.

The same library calls as the `lfsp` command line, with the same option names (as keywords: --lambda-p is
lambda_p), defaults and checks:

    import lfsp
    lf = lfsp.decode("capture.LFR")                      # or lfsp.read("views/"), or lfsp.LightField(array)
    disparity, confidence = lfsp.depth(lf)
    labels = lfsp.segment(lf, disparity, size=20)
    scores = lfsp.evaluate_segmentation(labels, gt_labels=truth.labels, gt_disparity=truth.disparity)

A LightField's arrays (samples, weights, disparity, labels) are numpy views of its own memory, never copies. Bad
input raises lfsp.Error (a ValueError) with the command line's one-line message; Ctrl-C stops long work (raising
KeyboardInterrupt); long work runs without the GIL, so other Python threads go on meanwhile.
"""

import atexit
import os
import tempfile
from typing import Any, NamedTuple, Optional

import numpy

# Passive OpenMP waiting unless the user chose otherwise, as the `lfsp` executable does
# (core/startup/omp_wait_policy.cc says why). libgomp reads it once, when the extension below first loads it.
if "OMP_WAIT_POLICY" not in os.environ and "GOMP_SPINCOUNT" not in os.environ:
    os.environ["OMP_WAIT_POLICY"] = "passive"

from . import _lfsp  # noqa: E402
from ._lfsp import (
    Error,
    LightField,
    all_in_focus,
    decode,
    depth,
    evaluate_depth,
    evaluate_segmentation,
    grid,
    read,
    read_disparity,
    recolor,
    refocus,
    segment,
    set_log_level,
    set_progress,
    shear,
    write,
    write_disparity,
)

# The same string as `lfsp --version`, every summary JSON and the installed package's metadata.
__version__: str = _lfsp.__version__

__all__ = [
    "Error",
    "LightField",
    "Simulation",
    "all_in_focus",
    "decode",
    "depth",
    "evaluate_depth",
    "evaluate_segmentation",
    "grid",
    "read",
    "read_disparity",
    "recolor",
    "refocus",
    "segment",
    "set_log_level",
    "set_progress",
    "shear",
    "simulate",
    "write",
    "write_disparity",
]

# Shown as lfsp.LightField and lfsp.Error, where users meet them.
LightField.__module__ = "lfsp"
Error.__module__ = "lfsp"

# A progress callback is a Python object held by the library: let it go while the interpreter can still free it.
atexit.register(set_progress, None)


class Simulation(NamedTuple):
    """What simulate() returns: the light field with its exact ground truth."""

    light_field: Optional[LightField]  # the ideal light field, or the capture's ideal decode (None for calibration)
    disparity: Optional[numpy.ndarray]  # true centre-view disparity (H, W), pixels per view step
    labels: Optional[numpy.ndarray]  # true object label of every ray (nv, nu, H, W)
    summary: dict  # what `lfsp simulate` records: scene, camera, files written, timings
    out: Optional[str]  # the folder the files were written to (None when a temporary one was used)


def _load_simulation(folder: str, summary: dict, out: Optional[str]) -> Simulation:
    for name in ("ideal.h5", os.path.join("ground_truth", "decoded.h5")):
        path = os.path.join(folder, name)
        if os.path.exists(path):
            light_field = read(path)
            return Simulation(light_field, light_field.disparity, light_field.labels, summary, out)
    return Simulation(None, None, None, summary, out)


def simulate(out: "Optional[str | os.PathLike[str]]" = None, **options: Any) -> Simulation:
    """Renders a synthetic scene with its exact ground truth, as `lfsp simulate` does.

    With `out`, writes there what `lfsp simulate --out OUT` writes (the lenslet capture with white images, or
    ideal.h5 with ideal_only=True) and returns the ideal light field (for a capture: the ideal decode on the decoded
    grid, ground_truth/decoded.h5) with its disparity and labels. Without `out`, a temporary folder is used and
    ideal_only defaults to True, since a capture would be deleted with it.
    """
    if out is None:
        options.setdefault("ideal_only", True)
        with tempfile.TemporaryDirectory(prefix="lfsp-simulate-") as folder:
            return _load_simulation(folder, _lfsp._simulate(folder, **options), None)
    folder = os.fspath(out)
    return _load_simulation(folder, _lfsp._simulate(folder, **options), folder)


simulate.__doc__ += (
    "\n    Keyword options (the command line's --option-name, written option_name):\n" + _lfsp._simulate_keywords
)
