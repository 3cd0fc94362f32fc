"""Scene, bake and bake_plan against answers known without the code."""
import math
import os

import numpy as np
import pytest

from tetprobe import Error, Scene, Status, Store, bake, bake_plan, sh

SCENES = os.path.join(os.path.dirname(__file__), "..", "..", "samples", "scenes")

QUAD = np.array([[-1, 0, -1], [1, 0, -1], [1, 0, 1], [-1, 0, 1]], dtype=np.float32)
QUAD_TRIANGLES = np.array([[0, 2, 1], [0, 3, 2]], dtype=np.uint32)


def test_uniform_sky_gives_the_constant_radiance_sh():
    scene = Scene()
    scene.set_sky(color=(0.5, 0.25, 1.0))
    positions = np.array([[0, 0, 0], [10, -3, 2]], dtype=np.float32)
    out = bake(scene, positions, rays=64, bounces=1)
    expected = sh.ambient((0.5, 0.25, 1.0))
    assert out.shape == (2, 27)
    assert np.allclose(out, expected, atol=1e-3 * expected[0])
    scene.set_sky(sh=expected)
    assert np.allclose(bake(scene, positions, rays=64), expected, atol=1e-3 * expected[0])
    plan = bake_plan(scene, positions)
    assert plan["sky"] and plan["lights"] == 0 and plan["bounces"] == 0 and "sky" in plan["text"]


def test_unoccluded_directional_light_is_the_analytic_delta():
    scene = Scene()
    direction = np.array([0.3, -1.0, 0.2])
    direction /= np.linalg.norm(direction)
    scene.add_directional_light(direction, color=(1.0, 0.5, 0.25), intensity=2.0)
    out = bake(scene, np.zeros((1, 3), dtype=np.float32), rays=16, bounces=0)
    expected = sh.directional(direction, 2.0 * np.array([1.0, 0.5, 0.25]))
    assert np.allclose(out[0], expected, atol=1e-4)


def test_point_light_follows_the_inverse_square_law():
    scene = Scene()
    scene.add_point_light((0, 0, 0), color=(1, 1, 1), intensity=4.0)
    positions = np.array([[1, 0, 0], [0, 2, 0], [0, 0, -4]], dtype=np.float32)
    out = bake(scene, positions, rays=16, bounces=0)
    irradiance_facing = [sh.eval_irradiance(out[i], -positions[i] / np.linalg.norm(positions[i]))[0] / 1.0625
                         for i in range(3)]
    assert np.allclose(irradiance_facing, [4.0, 1.0, 0.25], rtol=1e-3)


def test_an_occluder_removes_the_light_and_culling_changes_nothing():
    scene = Scene()
    scene.add_mesh(QUAD * 5 + np.array([0, 2, 0], dtype=np.float32), QUAD_TRIANGLES, albedo=(0, 0, 0))
    scene.add_directional_light((0, -1, 0), color=(1, 1, 1), intensity=3.0)
    positions = np.array([[0, 0, 0], [20, 0, 0]], dtype=np.float32)
    out = bake(scene, positions, rays=32, bounces=0)
    assert abs(out[0, 0]) < 1e-6                      # under the roof: no sun
    assert out[1, 0] == pytest.approx(3.0 * 0.282095, rel=1e-3)  # beside it: the sun
    same = bake(scene, positions, rays=32, bounces=0, culling=False)
    assert np.array_equal(out, same)


def test_realtime_light_contributes_only_bounced_light():
    scene = Scene()
    scene.add_directional_light((0, -1, 0), color=(1, 1, 1), intensity=3.0, mode="realtime")
    positions = np.zeros((1, 3), dtype=np.float32)
    assert np.allclose(bake(scene, positions, rays=32, bounces=2), 0.0)
    scene.add_mesh(QUAD * 50 + np.array([0, -1, 0], dtype=np.float32), QUAD_TRIANGLES, albedo=(0.5, 0.5, 0.5))
    plan = bake_plan(scene, positions, bounces=2)
    assert plan["realtime_lights"] == 1 and plan["direct_lights"] == 0
    out = bake(scene, positions, rays=256, bounces=1)
    down = sh.eval_irradiance(out[0], (0, -1, 0))[0]
    # Light from a lit floor below: irradiance facing it is about albedo * E (a large floor).
    assert 0.5 * 3.0 * 0.7 < down < 0.5 * 3.0 * 1.2


def test_same_seed_gives_the_same_bytes_whatever_the_thread_count():
    scene = Scene()
    scene.add_mesh(QUAD * 3 + np.array([0, -1, 0], dtype=np.float32), QUAD_TRIANGLES, albedo=(0.7, 0.7, 0.7))
    scene.add_point_light((0, 2, 0), (1, 1, 1), intensity=5.0)
    scene.set_sky(color=(0.1, 0.2, 0.3))
    rng = np.random.default_rng(1)
    positions = rng.uniform(-1, 1, (16, 3)).astype(np.float32) * np.array([1, 0.5, 1], dtype=np.float32)
    a = bake(scene, positions, rays=64, bounces=2, seed=7, threads=1)
    b = bake(scene, positions, rays=64, bounces=2, seed=7, threads=2)
    assert a.tobytes() == b.tobytes()


def test_scene_probes_bake_into_a_store():
    scene = Scene()
    scene.set_sky(color=(1, 1, 1))
    rng = np.random.default_rng(2)
    scene.probes = rng.random((20, 3)).astype(np.float32)
    assert scene.probes.shape == (20, 3)
    baked = bake(scene, rays=32)
    store = Store.build(scene.probes, baked)
    value, _ = store.interpolate([0.5, 0.5, 0.5])
    assert value[0] == pytest.approx(math.sqrt(4 * math.pi), rel=2e-3)


def test_progress_and_cancel():
    scene = Scene()
    scene.set_sky(color=(1, 1, 1))
    positions = np.zeros((4, 3), dtype=np.float32)
    seen = []
    bake(scene, positions, rays=32, progress=lambda f, stage: seen.append(f))
    assert seen and all(0.0 <= f <= 1.0 for f in seen)
    with pytest.raises(Error) as raised:
        bake(scene, positions, rays=32, progress=lambda f, stage: True)
    assert raised.value.status == Status.CANCELLED


def test_scene_errors(tmp_path):
    scene = Scene()
    with pytest.raises(Error):
        scene.add_mesh(QUAD, np.array([[0, 1, 9]]))
    nan_quad = QUAD.copy()
    nan_quad[1, 1] = np.nan
    with pytest.raises(Error):
        scene.add_mesh(nan_quad, QUAD_TRIANGLES)
    with pytest.raises(Error):
        scene.add_point_light((0, 0, 0), (1, 1, 1), intensity=-1.0)
    with pytest.raises(ValueError, match="mode"):
        scene.add_point_light((0, 0, 0), (1, 1, 1), mode="sometimes")
    with pytest.raises(ValueError, match="color and sh"):
        scene.set_sky()
    with pytest.raises(Error):
        bake(scene, np.zeros((2, 3), dtype=np.float32), rays=0)
    with pytest.raises(Error):
        Scene.load(str(tmp_path / "missing.json"))
    broken = tmp_path / "broken.json"
    broken.write_text('{"meshes": [ {"vertices": [1, 2,')
    with pytest.raises(Error) as raised:
        Scene.load(str(broken))
    assert raised.value.status == Status.SCENE and "broken.json" in raised.value.message


@pytest.mark.parametrize("name", ["cornell_box.json", "two_rooms.json", "race_track.json"])
def test_sample_scenes_load_and_plan(name):
    path = os.path.join(SCENES, name)
    if not os.path.exists(path):
        pytest.skip("%s not in samples/scenes yet" % name)
    scene = Scene.load(path)
    assert len(scene.probes) > 0
    plan = bake_plan(scene)
    assert plan["meshes"] > 0 and plan["text"]
