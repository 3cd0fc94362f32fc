"""Automatic probe placement and probes inside geometry, through the C ABI."""

import collections
import ctypes

import numpy as np

from . import _native
from ._arrays import UINT32_MAX, UINT64_MAX, Progress, choice, integer, number, rows, vector
from ._native import check, lib
from .scene import scene_argument

#: place_probes' result: positions[N, 3] float32 in the order chosen (refined at the target: a smaller
#: target's set need not be a prefix; an error-bound result and large targets are the greedy's order) and error_curve[K, 2] float32 of (probe count, estimated error), counts increasing to the result.
Placement = collections.namedtuple("Placement", ["positions", "error_curve"])

_MODES = {"whole": _native.PLACEMENT_WHOLE, "walkable": _native.PLACEMENT_WALKABLE}
_FIXES = {"drop": _native.INSIDE_DROP, "push": _native.INSIDE_PUSH}


def place_probes(scene, mode="whole", spacing=1.0, margin=0.1, walk_height=(0.0, 2.0), target=0, error_bound=None,
                 rays=128, bounces=2, seed=0, threads=0, progress=None, light_clearance=1.0):
    """Proposes probe positions for a scene -> Placement(positions[N, 3], error_curve[K, 2]).

    Candidates on a lattice of `spacing` (world units) over the scene (mode "whole") or across
    walk_height=(min, max) world units above upward-facing surfaces (the scene's up; mode "walkable"), none inside
    geometry or within `margin` (world units) of a surface, only those connected to the scene's playable
    seeds when it has some; baked with `rays` per candidate (in two halves) and `bounces`, then chosen by
    greedy insertion up to `target` probes or until the estimated error is at most error_bound (default
    0.25 without a target, none with one; 0 = none; with neither, every candidate is returned unbaked).
    The error: RMS over validation points and the 6 axis normals of the luminance irradiance's
    interpolation error, relative to its mean, with the bake's noise taken out; points closer than
    `light_clearance` to a point or spot light do not count. positions[N, 3] are float32 world units in
    the order chosen (refined at the target: a smaller target's set need not be a prefix; an error-bound result and
    large targets are the greedy's order); error_curve[K, 2] holds (probe count,
    error), counts increasing to the result. The same `seed` gives the same result whatever the `threads`
    count (0 = all cores); progress(fraction, stage) may return True to cancel (Error(CANCELLED));
    `scene` is a Scene or the path of a scene file."""
    options = _placement_options(mode, spacing, margin, walk_height, target, error_bound, rays, bounces, seed,
                                 threads, light_clearance)
    callback = Progress(progress)
    with scene_argument(scene) as scene:
        bound = _placement_bound(scene, options)
        options.progress = callback.function
        positions = np.empty((bound, 3), dtype=np.float32)
        curve = np.empty((bound + 1, 2), dtype=np.float32)
        count, points = ctypes.c_size_t(), ctypes.c_size_t()
        status = lib.tp_place_probes(scene._live(), ctypes.byref(options), positions, bound, ctypes.byref(count),
                                     curve, bound + 1, ctypes.byref(points))
    callback.reraise()
    check(status)
    return Placement(positions[:count.value].copy(), curve[:points.value].copy())


def _placement_options(mode, spacing, margin, walk_height, target, error_bound, rays, bounces, seed, threads,
                       light_clearance=None):
    """place_probes' arguments as a tp_placement_options (without progress)."""
    options = _native.PlacementOptions()
    check(lib.tp_placement_options_init(ctypes.byref(options)))
    options.mode = choice(mode, _MODES, "mode")
    options.spacing, options.margin = number(spacing, "spacing"), number(margin, "margin")
    options.walk_min_height, options.walk_max_height = (float(v) for v in vector(walk_height, 2, "walk_height"))
    options.target_count = integer(target, "target", 0, UINT32_MAX)
    if error_bound is None:
        error_bound = 0.0 if target else options.error_bound
    options.error_bound = number(error_bound, "error_bound")
    options.rays = integer(rays, "rays", 0, UINT32_MAX)
    options.bounces = integer(bounces, "bounces", 0, UINT32_MAX)
    options.seed = integer(seed, "seed", 0, UINT64_MAX)
    options.threads = integer(threads, "threads", 0, UINT32_MAX)
    if light_clearance is not None:
        options.light_clearance = number(light_clearance, "light_clearance")
    return options


def _placement_bound(scene, options):
    """tp_place_probes_bound: the most probes (and curve points) a placement with options returns.
    The command line calls it on its own to name the failing step as the C tool does."""
    bound = ctypes.c_size_t()
    check(lib.tp_place_probes_bound(scene._live(), ctypes.byref(options), ctypes.byref(bound)))
    return bound.value


def find_inside_probes(scene, positions):
    """Indices (ascending, int64) of the probes at positions[N, 3] (float32 world units) that are inside
    the geometry of `scene` (a Scene or a scene file's path): behind a one-sided triangle or within a
    closed mesh."""
    points, stride, _ = rows(positions, 3, "positions")
    out = np.empty(points.shape[0], dtype=np.uint32)
    count = ctypes.c_size_t()
    with scene_argument(scene) as scene:
        check(lib.tp_find_inside_probes(scene._live(), points, stride, points.shape[0], out, out.shape[0],
                                        ctypes.byref(count)))
    return out[:count.value].astype(np.int64)


def fix_inside_probes(scene, positions, mode="drop", margin=0.1):
    """The probes at positions[N, 3] (float32 world units) with those inside the geometry of `scene` (a
    Scene or a scene file's path) dropped (mode "drop") or pushed out to at least `margin` (world units,
    >= 0) from every surface (mode "push", every probe kept in order) -> positions[M, 3] float32."""
    fix = choice(mode, _FIXES, "mode")
    margin = number(margin, "margin")
    points, stride, _ = rows(positions, 3, "positions")
    out = np.empty((points.shape[0], 3), dtype=np.float32)
    count = ctypes.c_size_t()
    with scene_argument(scene) as scene:
        check(lib.tp_fix_inside_probes(scene._live(), points, stride, points.shape[0], fix, margin, out,
                                       out.shape[0], ctypes.byref(count)))
    return out[:count.value].copy()
