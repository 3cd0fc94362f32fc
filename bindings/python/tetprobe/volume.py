"""Shadow caster volumes: the region that can cast shadows from a light into a convex polyhedron."""

import ctypes

import numpy as np

from . import _native
from ._arrays import number, rows, vector
from ._native import check, lib

_TYPES = {"directional": (_native.LIGHT_DIRECTIONAL, "direction"), "point": (_native.LIGHT_POINT, "position"),
          "spot": (_native.LIGHT_SPOT, "position")}


def _light(light):
    """(type, vector) from {"type": "point", "position": xyz}, {"type": "directional", "direction": xyz}
    or a pair ("point", xyz) / ("directional", xyz)."""
    if isinstance(light, dict):
        kind = light.get("type")
        if not isinstance(kind, str):
            raise TypeError("light type must be a string, one of %s (got %r)" % (sorted(_TYPES), kind))
        if kind not in _TYPES:
            raise ValueError("light type must be one of %s (got %r)" % (sorted(_TYPES), kind))
        key = _TYPES[kind][1]
        if key not in light:
            raise ValueError("a %s light needs '%s'" % (kind, key))
        value = light[key]
    else:
        try:
            kind, value = light
        except (TypeError, ValueError):
            raise TypeError("light must be a dict or a (type, xyz) pair (got %r)" % (light,)) from None
        if not isinstance(kind, str):
            raise TypeError("light type must be a string, one of %s (got %r)" % (sorted(_TYPES), kind))
        if kind not in _TYPES:
            raise ValueError("light type must be one of %s (got %r)" % (sorted(_TYPES), kind))
    return _TYPES[kind][0], vector(value, 3, "light vector")


def _planes(planes):
    data, _, _ = rows(planes, 4, "planes")
    return np.ascontiguousarray(data)


def shadow_caster_volume(planes, light):
    """The shadow caster volume of `light` into a region: planes[K, 4] -> planes[J, 4] float32.

    planes[K, 4]: float32 rows (nx, ny, nz, d) of inward planes (a point x is inside when n.x + d >= 0)
    bounding a convex polyhedron, e.g. a view frustum or the probes' bounding box, in world units.
    light: {"type": "point" or "spot", "position": (x, y, z)}, {"type": "directional", "direction":
    (x, y, z)} (the direction the light travels), or a pair such as ("point", (x, y, z)). The result
    holds everything that can cast a shadow from the light into the region, in the same plane form;
    test objects against it with volume_test_aabb and volume_test_sphere."""
    data = _planes(planes)
    light_type, light_vector = _light(light)
    capacity = lib.tp_shadow_caster_volume_bound(data.shape[0])
    out = np.empty((max(capacity, 1), 4), dtype=np.float32)
    count = ctypes.c_size_t()
    check(lib.tp_shadow_caster_volume(data, data.shape[0], light_type, light_vector, out,
                                      capacity, ctypes.byref(count)))
    return out[:count.value].copy()


def volume_test_aabb(planes, box_min, box_max):
    """Whether the axis-aligned box box_min[3]..box_max[3] (world units) may intersect the volume of
    inward planes[K, 4] (rows nx, ny, nz, d): False only if it certainly lies outside (conservative)."""
    data = _planes(planes)
    hit = ctypes.c_int()
    check(lib.tp_volume_test_aabb(data, data.shape[0], vector(box_min, 3, "box_min"),
                                  vector(box_max, 3, "box_max"), ctypes.byref(hit)))
    return bool(hit.value)


def volume_test_sphere(planes, center, radius):
    """Whether the sphere of center[3] and radius (world units, >= 0) may intersect the volume of inward
    planes[K, 4] (rows nx, ny, nz, d): False only if it certainly lies outside (conservative)."""
    data = _planes(planes)
    hit = ctypes.c_int()
    check(lib.tp_volume_test_sphere(data, data.shape[0], vector(center, 3, "center"),
                                    number(radius, "radius"), ctypes.byref(hit)))
    return bool(hit.value)
