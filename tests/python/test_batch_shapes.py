"""Batches where the C ABI takes one item: sh.eval_irradiance / eval_radiance over [M, 27] with [3] or [M, 3]
(broadcast one side), store.locate over [M, 3]; checked against a numpy evaluation of the header's SH contract and
against the single calls. And $TETPROBE_LIBRARY naming a folder."""
import os
import subprocess
import sys

import numpy as np
import pytest

import tetprobe
from tetprobe import Store, sh

BANDS = np.array([np.pi] + [2 * np.pi / 3] * 3 + [np.pi / 4] * 5)


def basis(directions):
    """The header's real SH basis at unit directions [M, 3] -> [M, 9]."""
    x, y, z = np.asarray(directions, np.float64).T
    return np.stack([0.282095 * np.ones_like(x), 0.488603 * y, 0.488603 * z, 0.488603 * x, 1.092548 * x * y,
                     1.092548 * y * z, 0.315392 * (3 * z * z - 1), 1.092548 * x * z, 0.546274 * (x * x - y * y)], -1)


def unit(rows):
    return rows / np.linalg.norm(rows, axis=-1, keepdims=True)


def reference(coefficients, directions, convolve):
    """[M, 3]: each channel's 9 coefficients (times the band factors for irradiance) against the basis."""
    weights = basis(directions) * (BANDS if convolve else 1.0)
    return np.einsum("mk,mck->mc", weights, coefficients.reshape(-1, 3, 9).astype(np.float64))


def test_eval_irradiance_and_radiance_broadcast_sh_rows_against_normals():
    rng = np.random.default_rng(5)
    many_sh = rng.uniform(-1, 1, (50, 27)).astype(np.float32)
    many_normals = unit(rng.normal(size=(50, 3))).astype(np.float32)
    one_sh, one_normal = many_sh[7], many_normals[3]
    for function, convolve in ((sh.eval_irradiance, True), (sh.eval_radiance, False)):
        cases = {"[M,27] x [M,3]": (many_sh, many_normals, many_sh, many_normals),
                 "[M,27] x [3]": (many_sh, one_normal, many_sh, np.tile(one_normal, (50, 1))),
                 "[27] x [M,3]": (one_sh, many_normals, np.tile(one_sh, (50, 1)), many_normals)}
        for case, (coefficients, normals, full_sh, full_normals) in cases.items():
            out = function(coefficients, normals)
            assert out.shape == (50, 3) and out.dtype == np.float32, case
            np.testing.assert_allclose(out, reference(full_sh, full_normals, convolve), atol=2e-5, err_msg=case)
            # Bit for bit the single calls.
            singles = np.array([function(s, n) for s, n in zip(full_sh, full_normals)])
            assert np.array_equal(out, singles), case
        single = function(one_sh, one_normal)
        assert single.shape == (3,)
        # A list of rows and float64 are converted.
        assert np.array_equal(function(many_sh[:2].astype(np.float64).tolist(), one_normal),
                              function(many_sh[:2], one_normal))


def test_shapes_that_do_not_broadcast_name_the_parameter():
    rng = np.random.default_rng(6)
    many_sh = rng.uniform(-1, 1, (5, 27)).astype(np.float32)
    with pytest.raises(ValueError, match="sh has 5 rows and normal 4"):
        sh.eval_irradiance(many_sh, np.ones((4, 3)))
    with pytest.raises(ValueError, match=r"normal must have shape \[3\] or \[M, 3\]"):
        sh.eval_irradiance(many_sh, np.ones((5, 4)))
    with pytest.raises(ValueError, match=r"sh must have shape \[27\] or \[M, 27\]"):
        sh.eval_irradiance(np.ones((5, 9)), (0, 0, 1))
    with pytest.raises(ValueError, match="direction"):
        sh.eval_radiance(many_sh, np.ones((2, 2, 3)))
    with pytest.raises(TypeError, match="normal"):
        sh.eval_irradiance(many_sh, [["a", "b", "c"]])
    with pytest.raises(TypeError, match="sh"):
        sh.eval_irradiance("27 floats", (0, 0, 1))


def test_locate_takes_many_points_with_their_hints():
    rng = np.random.default_rng(7)
    positions = rng.random((60, 3)).astype(np.float32) * 4
    store = Store.build(positions, rng.uniform(-1, 1, (60, 27)).astype(np.float32))
    points = np.concatenate([rng.random((40, 3)) * 4, [[-20, 1, 1], [30, 2, 2]]]).astype(np.float32)
    batch = store.locate(points)
    assert batch["cell"].shape == (42,) and batch["probes"].shape == (42, 4) and batch["weights"].shape == (42, 4)
    assert list(batch["kind"][-2:]) == ["outer", "outer"] and (batch["kind"][:40] == "inner").sum() > 20
    for i, point in enumerate(points):
        one = store.locate(point)
        assert one["cell"] == batch["cell"][i] and one["kind"] == batch["kind"][i] and one["hint"] == batch["hint"][i]
        assert one["probes"] == batch["probes"][i].tolist() and one["weights"] == batch["weights"][i].tolist()
        assert one["steps"] == batch["steps"][i] and one["t"] == batch["t"][i] and one["fallback"] == batch["fallback"][i]
    # The weights are store.weights' and each hint is the cell found; hints given start the walks there.
    indices, weights, hints = store.weights(points)
    assert np.array_equal(batch["weights"], weights) and np.array_equal(batch["probes"], indices)
    assert np.array_equal(batch["hint"], batch["cell"]) and np.array_equal(batch["hint"], hints)
    warm = store.locate(points, hint=batch["hint"])
    assert np.array_equal(warm["cell"], batch["cell"]) and (warm["steps"] == 0).all()
    same_start = store.locate(points, hint=int(batch["cell"][0]))
    assert np.array_equal(same_start["cell"], batch["cell"])


def test_tetprobe_library_may_name_a_folder(tmp_path):
    folder = os.path.dirname(os.path.abspath(tetprobe.library_path))
    script = "import tetprobe; print(tetprobe.library_path)"
    env = dict(os.environ, TETPROBE_LIBRARY=folder)
    result = subprocess.run([sys.executable, "-c", script], capture_output=True, text=True, timeout=60, env=env)
    assert result.returncode == 0, result.stderr
    assert result.stdout.strip() == os.path.join(folder, "libtetprobe.so")
    env["TETPROBE_LIBRARY"] = str(tmp_path)  # a folder without the library: named in the error
    result = subprocess.run([sys.executable, "-c", script], capture_output=True, text=True, timeout=60, env=env)
    assert result.returncode != 0 and "TETPROBE_LIBRARY=%s cannot be loaded" % tmp_path in result.stderr
