"""SH helpers of the C ABI (the contract is in capi/tetprobe.h): 27 floats, channel-major."""

import numpy as np

from ._arrays import vector
from ._native import SH_FLOATS, check, lib


def eval_radiance(sh, direction):
    """Radiance (r, g, b) arriving from unit `direction`."""
    out = np.empty(3, dtype=np.float32)
    check(lib.tp_sh_eval_radiance(vector(sh, SH_FLOATS, "sh"), vector(direction, 3, "direction"),
                                  out))
    return out


def eval_irradiance(sh, normal):
    """Irradiance (r, g, b) on a surface with unit `normal` (clamped-cosine convolution)."""
    out = np.empty(3, dtype=np.float32)
    check(lib.tp_sh_eval_irradiance(vector(sh, SH_FLOATS, "sh"), vector(normal, 3, "normal"),
                                    out))
    return out


def ambient(rgb, sh=None):
    """sh[27] (a new zero array when None) plus uniform radiance rgb from every direction."""
    out = np.zeros(SH_FLOATS, dtype=np.float32) if sh is None else vector(sh, SH_FLOATS, "sh").copy()
    check(lib.tp_sh_add_ambient(out, vector(rgb, 3, "rgb")))
    return out


def directional(direction, rgb, sh=None):
    """sh[27] plus a directional light travelling along `direction` with irradiance rgb facing it."""
    out = np.zeros(SH_FLOATS, dtype=np.float32) if sh is None else vector(sh, SH_FLOATS, "sh").copy()
    check(lib.tp_sh_add_directional(out, vector(direction, 3, "direction"),
                                    vector(rgb, 3, "rgb")))
    return out
