"""SH helpers and shadow caster volumes, against analytic answers."""
import math

import numpy as np
import pytest

from tetprobe import Error, Status, sh, shadow_caster_volume, volume_test_aabb, volume_test_sphere

CUBE = np.array([[1, 0, 0, 1], [-1, 0, 0, 1], [0, 1, 0, 1], [0, -1, 0, 1], [0, 0, 1, 1], [0, 0, -1, 1]],
                dtype=np.float32)


def test_ambient_gives_constant_radiance_and_pi_irradiance():
    coefficients = sh.ambient([0.5, 1.0, 2.0])
    for direction in ([1, 0, 0], [0, 0, -1], [0.6, 0.0, 0.8]):
        assert np.allclose(sh.eval_radiance(coefficients, direction), [0.5, 1.0, 2.0], rtol=1e-5)
        assert np.allclose(sh.eval_irradiance(coefficients, direction), np.pi * np.array([0.5, 1.0, 2.0]),
                           rtol=1e-5)
    assert coefficients[0] == pytest.approx(0.5 * math.sqrt(4 * math.pi), rel=1e-5)


def test_directional_light_follows_the_l2_cosine_lobe():
    coefficients = sh.directional([0, 0, -1], [1.0, 2.0, 3.0])
    for normal, factor in (([0, 0, 1], 1.0625), ([0, 0, -1], 0.0625), ([1, 0, 0], 0.09375)):
        assert np.allclose(sh.eval_irradiance(coefficients, normal), factor * np.array([1.0, 2.0, 3.0]), rtol=1e-4)
    both = sh.ambient([1, 1, 1], coefficients)
    assert np.allclose(both - coefficients, sh.ambient([1, 1, 1]), atol=1e-6)


def test_sh_errors():
    with pytest.raises(ValueError):
        sh.eval_radiance(np.zeros(9), [0, 0, 1])
    with pytest.raises(Error) as raised:
        sh.eval_irradiance(np.zeros(27), [np.nan, 0, 1])
    assert raised.value.status == Status.INVALID_ARGUMENT


def corners():
    return np.array([[x, y, z] for x in (-1, 1) for y in (-1, 1) for z in (-1, 1)], dtype=np.float64)


def test_point_light_volume_is_the_hull_of_box_and_light():
    light = np.array([0.0, 5.0, 0.0])
    for form in ({"type": "point", "position": light}, ("point", light)):
        planes = shadow_caster_volume(CUBE, form)
        assert planes.shape[1] == 4 and 5 <= len(planes)
        values = np.vstack([corners(), light]) @ planes[:, :3].T + planes[:, 3]
        assert np.all(values >= -1e-4 * np.linalg.norm(planes[:, :3], axis=1))
        assert volume_test_sphere(planes, [0, 3, 0], 0.1)
        assert not volume_test_sphere(planes, [0, 7, 0], 0.5)
        assert not volume_test_sphere(planes, [3, 3, 0], 0.5)
        assert volume_test_aabb(planes, [-0.2, 1.5, -0.2], [0.2, 2.5, 0.2])
        assert not volume_test_aabb(planes, [3, -1, 3], [4, 0, 4])


def test_directional_light_volume_is_infinite_towards_the_light():
    planes = shadow_caster_volume(CUBE, {"type": "directional", "direction": [0, -1, 0]})
    assert volume_test_sphere(planes, [0, 1000, 0], 0.5)
    assert not volume_test_sphere(planes, [0, -5, 0], 1.0)
    assert not volume_test_aabb(planes, [5, 10, 5], [6, 11, 6])
    rng = np.random.default_rng(3)
    # Every point above the cube inside its footprint is inside every plane (no false negatives).
    points = np.column_stack([rng.uniform(-1, 1, 200), rng.uniform(-1, 100, 200), rng.uniform(-1, 1, 200)])
    assert np.all(points @ planes[:, :3].T + planes[:, 3] >= -1e-3)


def test_volume_errors():
    with pytest.raises(ValueError, match="light type"):
        shadow_caster_volume(CUBE, {"type": "area", "position": [0, 0, 0]})
    with pytest.raises(ValueError, match="position"):
        shadow_caster_volume(CUBE, {"type": "point"})
    with pytest.raises(Error):
        shadow_caster_volume(CUBE, ("point", [np.nan, 0, 0]))
    with pytest.raises(ValueError):
        shadow_caster_volume(CUBE[:, :3], ("point", [0, 5, 0]))
    with pytest.raises(Error):
        volume_test_sphere(CUBE, [0, 0, 0], -1.0)
