"""SH helpers of the C ABI: evaluate and build the 27-float SH that stores and bakes use.

The SH contract (capi/tetprobe.h): real, orthonormal SH of 3 bands (L2), 9 coefficients per colour
channel, 27 float32 per probe, channel-major [r0..r8, g0..g8, b0..b8] (Unity's SphericalHarmonicsL2
layout), in the order L00, L1-1, L10, L11, L2-2, L2-1, L20, L21, L22 with Y1-1 ~ y, Y10 ~ z, Y11 ~ x in
the caller's own frame. A probe holds the projection of incoming radiance (not pre-convolved);
irradiance applies the clamped-cosine convolution (pi, 2pi/3, pi/4 per band).
"""

import numbers
from ctypes import byref, c_float

import numpy as np

from ._arrays import UINT32_MAX, as_array, choice, integer, number, vector
from ._native import (SH_FLOATS, SH_ORDER_L1, SH_ORDER_L2, SH_ORDER_ZH3, SH_WINDOW_NONE, SH_WINDOW_NONNEGATIVE,
                      SH_WINDOW_SLOAN, ShEvalOptions, check, lib)


def _sh_rows(sh):
    """sh [27] or [M, 27] as contiguous float32 rows [M, 27], and whether it was a single [27]."""
    data = np.ascontiguousarray(as_array(sh, "sh"))
    if data.shape[-1:] != (SH_FLOATS,) or data.ndim not in (1, 2):
        raise ValueError("sh must have shape [27] or [M, 27] (got %s)" % (np.shape(sh),))
    return data.reshape(-1, SH_FLOATS), data.ndim == 1


def _evaluate(function, sh, vectors, name, *options):
    """function(sh row, vector row, *options, out row) over sh [27] or [M, 27] and vectors [3] or [M, 3]: a
    single side is used for every row of the other. Returns float32 [3] when both are single, else [M, 3]."""
    rows, single_sh = _sh_rows(sh)
    directions = np.ascontiguousarray(as_array(vectors, name))
    if directions.shape[-1:] != (3,) or directions.ndim not in (1, 2):
        raise ValueError("%s must have shape [3] or [M, 3] (got %s)" % (name, np.shape(vectors)))
    single_vector = directions.ndim == 1
    directions = directions.reshape(-1, 3)
    count = max(len(rows), len(directions))
    if len(rows) not in (1, count) or len(directions) not in (1, count):
        raise ValueError("sh has %d rows and %s %d; they must match or one of them be single" %
                         (len(rows), name, len(directions)))
    out = np.empty((count, 3), dtype=np.float32)
    for i in range(count):
        check(function(rows[i if len(rows) > 1 else 0], directions[i if len(directions) > 1 else 0], *options,
                       out[i]))
    return out[0] if single_sh and single_vector else out


def eval_radiance(sh, direction):
    """Radiance rgb float32 arriving from unit direction (pointing away from the probe) for the radiance SH sh.

    sh is [27] or [M, 27] (channel-major), direction [3] or [M, 3]; a single one of them is used for every
    row of the other. Returns [3] when both are single, else [M, 3]."""
    return _evaluate(lib.tp_sh_eval_radiance, sh, direction, "direction")


def eval_irradiance(sh, normal):
    """Irradiance rgb float32 on a surface with unit normal lit by the radiance SH sh (clamped-cosine
    convolution).

    sh is [27] or [M, 27] (channel-major), normal [3] or [M, 3]; a single one of them is used for every
    row of the other (e.g. one probe's SH under many normals, or many SH under one normal). Returns [3]
    when both are single, else [M, 3]."""
    return _evaluate(lib.tp_sh_eval_irradiance, sh, normal, "normal")


def ambient(rgb, sh=None):
    """A new sh[27] float32: sh[27] (None = zeros; not modified) plus uniform radiance rgb[3] arriving from
    every direction."""
    out = np.zeros(SH_FLOATS, dtype=np.float32) if sh is None else vector(sh, SH_FLOATS, "sh").copy()
    check(lib.tp_sh_add_ambient(out, vector(rgb, 3, "rgb")))
    return out


def directional(direction, rgb, sh=None):
    """A new sh[27] float32: sh[27] (None = zeros; not modified) plus a directional light travelling along
    unit direction[3] whose irradiance on a surface facing it is rgb[3]."""
    out = np.zeros(SH_FLOATS, dtype=np.float32) if sh is None else vector(sh, SH_FLOATS, "sh").copy()
    check(lib.tp_sh_add_directional(out, vector(direction, 3, "direction"),
                                    vector(rgb, 3, "rgb")))
    return out


#: Evaluation orders and windows (see eval_options); names or the C ABI's TP_SH_ORDER_* / TP_SH_WINDOW_* values.
ORDERS = {"l2": SH_ORDER_L2, "l1": SH_ORDER_L1, "zh3": SH_ORDER_ZH3}
WINDOWS = {"none": SH_WINDOW_NONE, "sloan": SH_WINDOW_SLOAN, "nonnegative": SH_WINDOW_NONNEGATIVE}


def _choice(value, table, name):
    """A name of table, or one of the C ABI's values (an int, checked by the library)."""
    if isinstance(value, numbers.Integral) and not isinstance(value, (bool, np.bool_)):
        return integer(value, name, 0, UINT32_MAX)
    return choice(value, table, name)


def eval_options(order="l2", window="none", strength=0.0):
    """A tp_sh_eval_options struct: order "l2" (27 floats), "l1" (bands 0-1) or "zh3" (L1 plus a zonal L2
    term estimated from it); window "none", "sloan" (band l scaled by 1 / (1 + strength (l(l+1))^2)) or
    "nonnegative" (the smallest such strength keeping the irradiance >= 0; strength not read); strength
    is a float >= 0."""
    options = ShEvalOptions()
    check(lib.tp_sh_eval_options_init(byref(options)))
    options.order = _choice(order, ORDERS, "order")
    options.window = _choice(window, WINDOWS, "window")
    options.window_strength = number(strength, "strength")
    return options


def eval_irradiance_ex(sh, normals, order="l2", window="none", strength=0.0):
    """Irradiance (r, g, b), as eval_irradiance gives it, under the evaluation options.

    sh is [27] or [M, 27] (channel-major), normals [3] or [M, 3] (unit length is not required); one side
    may be single and is then used for every row of the other. order, window and strength as in
    eval_options. Returns float32 [3] when both are single, else [M, 3]."""
    options = eval_options(order, window, strength)
    return _evaluate(lib.tp_sh_eval_irradiance_ex, sh, normals, "normals", byref(options))


def apply_options(sh, order="l2", window="none", strength=0.0):
    """A copy of sh ([27] or [M, 27], channel-major) rewritten so that plain eval_irradiance is the evaluation
    chosen by order, window and strength (as in eval_options)."""
    options = eval_options(order, window, strength)
    rows, single = _sh_rows(sh)
    out = rows.copy()
    for row in out:
        check(lib.tp_sh_apply_options(row, byref(options)))
    return out[0] if single else out


def min_irradiance(sh, order="l2", window="none", strength=0.0):
    """(min_rgb, normal): each channel's smallest irradiance over all unit normals under the options, and
    the unit normal where the smallest of the three occurs; [3] and [3] for sh [27], [M, 3] each for
    [M, 27]. order, window and strength as in eval_options. Exact to double rounding (the trust-region
    solution), not sampled."""
    options = eval_options(order, window, strength)
    rows, single = _sh_rows(sh)
    minima = np.empty((len(rows), 3), dtype=np.float32)
    normals = np.empty((len(rows), 3), dtype=np.float32)
    for i, row in enumerate(rows):
        check(lib.tp_sh_min_irradiance(row, byref(options), minima[i], normals[i]))
    return (minima[0], normals[0]) if single else (minima, normals)


def nonnegative_window_strength(sh, order="l2"):
    """The Sloan window strength the "nonnegative" window picks for sh under order (as in eval_options): a
    float for sh [27], an array [M] for [M, 27]; 0 when the irradiance is already non-negative, inf if no
    finite one does."""
    options = eval_options(order)
    rows, single = _sh_rows(sh)
    out = np.empty(len(rows), dtype=np.float32)
    value = c_float()
    for i, row in enumerate(rows):
        check(lib.tp_sh_nonnegative_window_strength(row, byref(options), byref(value)))
        out[i] = value.value
    return float(out[0]) if single else out
