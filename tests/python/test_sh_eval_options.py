"""SH evaluation options through the C ABI: identities, analytic answers, brute force and bad arguments."""
import ctypes
import math
import os
import re

import numpy as np
import pytest

from tetprobe import Error, Status, sh
from tetprobe import _native

Y = (0.28209479177387814, 0.4886025119029199, 1.0925484305920792, 0.31539156525252005, 0.5462742152960396)
BAND_FACTORS = np.array([math.pi] + [2 * math.pi / 3] * 3 + [math.pi / 4] * 5)


def fibonacci_sphere(count):
    i = np.arange(count) + 0.5
    z = 1 - 2 * i / count
    r = np.sqrt(1 - z * z)
    phi = math.pi * (3 - math.sqrt(5)) * np.arange(count)
    return np.stack([r * np.cos(phi), r * np.sin(phi), z], axis=1)


def irradiance(sh27, normals):
    """[N, 3] irradiance in double from the contract's basis: the slow reference."""
    x, y, z = normals[:, 0], normals[:, 1], normals[:, 2]
    basis = np.stack([np.full_like(x, Y[0]), Y[1] * y, Y[1] * z, Y[1] * x, Y[2] * x * y, Y[2] * y * z,
                      Y[3] * (3 * z * z - 1), Y[2] * x * z, Y[4] * (x * x - y * y)], axis=1) * BAND_FACTORS
    return basis @ np.asarray(sh27, dtype=np.float64).reshape(3, 9).T


def random_sh(rng, count, spread=0.6):
    out = rng.uniform(-spread, spread, size=(count, 27)).astype(np.float32)
    out[:, [0, 9, 18]] = rng.uniform(0.5, 1.5, size=(count, 3))
    return out


def test_defaults_equal_the_plain_evaluation_bit_for_bit():
    rng = np.random.default_rng(1)
    coefficients = random_sh(rng, 1, 3.0)[0]
    normals = fibonacci_sphere(50).astype(np.float32)
    plain = np.array([sh.eval_irradiance(coefficients, n) for n in normals])
    assert np.array_equal(sh.eval_irradiance_ex(coefficients, normals), plain)
    out = np.empty(3, dtype=np.float32)
    assert _native.lib.tp_sh_eval_irradiance_ex(coefficients, normals[0], None, out) == 0
    assert np.array_equal(out, plain[0])


@pytest.mark.parametrize("order", ["l2", "l1", "zh3"])
@pytest.mark.parametrize("window,strength", [("none", 0.0), ("sloan", 0.05), ("nonnegative", 0.0)])
def test_apply_then_plain_evaluation_is_the_evaluation_with_options(order, window, strength):
    rng = np.random.default_rng(2)
    rows = random_sh(rng, 4)
    normals = fibonacci_sphere(4).astype(np.float32)
    applied = sh.apply_options(rows, order, window, strength)
    assert applied.shape == (4, 27)
    plain = np.array([sh.eval_irradiance(applied[i], normals[i]) for i in range(4)])
    assert np.array_equal(sh.eval_irradiance_ex(rows, normals, order, window, strength), plain)
    assert np.array_equal(applied[1], sh.apply_options(rows[1], order, window, strength))


def test_l1_zeroes_band_two_and_zh3_writes_a_zonal_term():
    light = sh.directional([0, 0, -1], [1, 1, 1])
    l1 = sh.apply_options(light, "l1")
    assert np.array_equal(l1.reshape(3, 9)[:, :4], light.reshape(3, 9)[:, :4])
    assert not l1.reshape(3, 9)[:, 4:].any()
    zh3 = sh.apply_options(light, "zh3").reshape(3, 9)
    # A light from +z: zonal about z, z = Y1 (0.08 + 0.6 sqrt 3), written as z sqrt(4pi/5) Y20(z axis).
    zonal = Y[1] * (0.08 + 0.6 * math.sqrt(3))
    assert zh3[:, 6] == pytest.approx(zonal * math.sqrt(4 * math.pi / 5) * 2 * Y[3], rel=1e-6)
    assert np.abs(zh3[:, [4, 5, 7, 8]]).max() < 1e-7


def test_min_irradiance_against_100k_directions():
    rng = np.random.default_rng(3)
    directions = fibonacci_sphere(100000)
    h = 2 * math.sqrt(4 * math.pi / 100000)
    rows = random_sh(rng, 6)
    minima, normals = sh.min_irradiance(rows)
    assert minima.shape == (6, 3) and normals.shape == (6, 3)
    for row, found, normal in zip(rows, minima, normals):
        brute = irradiance(row, directions).min(axis=0)
        channels = row.astype(np.float64).reshape(3, 9)
        b = (2 * math.pi / 3) * Y[1] * np.linalg.norm(channels[:, 1:4], axis=1)
        a = (math.pi / 4) * (Y[2] * np.abs(channels[:, [4, 5, 7]]).sum(axis=1) + 2 * Y[4] * np.abs(channels[:, 8])
                             + 3 * Y[3] * np.abs(channels[:, 6]))
        scale = (BAND_FACTORS * np.abs(channels)).sum(axis=1)
        assert np.all(found <= brute + 1e-6 * scale)
        assert np.all(found >= brute - 0.5 * (b + 4 * a) * h * h - 1e-6 * scale)
        smallest = int(np.argmin(found))
        at_normal = irradiance(row, normal[None, :].astype(np.float64))[0, smallest]
        assert at_normal == pytest.approx(found[smallest], abs=1e-5 * scale[smallest])


def test_nonnegative_window():
    light = sh.directional([0.36, -0.48, 0.8], [1.0, 0.5, 2.0])
    # L1 of a directional light: E (1/4 + w1 cos / 2) >= 0 exactly when 1 / (1 + 4 s) <= 1/2.
    assert sh.nonnegative_window_strength(light, "l1") == pytest.approx(0.25, rel=1e-5)
    # L2: E (3/32 + t/2 + 15/32 t^2) dips to -0.0396 E at t = -8/15; windowed, the minimum sits at t = -1
    # once the window holds it there, so the strength is the root of 1/4 - w1/2 + 5/16 w2 = 0.
    minima, _ = sh.min_irradiance(light)
    assert minima == pytest.approx((3 / 32 - 1 / (4 * 15 / 8)) * np.array([1.0, 0.5, 2.0]), rel=1e-5)
    # The window must also clear the float evaluation's proven rounding bound, 21 * 2^-24 * S with
    # S = sum of band factor * |coefficient| * basis magnitude (tetprobe.h), here per unit E.
    toward_light = -np.array([0.36, -0.48, 0.8])
    x, y, z = toward_light
    coefficients = np.abs([Y[0], Y[1] * y, Y[1] * z, Y[1] * x, Y[2] * x * y, Y[2] * y * z, Y[3] * (3 * z * z - 1),
                           Y[2] * x * z, Y[4] * (x * x - y * y)])
    magnitudes = np.array([Y[0], Y[1], Y[1], Y[1], Y[2], Y[2], 4 * Y[3], Y[2], Y[4]])
    low, high = 0.0, 1.0
    for _ in range(60):
        mid = 0.5 * (low + high)
        windows = np.array([1.0] + [1 / (1 + 4 * mid)] * 3 + [1 / (1 + 36 * mid)] * 5)
        margin = 21 * 2.0 ** -24 * (BAND_FACTORS * coefficients * windows * magnitudes).sum()
        low, high = (low, mid) if 0.25 - 0.5 * windows[1] + 0.3125 * windows[4] >= margin else (mid, high)
    assert sh.nonnegative_window_strength(light, "l2") == pytest.approx(high, rel=2e-6)
    assert sh.nonnegative_window_strength(sh.ambient([1, 2, 3]), "l2") == 0.0
    rng = np.random.default_rng(4)
    rows = random_sh(rng, 8)
    strengths = sh.nonnegative_window_strength(rows)
    before, _ = sh.min_irradiance(rows)
    assert np.array_equal(strengths > 0, before.min(axis=1) < 0)
    windowed = sh.apply_options(rows, "l2", "nonnegative")
    same = sh.apply_options(rows[0], "l2", "sloan", strengths[0])
    assert np.array_equal(windowed[0], same)
    directions = fibonacci_sphere(20000)
    for row in windowed:
        assert irradiance(row, directions).min() >= 0
    after, _ = sh.min_irradiance(rows, "l2", "nonnegative")
    assert after.min() >= 0


@pytest.mark.parametrize("order", ["l2", "l1", "zh3"])
def test_nonnegative_window_keeps_the_float_evaluation_non_negative(order):
    """The shipped float evaluation through the C ABI, not a double reference: at the normal
    min_irradiance reports and at 2000 lattice normals, for 300 random SH per order."""
    rng = np.random.default_rng(7)
    rows = np.concatenate([random_sh(rng, 150, 0.6), random_sh(rng, 150, 2.0)])
    lattice = fibonacci_sphere(2000).astype(np.float32)
    minima, normals = sh.min_irradiance(rows, order, "nonnegative")
    assert minima.min() >= 0
    assert sh.eval_irradiance_ex(rows, normals, order, "nonnegative").min() >= 0
    applied = sh.apply_options(rows, order, "nonnegative")
    assert (sh.nonnegative_window_strength(rows, order) > 0).sum() >= 150
    for row in applied:
        assert sh.eval_irradiance_ex(row, lattice).min() >= 0


def test_bad_arguments():
    coefficients = sh.ambient([1, 1, 1])
    with pytest.raises(ValueError):
        sh.eval_options(order="l3")
    for order, window, strength in ((3, "none", 0.0), ("l2", 7, 0.0), ("l2", "sloan", float("nan")),
                                    ("l2", "sloan", -0.5), ("l2", "sloan", float("inf"))):
        with pytest.raises(Error) as raised:
            sh.eval_irradiance_ex(coefficients, [0, 0, 1], order, window, strength)
        assert raised.value.status == Status.INVALID_ARGUMENT
        with pytest.raises(Error):
            sh.apply_options(coefficients, order, window, strength)
        with pytest.raises(Error):
            sh.min_irradiance(coefficients, order, window, strength)
    # The strength is read for the Sloan window only.
    assert sh.eval_irradiance_ex(coefficients, [0, 0, 1], "l1", "none", float("nan")) == pytest.approx(math.pi)
    with pytest.raises(Error) as raised:
        sh.eval_irradiance_ex(coefficients, [0, 0, 0], "l1")
    assert raised.value.status == Status.INVALID_ARGUMENT
    with pytest.raises(Error):
        sh.min_irradiance(np.full(27, np.nan, dtype=np.float32))
    with pytest.raises(Error):
        sh.apply_options(np.full(27, np.inf, dtype=np.float32), "l2", "nonnegative")

    lib, out = _native.lib, np.empty(3, dtype=np.float32)
    options = sh.eval_options()
    assert options.struct_size == ctypes.sizeof(_native.ShEvalOptions) and options.order == 0 and options.window == 0
    normal = np.array([0, 0, 1], dtype=np.float32)
    assert lib.tp_sh_eval_irradiance_ex(None, normal, ctypes.byref(options), out) == Status.INVALID_ARGUMENT
    assert "sh" in _native.last_error()
    assert lib.tp_sh_apply_options(None, None) == Status.INVALID_ARGUMENT
    assert lib.tp_sh_min_irradiance(coefficients, None, None, out) == Status.INVALID_ARGUMENT
    assert lib.tp_sh_nonnegative_window_strength(coefficients, None, None) == Status.INVALID_ARGUMENT
    assert lib.tp_sh_eval_options_init(None) == Status.INVALID_ARGUMENT
    options.struct_size = 0
    assert lib.tp_sh_apply_options(coefficients.copy(), ctypes.byref(options)) == Status.INVALID_ARGUMENT
    assert "struct_size" in _native.last_error()
    # The nonnegative strength reads the order only: bad window fields are not its business.
    light = sh.directional([0.36, -0.48, 0.8], [1.0, 0.5, 2.0])
    strength = ctypes.c_float(-1.0)
    for window, window_strength in ((7, 0.0), (1, -0.5), (1, float("nan"))):
        options = _native.ShEvalOptions(ctypes.sizeof(_native.ShEvalOptions), 1, window, window_strength)
        assert lib.tp_sh_nonnegative_window_strength(light, ctypes.byref(options), ctypes.byref(strength)) == 0
        assert strength.value == sh.nonnegative_window_strength(light, "l1")
    options = _native.ShEvalOptions(ctypes.sizeof(_native.ShEvalOptions), 3, 0, 0.0)
    assert lib.tp_sh_nonnegative_window_strength(light, ctypes.byref(options), ctypes.byref(strength)) != 0
    assert "order" in _native.last_error()
    # A caller built against a struct holding only the order: the rest keep their defaults.
    options = sh.eval_options("l1", "sloan", float("nan"))
    options.struct_size = 8
    assert lib.tp_sh_eval_irradiance_ex(coefficients, normal, ctypes.byref(options), out) == 0


def test_constants_and_struct_match_the_header():
    with open(os.path.join(os.path.dirname(__file__), "..", "..", "capi", "tetprobe.h")) as f:
        defines = dict(re.findall(r"#define\s+(TP_SH_\w+)\s+(\d+)u", f.read()))
    for name in ("ORDER_L2", "ORDER_L1", "ORDER_ZH3", "WINDOW_NONE", "WINDOW_SLOAN", "WINDOW_NONNEGATIVE"):
        assert int(defines["TP_SH_" + name]) == getattr(_native, "SH_" + name)
    assert ctypes.sizeof(_native.ShEvalOptions) == 16
