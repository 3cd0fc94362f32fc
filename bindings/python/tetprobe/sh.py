"""SH helpers of the C ABI: evaluate and build the 27-float SH that stores and bakes use.

The SH contract (capi/tetprobe.h): real, orthonormal SH of 3 bands (L2), 9 coefficients per colour
channel, 27 float32 per probe, channel-major [r0..r8, g0..g8, b0..b8] (Unity's SphericalHarmonicsL2
layout), in the order L00, L1-1, L10, L11, L2-2, L2-1, L20, L21, L22 with Y1-1 ~ y, Y10 ~ z, Y11 ~ x in
the caller's own frame. A probe holds the projection of incoming radiance (not pre-convolved);
irradiance applies the clamped-cosine convolution (pi, 2pi/3, pi/4 per band).
"""

import numpy as np

from ._arrays import vector
from ._native import SH_FLOATS, check, lib


def eval_radiance(sh, direction):
    """Radiance rgb[3] float32 arriving from unit direction[3] (pointing away from the probe) for sh[27]."""
    out = np.empty(3, dtype=np.float32)
    check(lib.tp_sh_eval_radiance(vector(sh, SH_FLOATS, "sh"), vector(direction, 3, "direction"),
                                  out))
    return out


def eval_irradiance(sh, normal):
    """Irradiance rgb[3] float32 on a surface with unit normal[3] lit by the radiance sh[27] (clamped-cosine
    convolution)."""
    out = np.empty(3, dtype=np.float32)
    check(lib.tp_sh_eval_irradiance(vector(sh, SH_FLOATS, "sh"), vector(normal, 3, "normal"),
                                    out))
    return out


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
