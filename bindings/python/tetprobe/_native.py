"""The C ABI as ctypes: the library search, the version check, the structs and ONE prototype table.

Every function of capi/tetprobe.h is declared in PROTOTYPES below and nowhere else. Buffers are
numpy arrays passed as they are (see Buffer), so strided views go through without copies.
"""

import ctypes
import ctypes.util
import os
import sys
from ctypes import (CFUNCTYPE, POINTER, Structure, c_char, c_char_p, c_double, c_float, c_int, c_int32,
                    c_size_t, c_uint32, c_uint64, c_void_p)

from .errors import Error, Status

#: The library version this package was written for; major.minor must match the loaded library.
PACKAGE_VERSION = (0, 8, 0)

SH_FLOATS = 27

BUILD_NO_EXTRAPOLATION = 1
BUILD_INDEX32 = 2
BUILD_COMPACT = 4
#: TP_SH_ENCODING_* by the names Store.build takes.
SH_ENCODINGS = {"half": 0, "unorm8": 1, "half_l1": 2, "unorm8_l1": 3}
#: TP_LAYOUT_* by name.
LAYOUTS = {"fast": 0, "compact": 1, "rebuilt": 2}
#: TP_STORE_SECTION_* by name, in index order (the keys of Store.info()["section_bytes"]).
STORE_SECTIONS = ("header", "positions", "normals", "sh", "probe_source", "input_remap", "cells", "grid",
                  "occlusion", "leak_offsets", "leak_edges", "padding")
BATCH_CHAIN_HINTS = 1
BAKE_NO_CULLING = 1
CELL_INNER = 0
CELL_OUTER = 1
LIGHT_DIRECTIONAL = 0
LIGHT_POINT = 1
LIGHT_SPOT = 2
LIGHT_MODE_BAKED = 0
LIGHT_MODE_REALTIME = 1
LIGHT_MODE_MIXED = 2
SH_ORDER_L2 = 0
SH_ORDER_L1 = 1
SH_ORDER_ZH3 = 2
SH_WINDOW_NONE = 0
SH_WINDOW_SLOAN = 1
SH_WINDOW_NONNEGATIVE = 2
PLACEMENT_WHOLE = 0
PLACEMENT_WALKABLE = 1
INSIDE_DROP = 0
INSIDE_PUSH = 1
UP_FILE = 0
VOLUME_MAX_SIDE = 32
VOLUME_SH_L2 = 0
VOLUME_SH_L1 = 1
VOLUME_UNITY_L1 = 2
VOLUME_UNITY_L2 = 3
#: TP_UP_POS_X ... TP_UP_NEG_Z by name.
UP_AXES = {"+x": 1, "-x": 2, "+y": 3, "-y": 4, "+z": 5, "-z": 6}

ProgressFn = CFUNCTYPE(c_int, c_void_p, c_float, c_char_p)


class BuildOptions(Structure):
    _fields_ = [("struct_size", c_uint32), ("flags", c_uint32), ("merge_tolerance", c_double),
                ("flat_tolerance", c_double), ("progress", ProgressFn), ("progress_user", c_void_p),
                ("occlusion", c_void_p), ("occlusion_stride", c_size_t), ("occlusion_lights", c_uint32),
                ("scene", c_void_p), ("sh_encoding", c_uint32), ("quantize_positions", c_uint32),
                ("layout", c_uint32)]


class StoreLoadOptions(Structure):
    _fields_ = [("struct_size", c_uint32), ("max_file_bytes", c_uint64)]


class StoreInfo(Structure):
    _fields_ = [("struct_size", c_uint32), ("format_version", c_uint32), ("dimension", c_uint32),
                ("probes", c_uint32), ("input_probes", c_uint32), ("merged_probes", c_uint32),
                ("cells", c_uint32), ("inner_cells", c_uint32), ("outer_cells", c_uint32),
                ("index_bits", c_uint32), ("flags", c_uint32), ("grid", c_uint32 * 3), ("bytes", c_uint64),
                ("origin", c_double * 3), ("bounds_min", c_float * 3), ("bounds_max", c_float * 3),
                ("occlusion_lights", c_uint32), ("leak_edges", c_uint32), ("layout", c_uint32),
                ("sh_encoding", c_uint32), ("quantized_positions", c_uint32), ("hull_probes", c_uint32),
                ("position_step", c_double * 3), ("section_bytes", c_uint64 * 16)]


class BatchOptions(Structure):
    _fields_ = [("struct_size", c_uint32), ("flags", c_uint32), ("threads", c_uint32)]


class Location(Structure):
    _fields_ = [("struct_size", c_uint32), ("cell", c_int32), ("cell_kind", c_uint32), ("steps", c_uint32),
                ("fallback", c_uint32), ("probes", c_uint32 * 4), ("weights", c_float * 4), ("t", c_float)]


class VolumeLayout(Structure):
    _fields_ = [("struct_size", c_uint32), ("format", c_uint32), ("point_stride", c_size_t), ("row_stride", c_size_t),
                ("slice_stride", c_size_t), ("vector_stride", c_size_t)]


class ShEvalOptions(Structure):
    _fields_ = [("struct_size", c_uint32), ("order", c_uint32), ("window", c_uint32), ("window_strength", c_float)]


class Material(Structure):
    _fields_ = [("struct_size", c_uint32), ("albedo", c_float * 3), ("emission", c_float * 3),
                ("two_sided", c_int32)]


class Light(Structure):
    _fields_ = [("struct_size", c_uint32), ("type", c_uint32), ("mode", c_uint32), ("shadows", c_int32),
                ("color", c_float * 3), ("intensity", c_float), ("position", c_float * 3),
                ("direction", c_float * 3), ("range", c_float), ("inner_angle", c_float),
                ("outer_angle", c_float), ("near_distance", c_float)]


class SceneLoadOptions(Structure):
    _fields_ = [("struct_size", c_uint32), ("up", c_uint32), ("scale", c_float)]


class BakeOptions(Structure):
    _fields_ = [("struct_size", c_uint32), ("flags", c_uint32), ("rays", c_uint32), ("bounces", c_uint32),
                ("seed", c_uint64), ("threads", c_uint32), ("progress", ProgressFn), ("progress_user", c_void_p)]


class EffectsPlan(Structure):
    _fields_ = [("struct_size", c_uint32), ("lights", c_uint32), ("direct_lights", c_uint32),
                ("realtime_lights", c_uint32), ("out_of_range_lights", c_uint32), ("sky", c_int32),
                ("emissive_meshes", c_uint32), ("bounces", c_uint32), ("shadows", c_int32), ("meshes", c_uint32),
                ("shadow_casters", c_uint32), ("shadow_caster_candidates", c_uint32), ("inside_probes", c_uint32)]


class PlacementOptions(Structure):
    _fields_ = [("struct_size", c_uint32), ("mode", c_uint32), ("spacing", c_float), ("margin", c_float),
                ("walk_min_height", c_float), ("walk_max_height", c_float), ("target_count", c_uint32),
                ("error_bound", c_float), ("rays", c_uint32), ("bounces", c_uint32), ("seed", c_uint64),
                ("threads", c_uint32), ("progress", ProgressFn), ("progress_user", c_void_p),
                ("light_clearance", c_float)]


_status = c_int
_handle = c_void_p


class Buffer:
    """A caller-owned buffer argument: a numpy array (or None for NULL); counts and strides travel separately.

    The array itself is the call's argument, so it stays alive until the C function returns."""

    @classmethod
    def from_param(cls, array):
        if array is None:
            return None
        return c_void_p(array.ctypes.data)


_buffer = Buffer

#: (name, restype, argtypes) for every function of capi/tetprobe.h, in the header's order.
PROTOTYPES = (
    ("tp_version", c_uint32, ()),
    ("tp_last_error", c_char_p, ()),
    ("tp_status_name", c_char_p, (c_int,)),
    ("tp_build_options_init", _status, (POINTER(BuildOptions),)),
    ("tp_store_build", _status, (_buffer, c_size_t, _buffer, c_size_t, c_size_t, POINTER(BuildOptions),
                                 POINTER(_handle))),
    ("tp_store_load", _status, (_buffer, c_size_t, POINTER(_handle))),
    ("tp_store_load_options_init", _status, (POINTER(StoreLoadOptions),)),
    ("tp_store_load_file", _status, (c_char_p, POINTER(_handle))),
    ("tp_store_load_file_ex", _status, (c_char_p, POINTER(StoreLoadOptions), POINTER(_handle))),
    ("tp_store_save_file", _status, (_handle, c_char_p)),
    ("tp_store_blob", _status, (_handle, POINTER(c_void_p), POINTER(c_size_t))),
    ("tp_store_release", _status, (_handle,)),
    ("tp_store_get_info", _status, (_handle, POINTER(StoreInfo))),
    ("tp_store_probe_sh", _status, (_handle, c_uint32, _buffer)),
    ("tp_store_interpolate", _status, (_handle, _buffer, POINTER(c_int32), _buffer)),
    ("tp_store_interpolate_occlusion", _status, (_handle, _buffer, POINTER(c_int32), _buffer, _buffer)),
    ("tp_store_interpolate_occlusion_batch", _status, (_handle, c_size_t, _buffer, c_size_t, _buffer, c_size_t,
                                                       _buffer, c_size_t, _buffer, c_size_t, POINTER(BatchOptions))),
    ("tp_batch_options_init", _status, (POINTER(BatchOptions),)),
    ("tp_store_interpolate_batch", _status, (_handle, c_size_t, _buffer, c_size_t, _buffer, c_size_t, _buffer,
                                             c_size_t, POINTER(BatchOptions))),
    ("tp_store_weights", _status, (_handle, _buffer, POINTER(c_int32), _buffer, _buffer)),
    ("tp_store_weights_batch", _status, (_handle, c_size_t, _buffer, c_size_t, _buffer, c_size_t, _buffer,
                                         c_size_t, _buffer, c_size_t, POINTER(BatchOptions))),
    ("tp_store_locate", _status, (_handle, _buffer, POINTER(c_int32), POINTER(Location))),
    ("tp_volume_layout_init", _status, (POINTER(VolumeLayout),)),
    ("tp_store_sample_volume", _status, (_handle, _buffer, _buffer, _buffer, POINTER(c_int32), POINTER(VolumeLayout),
                                         _buffer)),
    ("tp_sh_eval_radiance", _status, (_buffer, _buffer, _buffer)),
    ("tp_sh_eval_irradiance", _status, (_buffer, _buffer, _buffer)),
    ("tp_sh_add_ambient", _status, (_buffer, _buffer)),
    ("tp_sh_add_directional", _status, (_buffer, _buffer, _buffer)),
    ("tp_sh_eval_options_init", _status, (POINTER(ShEvalOptions),)),
    ("tp_sh_eval_irradiance_ex", _status, (_buffer, _buffer, POINTER(ShEvalOptions), _buffer)),
    ("tp_sh_apply_options", _status, (_buffer, POINTER(ShEvalOptions))),
    ("tp_sh_min_irradiance", _status, (_buffer, POINTER(ShEvalOptions), _buffer, _buffer)),
    ("tp_sh_nonnegative_window_strength", _status, (_buffer, POINTER(ShEvalOptions), POINTER(c_float))),
    ("tp_shadow_caster_volume_bound", c_size_t, (c_size_t,)),
    ("tp_shadow_caster_volume", _status, (_buffer, c_size_t, c_uint32, _buffer, _buffer, c_size_t,
                                          POINTER(c_size_t))),
    ("tp_volume_test_aabb", _status, (_buffer, c_size_t, _buffer, _buffer, POINTER(c_int))),
    ("tp_volume_test_sphere", _status, (_buffer, c_size_t, _buffer, c_float, POINTER(c_int))),
    ("tp_material_init", _status, (POINTER(Material),)),
    ("tp_light_init", _status, (POINTER(Light),)),
    ("tp_scene_create", _status, (POINTER(_handle),)),
    ("tp_scene_release", _status, (_handle,)),
    ("tp_scene_load_file", _status, (c_char_p, POINTER(_handle))),
    ("tp_scene_load_options_init", _status, (POINTER(SceneLoadOptions),)),
    ("tp_scene_load_file_ex", _status, (c_char_p, POINTER(SceneLoadOptions), POINTER(_handle))),
    ("tp_scene_notes", _status, (_handle, POINTER(c_char), c_size_t, POINTER(c_size_t))),
    ("tp_scene_up", _status, (_handle, POINTER(c_uint32))),
    ("tp_scene_set_up", _status, (_handle, c_uint32)),
    ("tp_scene_add_mesh", _status, (_handle, _buffer, c_size_t, _buffer, c_size_t, POINTER(Material), c_size_t,
                                    _buffer, POINTER(c_uint32))),
    ("tp_scene_add_light", _status, (_handle, POINTER(Light), POINTER(c_uint32))),
    ("tp_scene_set_sky_color", _status, (_handle, _buffer)),
    ("tp_scene_set_sky_sh", _status, (_handle, _buffer)),
    ("tp_scene_probes", _status, (_handle, POINTER(c_void_p), POINTER(c_size_t))),
    ("tp_scene_set_probes", _status, (_handle, _buffer, c_size_t)),
    ("tp_scene_set_playable_seeds", _status, (_handle, _buffer, c_size_t)),
    ("tp_bake_options_init", _status, (POINTER(BakeOptions),)),
    ("tp_bake_plan", _status, (_handle, _buffer, c_size_t, c_size_t, POINTER(BakeOptions), POINTER(EffectsPlan),
                               POINTER(c_char), c_size_t)),
    ("tp_bake", _status, (_handle, _buffer, c_size_t, c_size_t, POINTER(BakeOptions), _buffer, c_size_t)),
    ("tp_bake_occlusion", _status, (_handle, _buffer, c_size_t, c_size_t, POINTER(BakeOptions), _buffer, c_size_t,
                                    POINTER(c_uint32))),
    ("tp_placement_options_init", _status, (POINTER(PlacementOptions),)),
    ("tp_place_probes_bound", _status, (_handle, POINTER(PlacementOptions), POINTER(c_size_t))),
    ("tp_place_probes", _status, (_handle, POINTER(PlacementOptions), _buffer, c_size_t, POINTER(c_size_t), _buffer,
                                  c_size_t, POINTER(c_size_t))),
    ("tp_find_inside_probes", _status, (_handle, _buffer, c_size_t, c_size_t, _buffer, c_size_t, POINTER(c_size_t))),
    ("tp_fix_inside_probes", _status, (_handle, _buffer, c_size_t, c_size_t, c_uint32, c_float, _buffer, c_size_t,
                                       POINTER(c_size_t))),
)

_LIBRARY_NAME = {"darwin": "libtetprobe.dylib", "win32": "tetprobe.dll"}.get(sys.platform, "libtetprobe.so")


def _explicit_library():
    """$TETPROBE_LIBRARY as a library path: the file it names, or the library inside the folder it names."""
    explicit = os.environ.get("TETPROBE_LIBRARY")
    if explicit and os.path.isdir(explicit):
        return os.path.join(explicit, _LIBRARY_NAME)
    return explicit


def candidate_paths():
    """Where the library is looked for, in order: $TETPROBE_LIBRARY (a library file, or a folder holding
    it), next to the package, and (only when the package sits in the source tree) the tree's build/
    directory; the system's search path comes last."""
    package_dir = os.path.dirname(os.path.abspath(__file__))
    repo_root = os.path.normpath(os.path.join(package_dir, "..", "..", ".."))
    paths = []
    if _explicit_library():
        paths.append(_explicit_library())
    paths.append(os.path.join(package_dir, _LIBRARY_NAME))
    # An installed package must not pick up whatever build/ happens to lie two levels above it.
    if os.path.exists(os.path.join(repo_root, "capi", "tetprobe.h")):
        paths.append(os.path.join(repo_root, "build", _LIBRARY_NAME))
    return paths


def check_version(library_version, package_version=PACKAGE_VERSION, path=None):
    """Raises Error(VERSION) unless the library's (major << 16 | minor << 8 | patch) matches major.minor."""
    major, minor = (library_version >> 16) & 0xFFFF, (library_version >> 8) & 0xFF
    if (major, minor) != tuple(package_version[:2]):
        where = " at %s" % path if path else ""
        raise Error(Status.VERSION, "libtetprobe %d.%d.%d%s does not match the tetprobe package %d.%d.%d "
                    "(major.minor must agree); set TETPROBE_LIBRARY to a matching build" %
                    ((major, minor, library_version & 0xFF, where) + tuple(package_version)))


def _load():
    explicit = _explicit_library()
    tried = []
    for path in candidate_paths():
        if path != explicit and not os.path.exists(path):
            tried.append(path)
            continue
        try:
            return ctypes.CDLL(path), path
        except OSError as error:
            if path == explicit:
                raise ImportError("TETPROBE_LIBRARY=%s cannot be loaded: %s" % (os.environ["TETPROBE_LIBRARY"], error))
            tried.append(path)
    system = ctypes.util.find_library("tetprobe")
    if system:
        return ctypes.CDLL(system), system
    raise ImportError("libtetprobe not found; set TETPROBE_LIBRARY (looked in: %s and the system's library path)"
                      % ", ".join(tried))


def _declare(library):
    for name, restype, argtypes in PROTOTYPES:
        function = getattr(library, name)
        function.restype = restype
        function.argtypes = argtypes
    return library


lib, library_path = _load()
_declare(lib)
check_version(lib.tp_version(), path=library_path)


def last_error():
    """The library's message of the last failure on this thread."""
    return lib.tp_last_error().decode("utf-8", "replace")


def check(status):
    """Turns a tp_status into an Error carrying the library's message for this thread."""
    if status != 0:
        raise Error(status, last_error())
