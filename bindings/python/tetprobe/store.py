"""Store: a built or loaded probe store, queried in batches through the C ABI."""

import ctypes
import numbers
import os

import numpy as np

from . import _native
from ._handle import NativeHandle
from ._arrays import UINT32_MAX, UINT64_MAX, Progress, as_array, choice, flag, integer, number, rows, vector
from ._arrays import path as _path_argument
from ._native import SH_FLOATS, check, lib
from .scene import scene_argument


class Store(NativeHandle):
    """An immutable probe store. Build it with Store.build or read it with Store.load; any number of threads
    may query one store at once. close() or a `with` block releases it (so does garbage collection);
    a closed store raises Error(INVALID_ARGUMENT, "the store is closed")."""

    _release = staticmethod(lib.tp_store_release)
    _noun = "store"

    def __init__(self, handle):
        if not handle:
            raise ValueError("Store() takes a native handle; use Store.build or Store.load")
        self._adopt(handle)

    # ---- creation

    @classmethod
    def build(cls, positions, sh=None, *, compact=False, extrapolate=True, index32=False, merge_tolerance=None,
              flat_tolerance=None, progress=None, scene=None, occlusion=None, occlusion_lights=None,
              sh_encoding="half", quantize_positions=False, layout="fast"):
        """Builds a store from probe positions[N, 3] and their SH sh[N, 27] (None = all zeros).

        positions: float32 world units (other number dtypes are converted), one row per probe; any row
        stride. sh: 27 float32 per probe, channel-major [r0..r8, g0..g8, b0..b8] in the order L00, L1-1,
        L10, L11, L2-2, L2-1, L20, L21, L22 (radiance, not pre-convolved). sh_encoding says how the store
        keeps them: "half" (27 half floats), "unorm8" (L0 as halves, the rest as 8-bit ratios to L0 over
        the range a non-negative radiance reaches), or "half_l1" / "unorm8_l1" (band 2 dropped: queries
        return zeros there). quantize_positions=True stores positions in 16 bits per axis on a
        power-of-two grid over the probes' bounds (quantised first, so the cells are exactly Delaunay for
        the stored positions and a query at a stored probe weighs it exactly 1; a stored probe moves at
        most half of info()["position_step"] per axis, one already on that grid not at all; probes that
        quantise to one point merge). Duplicate and near-duplicate probes are merged (the first given
        survives, SH averaged).
        layout: "fast" (the default), "compact" (no neighbour section, rebuilt when the store is loaded;
        the same as compact=True) or "rebuilt" (no cells, neighbours or start grid: rebuilt from the
        positions when loaded, exactly the cells the other layouts store; the smallest blob, some
        milliseconds per 10,000 probes to load; a set with more than 16 cells a probe is refused). Every
        layout answers as the fast one (same cells, weights within 1e-6). compact=True with another
        layout than "fast" or "compact" raises ValueError.
        extrapolate=False builds no outer cells (queries outside the hull raise Error(OUTSIDE));
        index32=True forces 32-bit indices; merge_tolerance and flat_tolerance are fractions of the
        set's bounding-box diagonal (None = the library's defaults, 1e-6 and 1e-4); progress is a
        callable progress(fraction, stage) called on this thread that may return True to cancel
        (Error(CANCELLED)). scene (a Scene, or the path of a scene file, loaded for the build) turns on
        leak control: probe pairs of a cell that cannot see each other are stored and queries weigh down
        the probe behind the wall. occlusion[N, 4] uint8
        (bake_occlusion's output) stores occlusion probes of occlusion_lights mixed lights (the count
        bake_occlusion returns; None = all 4 channels). Raises ValueError/TypeError for a wrong shape or
        dtype, Error otherwise."""
        points, point_stride, _ = rows(positions, 3, "positions")
        coefficients, sh_stride = None, 0
        if sh is not None:
            coefficients, sh_stride, _ = rows(sh, SH_FLOATS, "sh")
            if coefficients.shape[0] != points.shape[0]:
                raise ValueError("sh has %d rows for %d positions" % (coefficients.shape[0], points.shape[0]))
        options = _native.BuildOptions()
        check(lib.tp_build_options_init(ctypes.byref(options)))
        options.sh_encoding = choice(sh_encoding, _native.SH_ENCODINGS, "sh_encoding")
        options.quantize_positions = 1 if flag(quantize_positions, "quantize_positions") else 0
        options.layout = choice(layout, _native.LAYOUTS, "layout")
        options.flags = (0 if flag(extrapolate, "extrapolate") else _native.BUILD_NO_EXTRAPOLATION) | \
                        (_native.BUILD_INDEX32 if flag(index32, "index32") else 0) | \
                        (_native.BUILD_COMPACT if flag(compact, "compact") else 0)
        if compact and options.layout not in (_native.LAYOUTS["fast"], _native.LAYOUTS["compact"]):
            raise ValueError("compact=True asks for the compact layout, layout=%r for another" % layout)
        if merge_tolerance is not None:
            options.merge_tolerance = number(merge_tolerance, "merge_tolerance")
        if flat_tolerance is not None:
            options.flat_tolerance = number(flat_tolerance, "flat_tolerance")
        occlusion_bytes = None
        if occlusion is not None:
            occlusion_bytes = np.ascontiguousarray(as_array(occlusion, "occlusion", np.uint8))
            if occlusion_bytes.shape != (points.shape[0], 4):
                raise ValueError("occlusion must be [%d, 4] uint8 (got %s)" % (points.shape[0], occlusion_bytes.shape))
            options.occlusion = occlusion_bytes.ctypes.data
            options.occlusion_stride = 4
            options.occlusion_lights = 4 if occlusion_lights is None else integer(occlusion_lights, "occlusion_lights",
                                                                                  0, UINT32_MAX)
        elif occlusion_lights is not None:
            integer(occlusion_lights, "occlusion_lights", 0, UINT32_MAX)
        callback = Progress(progress)
        options.progress = callback.function
        handle = ctypes.c_void_p()
        with scene_argument(scene, optional=True) as live_scene:
            if live_scene is not None:
                options.scene = live_scene._live()
            status = lib.tp_store_build(points, point_stride, coefficients, sh_stride,
                                        points.shape[0], ctypes.byref(options), ctypes.byref(handle))
        callback.reraise()
        check(status)
        return cls(handle.value)

    @classmethod
    def load(cls, source, max_file_bytes=None):
        """Loads and validates a store from source: a file path (str or os.PathLike) or the blob itself
        (bytes, bytearray or memoryview, copied). Safe for untrusted input: a bad blob raises
        Error(INVALID_BLOB) or Error(VERSION); a missing file, one that is not a regular file (a
        directory, a device, a FIFO) or one larger than max_file_bytes (default 1 GiB) Error(IO)."""
        if max_file_bytes is not None:
            max_file_bytes = integer(max_file_bytes, "max_file_bytes", 1, UINT64_MAX)
        handle = ctypes.c_void_p()
        if isinstance(source, (bytes, bytearray, memoryview)):
            data = np.frombuffer(source, dtype=np.uint8)
            check(lib.tp_store_load(data if data.size else np.zeros(1, np.uint8), data.size, ctypes.byref(handle)))
        elif isinstance(source, (str, os.PathLike)):
            path = _path_argument(source, "source")
            if max_file_bytes is None:
                check(lib.tp_store_load_file(path, ctypes.byref(handle)))
            else:
                options = _native.StoreLoadOptions()
                check(lib.tp_store_load_options_init(ctypes.byref(options)))
                options.max_file_bytes = max_file_bytes
                check(lib.tp_store_load_file_ex(path, ctypes.byref(options), ctypes.byref(handle)))
        else:
            raise TypeError("source must be a path (str or os.PathLike) or the blob (bytes, bytearray or memoryview) "
                            "(got %s)" % type(source).__name__)
        return cls(handle.value)

    # ---- blob

    def save(self, path):
        """Writes the blob to path (str or os.PathLike) atomically: a temporary file next to it, then a
        rename. A symbolic link is written through, an existing file keeps its permissions, and the
        temporary file never outlives a failed save (see tp_store_save_file)."""
        check(lib.tp_store_save_file(self._live(), _path_argument(path, "path")))

    def to_bytes(self):
        """The store's blob as bytes (what save writes and load reads)."""
        data, size = ctypes.c_void_p(), ctypes.c_size_t()
        check(lib.tp_store_blob(self._live(), ctypes.byref(data), ctypes.byref(size)))
        return ctypes.string_at(data.value, size.value)

    def info(self):
        """Counts and layout as a dict: probes, input_probes, merged_probes, cells, inner_cells,
        outer_cells, index_bits (16 or 32), bytes (the blob's size), format_version (6), dimension of
        the probe set (0 point, 1 line, 2 flat, 3 general), flags (TP_BUILD_* bits of the blob;
        BUILD_INDEX32 whenever it uses 32-bit indices), compact (True for the compact layout),
        extrapolation, grid (cold-start grid cells along x, y, z), origin (the local origin, world
        units, float64), bounds_min and bounds_max (world units, float32 values), occlusion_lights
        (mixed lights with occlusion probes, 0-4), leak_edges (probe pairs stored for leak control),
        layout ("fast", "compact" or "rebuilt"), sh_encoding ("half", "unorm8", "half_l1", "unorm8_l1"),
        quantized_positions, position_step (per axis: the largest gap between stored position values,
        0.0 for float positions), hull_probes, and section_bytes: a dict of the blob's bytes by part
        (header, positions, normals, sh, probe_source, input_remap, cells, grid, occlusion, leak_offsets,
        leak_edges, padding), which add up to bytes."""
        info = _native.StoreInfo()
        info.struct_size = ctypes.sizeof(info)
        check(lib.tp_store_get_info(self._live(), ctypes.byref(info)))
        return {
            "format_version": info.format_version,
            "dimension": info.dimension,
            "probes": info.probes,
            "input_probes": info.input_probes,
            "merged_probes": info.merged_probes,
            "cells": info.cells,
            "inner_cells": info.inner_cells,
            "outer_cells": info.outer_cells,
            "index_bits": info.index_bits,
            "flags": info.flags,
            "compact": bool(info.flags & _native.BUILD_COMPACT),
            "extrapolation": not (info.flags & _native.BUILD_NO_EXTRAPOLATION),
            "grid": tuple(info.grid),
            "bytes": info.bytes,
            "origin": tuple(info.origin),
            "bounds_min": tuple(info.bounds_min),
            "bounds_max": tuple(info.bounds_max),
            "occlusion_lights": info.occlusion_lights,
            "leak_edges": info.leak_edges,
            "layout": {v: k for k, v in _native.LAYOUTS.items()}.get(info.layout, info.layout),
            "sh_encoding": {v: k for k, v in _native.SH_ENCODINGS.items()}.get(info.sh_encoding, info.sh_encoding),
            "quantized_positions": bool(info.quantized_positions),
            "position_step": tuple(info.position_step),
            "hull_probes": info.hull_probes,
            "section_bytes": {name: info.section_bytes[i] for i, name in enumerate(_native.STORE_SECTIONS)},
        }

    def probe_sh(self, probe):
        """The stored SH of input probe index `probe` (an int in [0, input_probes)) as sh[27] float32,
        channel-major, decoded: the input rounded to the store's SH encoding (half floats by default;
        zeros in band 2 for the L1 encodings), exactly what a query at the probe returns. A merged probe
        reads its survivor."""
        out = np.empty(SH_FLOATS, dtype=np.float32)
        check(lib.tp_store_probe_sh(self._live(), integer(probe, "probe", 0, UINT32_MAX), out))
        return out

    # ---- queries

    @staticmethod
    def _hints(hints, count, chain_hints):
        """The int32 hint buffer of a batch: the caller's, fresh -1s, or None (NULL) for chained hints."""
        if hints is None:
            return None if chain_hints else np.full(count, -1, dtype=np.int32)
        if chain_hints:
            raise ValueError("chain_hints applies only to batches without hints")
        out = np.array(as_array(hints, "hints", np.int32)).reshape(-1)
        if out.shape[0] != count:
            raise ValueError("hints has %d entries for %d points" % (out.shape[0], count))
        return out

    @staticmethod
    def _single_hint(hints):
        """The cell hint of a single query: -1 for None, else the one int given (a scalar or [1])."""
        if hints is None:
            return ctypes.c_int32(-1)
        if isinstance(hints, (bool, np.bool_)):
            raise TypeError("hints must be an int or an array of ints (got bool)")
        values = as_array(hints, "hints", np.int32).reshape(-1)
        if values.shape[0] != 1:
            raise ValueError("hints has %d entries for 1 point" % values.shape[0])
        return ctypes.c_int32(int(values[0]))

    @staticmethod
    def _batch_options(threads, chain_hints):
        options = _native.BatchOptions()
        check(lib.tp_batch_options_init(ctypes.byref(options)))
        options.threads = integer(threads, "threads", 0, UINT32_MAX)
        options.flags = _native.BATCH_CHAIN_HINTS if chain_hints else 0
        return options

    def interpolate(self, points, hints=None, threads=1, chain_hints=False, occlusion=False):
        """Interpolated SH at points[M, 3] -> (sh[M, 27] float32, hints[M] int32).

        points: float32 world units (other number dtypes are converted), any row stride. sh rows are
        channel-major [r0..r8, g0..g8, b0..b8] radiance SH (evaluate with tetprobe.sh). hints[M] int32
        are the cells the same objects were found in last time (-1 = none; None = all -1): keep one per
        moving object and pass the returned array back next frame. threads: deprecated and ignored
        (accepted for older callers): the library never starts threads; to use several, call this on
        disjoint slices of the points from your own threads, each slice with its own hints.
        chain_hints=True (only with hints=None) starts each query from the previous
        query's cell, for points given in a spatially coherent order; the returned hints are then None.
        A single point of shape [3] (with hints None or one int) is one tp_store_interpolate call and
        gives (sh[27], hint int). Points outside a store built with extrapolate=False raise
        Error(OUTSIDE) naming the first. occlusion=True returns (sh, occlusion, hints) with
        occlusion[M, 4] float32 in [0, 1] (or [4] for a single point): the mixed lights' interpolated
        visibility (1 for channels without a light)."""
        data, stride, single = rows(points, 3, "points")
        chain_hints, occlusion = flag(chain_hints, "chain_hints"), flag(occlusion, "occlusion")
        if single and not chain_hints:
            cell = self._single_hint(hints)
            out = np.empty(SH_FLOATS, dtype=np.float32)
            if occlusion:
                visible = np.empty(4, dtype=np.float32)
                check(lib.tp_store_interpolate_occlusion(self._live(), data, ctypes.byref(cell), out, visible))
                return out, visible, cell.value
            check(lib.tp_store_interpolate(self._live(), data, ctypes.byref(cell), out))
            return out, cell.value
        count = data.shape[0]
        cells = self._hints(hints, count, chain_hints)
        options = self._batch_options(threads, chain_hints)
        out = np.empty((count, SH_FLOATS), dtype=np.float32)
        if occlusion:
            visible = np.empty((count, 4), dtype=np.float32)
            check(lib.tp_store_interpolate_occlusion_batch(self._live(), count, data, stride, cells, 4, out,
                                                           SH_FLOATS * 4, visible, 16, ctypes.byref(options)))
            if single:
                return out[0], visible[0], (None if cells is None else int(cells[0]))
            return out, visible, cells
        check(lib.tp_store_interpolate_batch(self._live(), count, data, stride, cells, 4,
                                             out, SH_FLOATS * 4, ctypes.byref(options)))
        if single:
            return out[0], None
        return out, cells

    def weights(self, points, hints=None, threads=1, chain_hints=False):
        """Blended probes and weights at points[M, 3] -> (indices[M, 4] int64, weights[M, 4] float32,
        hints[M] int32).

        indices are input probe indices (survivors of merges) in [0, input_probes); unused slots weigh 0
        and repeat a used probe. Inside the hull the weights are the Delaunay barycentrics, in [0, 1],
        summing to 1; a query at a probe weighs it exactly 1. points[M, 3] (float32 world units),
        hints[M] (int32 cells, -1 = none), threads and chain_hints as in interpolate; a single point of
        shape [3] is one tp_store_weights call and gives (indices[4], weights[4], hint int)."""
        data, stride, single = rows(points, 3, "points")
        chain_hints = flag(chain_hints, "chain_hints")
        if single and not chain_hints:
            cell = self._single_hint(hints)
            probes = np.empty(4, dtype=np.uint32)
            weights = np.empty(4, dtype=np.float32)
            check(lib.tp_store_weights(self._live(), data, ctypes.byref(cell), probes, weights))
            return probes.astype(np.int64), weights, cell.value
        count = data.shape[0]
        cells = self._hints(hints, count, chain_hints)
        options = self._batch_options(threads, chain_hints)
        probes = np.empty((count, 4), dtype=np.uint32)
        weights = np.empty((count, 4), dtype=np.float32)
        check(lib.tp_store_weights_batch(self._live(), count, data, stride, cells, 4,
                                         probes, 16, weights, 16, ctypes.byref(options)))
        indices = probes.astype(np.int64)
        if single:
            return indices[0], weights[0], None
        return indices, weights, cells

    def sample_volume(self, origin, cell_size, dims, *, bands=2, unity=False, hint=None, out=None):
        """A probe volume (Unity's Light Probe Proxy Volume): the SH at origin + (x, y, z) * cell_size for
        x < nx, y < ny, z < nz, dims[3] = (nx, ny, nz), each 1..32 -> float32 [nz, ny, nx, 27].

        origin[3] and cell_size[3] (positive) are world units (cell_size may be one number). bands=1 keeps bands 0
        and 1: [nz, ny, nx, 12], 4 per channel. unity=True gives Unity's shader constants instead: [nz, ny, nx, 3, 4]
        (unity_SHAr, SHAg, SHAb of the L1 SH) for bands=1, [nz, ny, nx, 7, 4] (then SHBr, SHBg, SHBb, SHC) for
        bands=2 (see TP_VOLUME_UNITY_L1 in capi/tetprobe.h). The grid is walked from neighbour to neighbour with one
        cell hint, each point bit for bit what interpolate gives there in that walk. hint: the cell to start from
        (an int, -1 or None = cold), or hint[1], an int32 array of one element, which is updated to the cell of
        point (0, 0, 0) for the next frame. out: an array of the result's shape and float32 to write into (any
        non-negative strides whose last axis is packed, e.g. a view into a texture's atlas); it is returned.
        Points outside a store built with extrapolate=False raise Error(OUTSIDE) naming the first."""
        bands = integer(bands, "bands", 1, 2)
        unity = flag(unity, "unity")
        origin = vector(origin, 3, "origin")
        if isinstance(cell_size, numbers.Real) and not isinstance(cell_size, (bool, np.bool_)):
            cell_size = np.full(3, number(cell_size, "cell_size"), dtype=np.float32)
        cell_size = vector(cell_size, 3, "cell_size")
        sides = vector(dims, 3, "dims", np.uint32)
        nx, ny, nz = (int(side) for side in sides)
        if unity:
            fmt = _native.VOLUME_UNITY_L2 if bands == 2 else _native.VOLUME_UNITY_L1
            shape = (nz, ny, nx, 7 if bands == 2 else 3, 4)
        else:
            fmt = _native.VOLUME_SH_L2 if bands == 2 else _native.VOLUME_SH_L1
            shape = (nz, ny, nx, SH_FLOATS if bands == 2 else 12)
        if out is None:
            out = np.empty(shape, dtype=np.float32)
        elif not isinstance(out, np.ndarray) or out.dtype != np.float32:
            raise TypeError("out must be a float32 numpy array of shape %s (got %s)" % (shape, type(out).__name__))
        elif out.shape != shape:
            raise ValueError("out must have shape %s (got %s)" % (shape, out.shape))
        elif not out.flags.writeable or out.strides[-1] != 4 or min(out.strides) < 0:
            raise ValueError("out must be writeable with non-negative strides and its last axis packed")
        layout = _native.VolumeLayout()
        check(lib.tp_volume_layout_init(ctypes.byref(layout)))
        layout.format = fmt
        layout.slice_stride, layout.row_stride, layout.point_stride = out.strides[:3]
        if unity:
            layout.vector_stride = out.strides[3]
        held = hint if isinstance(hint, np.ndarray) else None
        if held is not None and (held.dtype != np.int32 or held.size != 1 or not held.flags.writeable):
            raise ValueError("hint as an array must be a writeable int32 array of one element")
        cell = ctypes.c_int32(int(held.reshape(-1)[0]) if held is not None else
                              (-1 if hint is None else integer(hint, "hint", -2 ** 31, 2 ** 31 - 1)))
        check(lib.tp_store_sample_volume(self._live(), origin, cell_size, sides, ctypes.byref(cell),
                                         ctypes.byref(layout), out))
        if held is not None:
            held.reshape(-1)[0] = cell.value
        return out

    def locate(self, point, hint=-1):
        """Diagnostics of the query at point[3] or of each of points point[M, 3] (float32 world units),
        starting from cell `hint` (an int, or hint[M] int32 for [M, 3]; -1 = cold).

        For a single point, a dict: cell, kind ("inner" or "outer"), steps (cells walked after the start),
        fallback (True if the exhaustive search decided, outside the hull only), probes (4 input probe
        indices), weights (4 floats), t (outer cells: the ray parameter, 0 on the hull) and hint (the cell
        found). For [M, 3], the same keys holding arrays: cell[M] int32, kind[M] str, steps[M] uint32,
        fallback[M] bool, probes[M, 4] int64, weights[M, 4] float32, t[M] float32 and hint[M] int32 (each
        query starts from its own hint, which is updated)."""
        data, _, single = rows(point, 3, "point")
        count = data.shape[0]
        if single:
            cells = np.array([self._single_hint(hint).value], dtype=np.int32)
        elif isinstance(hint, numbers.Integral) and not isinstance(hint, (bool, np.bool_)):
            cells = np.full(count, integer(hint, "hint", -2 ** 31, 2 ** 31 - 1), dtype=np.int32)
        else:
            cells = np.array(as_array(hint, "hint", np.int32)).reshape(-1)
            if cells.shape[0] != count:
                raise ValueError("hint has %d entries for %d points" % (cells.shape[0], count))
        location = _native.Location()
        location.struct_size = ctypes.sizeof(location)
        found = {"cell": np.empty(count, np.int32), "kind": np.empty(count, "<U5"), "steps": np.empty(count, np.uint32),
                 "fallback": np.empty(count, bool), "probes": np.empty((count, 4), np.int64),
                 "weights": np.empty((count, 4), np.float32), "t": np.empty(count, np.float32)}
        store = self._live()
        for i in range(count):
            cell = ctypes.c_int32(int(cells[i]))
            check(lib.tp_store_locate(store, data[i], ctypes.byref(cell), ctypes.byref(location)))
            cells[i] = cell.value
            found["cell"][i] = location.cell
            found["kind"][i] = "outer" if location.cell_kind == _native.CELL_OUTER else "inner"
            found["steps"][i] = location.steps
            found["fallback"][i] = bool(location.fallback)
            found["probes"][i] = list(location.probes)
            found["weights"][i] = list(location.weights)
            found["t"][i] = location.t
        found["hint"] = cells
        if not single:
            return found
        return {"cell": int(found["cell"][0]), "kind": str(found["kind"][0]), "steps": int(found["steps"][0]),
                "fallback": bool(found["fallback"][0]), "probes": found["probes"][0].tolist(),
                "weights": [float(w) for w in found["weights"][0]], "t": float(found["t"][0]),
                "hint": int(cells[0])}

    def __repr__(self):
        if not self._handle:
            return "<tetprobe.Store closed>"
        info = self.info()
        return "<tetprobe.Store %d probes, %d cells, %d bytes>" % (info["probes"], info["cells"], info["bytes"])
