"""Leak control and occlusion probes through the Python binding: Store.build(scene=, occlusion=),
store.interpolate(occlusion=True), bake_occlusion and the "mixed" light mode."""

import numpy as np
import pytest

import tetprobe


def wall_scene(mixed=True):
    """A two-sided wall in the plane x = 0.37 (below y = 0.6) and a mixed light travelling +x."""
    scene = tetprobe.Scene()
    vertices = np.array([[0.37, -10, -10], [0.37, 0.6, -10], [0.37, 0.6, 10], [0.37, -10, 10]], np.float32)
    scene.add_mesh(vertices, np.array([[0, 1, 2], [0, 2, 3]], np.uint32), two_sided=True)
    scene.add_directional_light((1, 0, 0), (1, 1, 1), mode="mixed" if mixed else "realtime")
    return scene


def lattice():
    axis = np.arange(-2, 3, dtype=np.float32)
    return np.stack(np.meshgrid(axis, axis, axis, indexing="ij"), -1).reshape(-1, 3)


def test_occlusion_probes_blend_the_quantised_visibility():
    scene, probes = wall_scene(), lattice()
    occlusion, lights = tetprobe.bake_occlusion(scene, probes)
    assert lights == 1 and occlusion.shape == (125, 4)
    behind = (probes[:, 0] > 0.37) & (probes[:, 1] < 0.6)
    assert np.all(occlusion[behind, 0] == 0) and np.all(occlusion[~behind, 0] == 255)
    assert np.all(occlusion[:, 1:] == 255)
    store = tetprobe.Store.build(probes, occlusion=occlusion, occlusion_lights=lights)
    assert store.info()["occlusion_lights"] == 1
    points = np.random.default_rng(3).uniform(-2, 2, (500, 3)).astype(np.float32)
    sh, visible, _ = store.interpolate(points, occlusion=True)
    indices, weights, _ = store.weights(points)
    expected = (weights * occlusion[indices, 0] / 255.0).sum(axis=1)
    np.testing.assert_allclose(visible[:, 0], np.clip(expected, 0, 1), atol=1e-6)
    assert np.all(visible[:, 1:] == 1.0)
    plain_sh, _ = store.interpolate(points)
    assert np.array_equal(sh, plain_sh)


def test_leak_control_weighs_down_probes_behind_the_wall():
    scene, probes = wall_scene(), lattice()
    plain = tetprobe.Store.build(probes)
    leak = tetprobe.Store.build(probes, scene=scene)
    assert plain.info()["leak_edges"] == 0 and leak.info()["leak_edges"] > 20
    assert leak.info()["format_version"] == 6
    rng = np.random.default_rng(8)
    points = np.column_stack([rng.uniform(0.45, 0.9, 400), rng.uniform(-2, 0, 400),
                              rng.uniform(-2, 2, 400)]).astype(np.float32)
    behind = probes[:, 0] < 0.37
    far = []
    for store in (plain, leak):
        indices, weights, _ = store.weights(points)
        far.append((weights * behind[indices]).sum(axis=1).mean())
        np.testing.assert_allclose(weights.sum(axis=1), 1.0, atol=1e-5)
    assert far[0] > 0.2 and far[1] < 0.1 * far[0]
    # Exact at every probe, and a round trip keeps the leak data.
    indices, weights, _ = leak.weights(probes)
    assert np.all(weights.max(axis=1) == 1.0)
    again = tetprobe.Store.load(leak.to_bytes())
    assert np.array_equal(again.interpolate(points)[0], leak.interpolate(points)[0])


def test_bad_occlusion_input_is_refused():
    probes = lattice()
    with pytest.raises(ValueError, match="occlusion"):
        tetprobe.Store.build(probes, occlusion=np.zeros((3, 4), np.uint8))
    with pytest.raises(tetprobe.Error) as error:
        tetprobe.Store.build(probes, occlusion=np.zeros((125, 4), np.uint8), occlusion_lights=5)
    assert "occlusion_lights" in str(error.value)
    scene = tetprobe.Scene()
    for x in range(4):
        scene.add_point_light((x, 0, 0), (1, 1, 1), mode="mixed")
    with pytest.raises(tetprobe.Error) as error:
        scene.add_point_light((5, 0, 0), (1, 1, 1), mode="mixed")
    assert error.value.status == tetprobe.Status.SCENE and "fifth mixed light" in str(error.value)
