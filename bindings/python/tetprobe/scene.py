"""Scene, bake and bake_plan: the lighting bake through the C ABI."""

import ctypes
import math
import os

import numpy as np

from . import _native
from ._handle import NativeHandle
from ._arrays import Progress, rows, vector
from ._native import SH_FLOATS, check, lib
from .errors import Error, Status

_MODES = {"baked": _native.LIGHT_MODE_BAKED, "realtime": _native.LIGHT_MODE_REALTIME}


def _mode(mode):
    try:
        return _MODES[mode]
    except KeyError:
        raise Error(Status.INVALID_ARGUMENT, "light mode must be 'baked' or 'realtime' (got %r)" % (mode,))


class Scene(NativeHandle):
    """Triangle meshes, lights, a sky and optionally probe positions, for the bake."""

    _release = staticmethod(lib.tp_scene_release)
    _noun = "scene"

    def __init__(self, _handle=None):
        if _handle is None:
            handle = ctypes.c_void_p()
            check(lib.tp_scene_create(ctypes.byref(handle)))
            _handle = handle.value
        self._adopt(_handle)

    @classmethod
    def load(cls, path):
        """Reads a JSON scene file (meshes inline or from OBJ files, lights, sky, probes)."""
        handle = ctypes.c_void_p()
        check(lib.tp_scene_load_file(os.fsencode(path), ctypes.byref(handle)))
        return cls(handle.value)

    # ---- content

    def add_mesh(self, vertices, indices, albedo=None, emission=(0.0, 0.0, 0.0), two_sided=True):
        """Adds a mesh of vertices[V, 3] and triangles indices[T, 3] with one material; returns its id.

        albedo None takes the library's default; emission is emitted radiance."""
        points, _, _ = rows(vertices, 3, "vertices")
        points = np.ascontiguousarray(points)
        triangles = np.asarray(indices)
        if triangles.size and (triangles.min() < 0 or triangles.max() > 0xFFFFFFFF):
            raise Error(Status.INVALID_ARGUMENT, "indices must be in [0, %d)" % points.shape[0])
        triangles = np.ascontiguousarray(triangles, dtype=np.uint32).reshape(-1, 3)
        material = _native.Material()
        check(lib.tp_material_init(ctypes.byref(material)))
        if albedo is not None:
            material.albedo[:] = [float(v) for v in vector(albedo, 3, "albedo")]
        material.emission[:] = [float(v) for v in vector(emission, 3, "emission")]
        material.two_sided = 1 if two_sided else 0
        mesh = ctypes.c_uint32()
        check(lib.tp_scene_add_mesh(self._live(), points, points.shape[0], triangles,
                                    triangles.shape[0], ctypes.byref(material), 1, None, ctypes.byref(mesh)))
        return mesh.value

    def _add_light(self, light_type, color, intensity, mode, shadows, **fields):
        light = _native.Light()
        check(lib.tp_light_init(ctypes.byref(light)))
        light.type = light_type
        light.mode = _mode(mode)
        light.shadows = 1 if shadows else 0
        light.color[:] = [float(v) for v in vector(color, 3, "color")]
        light.intensity = intensity
        for name, value in fields.items():
            if value is None:
                continue
            if name in ("position", "direction"):
                getattr(light, name)[:] = [float(v) for v in vector(value, 3, name)]
            else:
                setattr(light, name, float(value))
        index = ctypes.c_uint32()
        check(lib.tp_scene_add_light(self._live(), ctypes.byref(light), ctypes.byref(index)))
        return index.value

    def add_directional_light(self, direction, color, intensity=1.0, mode="baked", shadows=True):
        """A light travelling along `direction`; intensity is the irradiance on a surface facing it."""
        return self._add_light(_native.LIGHT_DIRECTIONAL, color, intensity, mode, shadows, direction=direction)

    def add_point_light(self, position, color, intensity=1.0, range=math.inf, mode="baked", shadows=True):
        """A point light of radiant intensity `intensity` (irradiance intensity/d^2 at distance d)."""
        return self._add_light(_native.LIGHT_POINT, color, intensity, mode, shadows, position=position, range=range)

    def add_spot_light(self, position, direction, color, intensity=1.0, range=math.inf, inner_angle=None,
                       outer_angle=None, mode="baked", shadows=True):
        """A spot light; angles are full cone angles in degrees (None = the library's defaults)."""
        return self._add_light(_native.LIGHT_SPOT, color, intensity, mode, shadows, position=position,
                               direction=direction, range=range, inner_angle=inner_angle, outer_angle=outer_angle)

    def set_sky(self, color=None, sh=None):
        """A sky of constant radiance color=(r, g, b), or of SH radiance sh[27]; exactly one of them."""
        if (color is None) == (sh is None):
            raise Error(Status.INVALID_ARGUMENT, "set_sky takes exactly one of color and sh")
        if color is not None:
            check(lib.tp_scene_set_sky_color(self._live(), vector(color, 3, "color")))
        else:
            check(lib.tp_scene_set_sky_sh(self._live(), vector(sh, SH_FLOATS, "sh")))

    @property
    def probes(self):
        """The scene's probe positions[N, 3] (a copy)."""
        data, count = ctypes.c_void_p(), ctypes.c_size_t()
        check(lib.tp_scene_probes(self._live(), ctypes.byref(data), ctypes.byref(count)))
        if count.value == 0:
            return np.zeros((0, 3), dtype=np.float32)
        buffer = (ctypes.c_float * (3 * count.value)).from_address(data.value)
        return np.array(buffer, dtype=np.float32).reshape(-1, 3)

    @probes.setter
    def probes(self, positions):
        points, _, _ = rows(positions, 3, "positions")
        points = np.ascontiguousarray(points)
        check(lib.tp_scene_set_probes(self._live(), points, points.shape[0]))


def _options(rays, bounces, seed, threads, progress, culling=True):
    options = _native.BakeOptions()
    check(lib.tp_bake_options_init(ctypes.byref(options)))
    for name, value in (("rays", rays), ("bounces", bounces), ("seed", seed), ("threads", threads)):
        if value < 0:
            raise Error(Status.INVALID_ARGUMENT, "%s must be >= 0 (got %d)" % (name, value))
    options.rays, options.bounces, options.seed, options.threads = rays, bounces, seed, threads
    options.flags = 0 if culling else _native.BAKE_NO_CULLING
    callback = Progress(progress)
    options.progress = callback.function
    return options, callback


def _positions(scene, positions):
    if positions is None:
        positions = scene.probes
    return rows(positions, 3, "positions")[:2]


def bake(scene, positions=None, rays=256, bounces=2, seed=0, threads=0, progress=None, culling=True):
    """Bakes the SH of incoming radiance at positions[N, 3] (None = the scene's probes) -> sh[N, 27].

    bounces counts surface reflections between an emitter and the probe; the same seed gives the
    same result whatever the thread count; progress(fraction, stage) may return True to cancel."""
    points, stride = _positions(scene, positions)
    options, callback = _options(rays, bounces, seed, threads, progress, culling)
    out = np.empty((points.shape[0], SH_FLOATS), dtype=np.float32)
    status = lib.tp_bake(scene._live(), points, stride, points.shape[0], ctypes.byref(options),
                         out, SH_FLOATS * 4)
    callback.reraise()
    check(status)
    return out


def bake_plan(scene, positions=None, rays=256, bounces=2, seed=0, threads=0, progress=None, culling=True):
    """The effects plan of a bake with the same arguments, as a dict (with its one-line summary in 'text'; the
    probes inside geometry counted in 'inside_probes' and listed in 'inside_indices')."""
    points, stride = _positions(scene, positions)
    options, _ = _options(rays, bounces, seed, threads, progress, culling)
    plan = _native.EffectsPlan()
    plan.struct_size = ctypes.sizeof(plan)
    text = ctypes.create_string_buffer(1024)
    check(lib.tp_bake_plan(scene._live(), points, stride, points.shape[0], ctypes.byref(options),
                           ctypes.byref(plan), text, len(text)))
    result = {name: getattr(plan, name) for name, _ in _native.EffectsPlan._fields_ if name != "struct_size"}
    result["sky"] = bool(plan.sky)
    result["shadows"] = bool(plan.shadows)
    result["text"] = text.value.decode("utf-8", "replace")
    # The probes inside geometry by index (their count is result["inside_probes"]).
    result["inside_indices"] = []
    if plan.inside_probes:
        from .placement import find_inside_probes
        result["inside_indices"] = [int(i) for i in find_inside_probes(scene, points)]
    return result
