"""Scene, bake and bake_plan: the lighting bake through the C ABI."""

import contextlib
import ctypes
import math
import os

import numpy as np

from . import _native
from ._handle import NativeHandle
from ._arrays import UINT32_MAX, UINT64_MAX, Progress, choice, flag, integer, number, path, rows, vector
from ._native import SH_FLOATS, check, lib

_MODES = {"baked": _native.LIGHT_MODE_BAKED, "realtime": _native.LIGHT_MODE_REALTIME,
          "mixed": _native.LIGHT_MODE_MIXED}


class Scene(NativeHandle):
    """Triangle meshes, lights, a sky and optionally probe positions, for the bake (bake-time library only:
    the run-time library raises Error(UNSUPPORTED)). Positions are float32 world units; colours are
    linear RGB. Scene() is empty; Scene.load reads a glTF, FBX, OBJ or JSON scene file. close() or `with`
    releases it."""

    _release = staticmethod(lib.tp_scene_release)
    _noun = "scene"

    def __init__(self, _handle=None):
        if _handle is None:
            handle = ctypes.c_void_p()
            check(lib.tp_scene_create(ctypes.byref(handle)))
            _handle = handle.value
        self._adopt(_handle)

    @classmethod
    def load(cls, path, scale=None, up=None):
        """Reads the scene file at path: glTF 2.0 (.gltf, .glb), FBX, OBJ (with its .mtl) or a JSON scene
        (docs/scene-format.md), told by its first bytes, then its extension.

        scale: world units per unit of the file (a number > 0; None = the file's own unit in metres: glTF
        and OBJ 1, FBX its UnitScaleFactor / 100; a JSON scene is in world units); positions and ranges
        scale, point and spot intensities by the square of world units per metre. up: which way is up in
        the file, "+x", "-x", "+y", "-y", "+z" or "-z" (None = what the file says: glTF and OBJ "+y", FBX
        its UpAxis, a JSON scene its "up"); coordinates are kept and the scene records it (Scene.up).
        What the file holds that a bake cannot use (cameras, textures, animations, area lights) is left
        out and listed in Scene.notes. An invalid file raises Error(SCENE) naming the file and what is
        wrong; a missing one Error(IO)."""
        encoded = _path_argument(path, "path")
        handle = ctypes.c_void_p()
        if scale is None and up is None:
            check(lib.tp_scene_load_file(encoded, ctypes.byref(handle)))
            return cls(handle.value)
        options = _native.SceneLoadOptions()
        check(lib.tp_scene_load_options_init(ctypes.byref(options)))
        if scale is not None:
            options.scale = number(scale, "scale")
            if not options.scale > 0 or math.isinf(options.scale):
                raise ValueError("scale must be a finite number > 0 (got %r)" % (scale,))
        if up is not None:
            options.up = choice(up, _native.UP_AXES, "up")
        check(lib.tp_scene_load_file_ex(encoded, ctypes.byref(options), ctypes.byref(handle)))
        return cls(handle.value)

    @property
    def notes(self):
        """What loading the scene left out or converted (cameras, textures, animations, area lights,
        Assimp's warnings), a list of str, one per note; [] for a scene built in code."""
        size = ctypes.c_size_t()
        check(lib.tp_scene_notes(self._live(), None, 0, ctypes.byref(size)))
        text = ctypes.create_string_buffer(size.value)
        check(lib.tp_scene_notes(self._live(), text, len(text), None))
        return text.value.decode("utf-8", "replace").splitlines()

    @property
    def up(self):
        """Which way is up in the scene: "+x", "-x", "+y", "-y", "+z" or "-z" ("+y" unless loaded or set
        otherwise); placement's walkable mode stands probes on floors along it. Assign one to change it."""
        value = ctypes.c_uint32()
        check(lib.tp_scene_up(self._live(), ctypes.byref(value)))
        return {code: name for name, code in _native.UP_AXES.items()}[value.value]

    @up.setter
    def up(self, axis):
        check(lib.tp_scene_set_up(self._live(), choice(axis, _native.UP_AXES, "up")))

    # ---- content

    def add_mesh(self, vertices, indices, albedo=None, emission=(0.0, 0.0, 0.0), two_sided=True):
        """Adds a mesh of vertices[V, 3] (float32 world units) and triangles indices[T, 3] (integers in
        [0, V), counter-clockwise seen from the front) with one material; returns the mesh's id (int).

        albedo=(r, g, b): diffuse reflectance, each in [0, 1] (None = the library's default);
        emission=(r, g, b): emitted radiance, >= 0; two_sided=False makes only the front face reflect
        and emit.
        An index outside [0, V) raises Error(INVALID_ARGUMENT) from the library."""
        points, _, _ = rows(vertices, 3, "vertices")
        points = np.ascontiguousarray(points)
        triangles, _, _ = rows(indices, 3, "indices", np.uint32)
        triangles = np.ascontiguousarray(triangles)
        material = _native.Material()
        check(lib.tp_material_init(ctypes.byref(material)))
        if albedo is not None:
            material.albedo[:] = [float(v) for v in vector(albedo, 3, "albedo")]
        material.emission[:] = [float(v) for v in vector(emission, 3, "emission")]
        material.two_sided = 1 if flag(two_sided, "two_sided") else 0
        mesh = ctypes.c_uint32()
        check(lib.tp_scene_add_mesh(self._live(), points, points.shape[0], triangles,
                                    triangles.shape[0], ctypes.byref(material), 1, None, ctypes.byref(mesh)))
        return mesh.value

    def _add_light(self, light_type, color, intensity, mode, shadows, **fields):
        light = _native.Light()
        check(lib.tp_light_init(ctypes.byref(light)))
        light.type = light_type
        light.mode = choice(mode, _MODES, "mode")
        light.shadows = 1 if flag(shadows, "shadows") else 0
        light.color[:] = [float(v) for v in vector(color, 3, "color")]
        light.intensity = number(intensity, "intensity")
        for name, value in fields.items():
            if value is None:
                continue
            if name in ("position", "direction"):
                getattr(light, name)[:] = [float(v) for v in vector(value, 3, name)]
            else:
                setattr(light, name, number(value, name))
        index = ctypes.c_uint32()
        check(lib.tp_scene_add_light(self._live(), ctypes.byref(light), ctypes.byref(index)))
        return index.value

    def add_directional_light(self, direction, color, intensity=1.0, mode="baked", shadows=True):
        """Adds a directional light travelling along direction=(x, y, z) (need not be unit length) of linear
        color=(r, g, b); intensity scales color to the irradiance on a surface facing the light.
        mode: "baked" (direct and bounced light go into the probes), "realtime" (the engine draws the
        direct light; only its bounced light is baked) or "mixed" (baked as realtime, plus its occlusion
        probes from bake_occlusion; at most four per scene); shadows: whether it casts shadows. Returns the
        light's id (int)."""
        return self._add_light(_native.LIGHT_DIRECTIONAL, color, intensity, mode, shadows, direction=direction)

    def add_point_light(self, position, color, intensity=1.0, range=math.inf, mode="baked", shadows=True,
                        near_distance=0.0):
        """Adds a point light at position=(x, y, z) (world units) of linear color=(r, g, b) and radiant
        intensity `intensity` (irradiance color * intensity / d^2 at distance d, facing it), no light
        beyond range (world units, math.inf = unlimited); closer than near_distance (world units, 0 = none)
        the irradiance stays at its value at that distance (a light compiler's near-field clamp); mode and
        shadows as in add_directional_light. Returns the light's id (int)."""
        return self._add_light(_native.LIGHT_POINT, color, intensity, mode, shadows, position=position, range=range,
                               near_distance=near_distance)

    def add_spot_light(self, position, direction, color, intensity=1.0, range=math.inf, inner_angle=None,
                       outer_angle=None, mode="baked", shadows=True, near_distance=0.0):
        """Adds a spot light at position=(x, y, z) (world units) shining along direction=(x, y, z) of linear
        color=(r, g, b), intensity, range and near_distance as add_point_light; inner_angle and outer_angle are full
        cone angles in degrees (full intensity inside inner_angle, none beyond outer_angle; None = the
        library's defaults); mode and shadows as in add_directional_light. Returns the light's id (int)."""
        return self._add_light(_native.LIGHT_SPOT, color, intensity, mode, shadows, position=position,
                               direction=direction, range=range, inner_angle=inner_angle, outer_angle=outer_angle,
                               near_distance=near_distance)

    def set_sky(self, color=None, sh=None):
        """Sets the sky: constant linear radiance color=(r, g, b), or radiance given as SH sh[27] (float32,
        channel-major, the SH contract of tetprobe.sh); exactly one of them."""
        rgb = None if color is None else vector(color, 3, "color")
        radiance = None if sh is None else vector(sh, SH_FLOATS, "sh")
        if (rgb is None) == (radiance is None):
            raise ValueError("set_sky takes exactly one of color and sh")
        if rgb is not None:
            check(lib.tp_scene_set_sky_color(self._live(), rgb))
        else:
            check(lib.tp_scene_set_sky_sh(self._live(), radiance))

    @property
    def probes(self):
        """The scene's probe positions as positions[N, 3] float32 world units (a copy); assign an [N, 3]
        array to replace them."""
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

    def set_playable_seeds(self, positions):
        """Points known to be where objects go (spawn points), positions[N, 3] float32 world units (N = 0
        clears them): place_probes then keeps only candidates connected to a seed. A Quake 3 level loaded
        with Scene.load has its spawn points as seeds."""
        points, _, _ = rows(positions, 3, "positions")
        points = np.ascontiguousarray(points)
        check(lib.tp_scene_set_playable_seeds(self._live(), points if points.shape[0] else None, points.shape[0]))


def _path_argument(value, name):
    return path(value, name)


@contextlib.contextmanager
def scene_argument(scene, optional=False):
    """The Scene a `scene` parameter names: a Scene as it is, or the path of a scene file loaded for the
    call (and released after it); None when optional. TypeError naming the parameter otherwise."""
    if scene is None and optional:
        yield None
    elif isinstance(scene, Scene):
        yield scene
    elif isinstance(scene, (str, bytes, os.PathLike)):
        with Scene.load(scene) as loaded:
            yield loaded
    else:
        raise TypeError("scene must be a tetprobe.Scene or the path of a scene file (got %s)" % type(scene).__name__)


def _options(rays, bounces, seed, threads, progress, culling=True):
    options = _native.BakeOptions()
    check(lib.tp_bake_options_init(ctypes.byref(options)))
    options.rays = integer(rays, "rays", 0, UINT32_MAX)
    options.bounces = integer(bounces, "bounces", 0, UINT32_MAX)
    options.seed = integer(seed, "seed", 0, UINT64_MAX)
    options.threads = integer(threads, "threads", 0, UINT32_MAX)
    options.flags = 0 if flag(culling, "culling") else _native.BAKE_NO_CULLING
    callback = Progress(progress)
    options.progress = callback.function
    return options, callback


def _positions(scene, positions):
    if positions is None:
        positions = scene.probes
    return rows(positions, 3, "positions")[:2]


def bake(scene, positions=None, rays=256, bounces=2, seed=0, threads=0, progress=None, culling=True):
    """Bakes the SH of incoming radiance at positions[N, 3] (float32 world units; None = the scene's
    probes) -> sh[N, 27] float32, channel-major [r0..r8, g0..g8, b0..b8] (radiance, not pre-convolved;
    feed it to Store.build).

    scene: a Scene, or the path of a scene file (loaded for the call). rays: rays per probe; bounces:
    surface reflections between an emitter (light, sky, emissive surface) and the probe (0 = only light
    arriving directly); seed: the same seed gives the same bytes whatever the thread count; threads:
    worker threads (0 = all cores); progress: a callable progress(fraction, stage) that may return True
    to cancel (Error(CANCELLED)); culling=False turns off shadow-caster culling (a test aid: same
    result, slower)."""
    options, callback = _options(rays, bounces, seed, threads, progress, culling)
    with scene_argument(scene) as scene:
        points, stride = _positions(scene, positions)
        out = np.empty((points.shape[0], SH_FLOATS), dtype=np.float32)
        status = lib.tp_bake(scene._live(), points, stride, points.shape[0], ctypes.byref(options),
                             out, SH_FLOATS * 4)
    callback.reraise()
    check(status)
    return out


def bake_plan(scene, positions=None, rays=256, bounces=2, seed=0, threads=0, progress=None, culling=True):
    """What bake(scene, positions, ...) with the same arguments will simulate, as a dict: lights,
    direct_lights, realtime_lights, out_of_range_lights, sky (bool), emissive_meshes, bounces, shadows
    (bool), meshes, shadow_casters, shadow_caster_candidates, inside_probes (probes inside geometry),
    inside_indices (their indices) and text (the one-line summary).

    scene (a Scene or a scene file's path), positions[N, 3] (float32 world units; None = the scene's
    probes), rays, bounces, seed, threads, progress and culling as in bake; progress is not called
    (planning is quick)."""
    options, _ = _options(rays, bounces, seed, threads, progress, culling)
    with scene_argument(scene) as scene:
        points, stride = _positions(scene, positions)
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


def bake_occlusion(scene, positions=None, progress=None):
    """Occlusion probes at positions[N, 3] (float32 world units; None = the scene's probes) ->
    (occlusion[N, 4] uint8, mixed_lights).

    scene: a Scene or a scene file's path; progress(fraction, stage) may return True to cancel
    (Error(CANCELLED)). Byte i is 255 x the visibility of the scene's i-th mixed light from the position
    (one shadow ray: 0 or 255), 255 for channels without a light; pass it to Store.build(...,
    occlusion=...)."""
    options, callback = _options(1, 0, 0, 0, progress)
    with scene_argument(scene) as scene:
        points, stride = _positions(scene, positions)
        out = np.empty((points.shape[0], 4), dtype=np.uint8)
        lights = ctypes.c_uint32()
        status = lib.tp_bake_occlusion(scene._live(), points, stride, points.shape[0], ctypes.byref(options),
                                       out, 4, ctypes.byref(lights))
    callback.reraise()
    check(status)
    return out, lights.value
