"""Store: a built or loaded probe store, queried in batches through the C ABI."""

import ctypes
import os

import numpy as np

from . import _native
from ._handle import NativeHandle
from ._arrays import Progress, rows
from ._native import SH_FLOATS, check, lib
from .errors import Error, Status


class Store(NativeHandle):
    """An immutable probe store. Build it with Store.build or read it with Store.load."""

    _release = staticmethod(lib.tp_store_release)
    _noun = "store"

    def __init__(self, handle):
        if not handle:
            raise ValueError("Store() takes a native handle; use Store.build or Store.load")
        self._adopt(handle)

    # ---- creation

    @classmethod
    def build(cls, positions, sh=None, *, extrapolate=True, index32=False, merge_tolerance=None,
              flat_tolerance=None, progress=None):
        """Builds a store from positions[N, 3] and sh[N, 27] (None = zeros).

        extrapolate=False builds no outer cells (queries outside the hull raise Error(OUTSIDE));
        index32 forces 32-bit indices; tolerances are fractions of the set's diagonal (None = the
        library's default); progress(fraction, stage) may return True to cancel."""
        points, point_stride, _ = rows(positions, 3, "positions")
        coefficients, sh_stride = None, 0
        if sh is not None:
            coefficients, sh_stride, _ = rows(sh, SH_FLOATS, "sh")
            if coefficients.shape[0] != points.shape[0]:
                raise Error(Status.INVALID_ARGUMENT, "sh has %d rows for %d positions" %
                            (coefficients.shape[0], points.shape[0]))
        options = _native.BuildOptions()
        check(lib.tp_build_options_init(ctypes.byref(options)))
        options.flags = (0 if extrapolate else _native.BUILD_NO_EXTRAPOLATION) | \
                        (_native.BUILD_INDEX32 if index32 else 0)
        if merge_tolerance is not None:
            options.merge_tolerance = merge_tolerance
        if flat_tolerance is not None:
            options.flat_tolerance = flat_tolerance
        callback = Progress(progress)
        options.progress = callback.function
        handle = ctypes.c_void_p()
        status = lib.tp_store_build(points, point_stride, coefficients, sh_stride,
                                    points.shape[0], ctypes.byref(options), ctypes.byref(handle))
        callback.reraise()
        check(status)
        return cls(handle.value)

    @classmethod
    def load(cls, source):
        """Loads and validates a store from a file path or from bytes (bytes, bytearray, memoryview)."""
        handle = ctypes.c_void_p()
        if isinstance(source, (bytes, bytearray, memoryview)):
            data = np.frombuffer(source, dtype=np.uint8)
            check(lib.tp_store_load(data if data.size else np.zeros(1, np.uint8), data.size, ctypes.byref(handle)))
        else:
            check(lib.tp_store_load_file(os.fsencode(source), ctypes.byref(handle)))
        return cls(handle.value)

    # ---- blob

    def save(self, path):
        """Writes the blob to path atomically."""
        check(lib.tp_store_save_file(self._live(), os.fsencode(path)))

    def to_bytes(self):
        """The store's blob as bytes."""
        data, size = ctypes.c_void_p(), ctypes.c_size_t()
        check(lib.tp_store_blob(self._live(), ctypes.byref(data), ctypes.byref(size)))
        return ctypes.string_at(data.value, size.value)

    def info(self):
        """Counts and layout: probes, cells, inner_cells, outer_cells, merged_probes, index_bits, bytes, ..."""
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
            "extrapolation": not (info.flags & _native.BUILD_NO_EXTRAPOLATION),
            "grid": tuple(info.grid),
            "bytes": info.bytes,
            "origin": tuple(info.origin),
            "bounds_min": tuple(info.bounds_min),
            "bounds_max": tuple(info.bounds_max),
        }

    def probe_sh(self, probe):
        """The stored (half-precision) SH[27] of input probe `probe` (a merged probe reads its survivor)."""
        out = np.empty(SH_FLOATS, dtype=np.float32)
        check(lib.tp_store_probe_sh(self._live(), int(probe), out))
        return out

    # ---- queries

    @staticmethod
    def _hints(hints, count):
        if hints is None:
            return np.full(count, -1, dtype=np.int32)
        out = np.array(hints, dtype=np.int32).reshape(-1)
        if out.shape[0] != count:
            raise ValueError("hints has %d entries for %d points" % (out.shape[0], count))
        return out

    def interpolate(self, points, hints=None):
        """Interpolated SH at points[M, 3] -> (sh[M, 27], hints[M]); a point of shape [3] gives (sh[27], hint)."""
        data, stride, single = rows(points, 3, "points")
        count = data.shape[0]
        cells = self._hints(hints, count)
        out = np.empty((count, SH_FLOATS), dtype=np.float32)
        check(lib.tp_store_interpolate_batch(self._live(), count, data, stride, cells, 4,
                                             out, SH_FLOATS * 4))
        return (out[0], int(cells[0])) if single else (out, cells)

    def weights(self, points, hints=None):
        """Blended probes and weights at points[M, 3] -> (indices[M, 4] int64, weights[M, 4], hints[M])."""
        data, stride, single = rows(points, 3, "points")
        count = data.shape[0]
        cells = self._hints(hints, count)
        probes = np.empty((count, 4), dtype=np.uint32)
        weights = np.empty((count, 4), dtype=np.float32)
        check(lib.tp_store_weights_batch(self._live(), count, data, stride, cells, 4,
                                         probes, 16, weights, 16))
        indices = probes.astype(np.int64)
        return (indices[0], weights[0], int(cells[0])) if single else (indices, weights, cells)

    def locate(self, point, hint=-1):
        """Diagnostics of one query: cell, kind ("inner"/"outer"), steps, fallback, probes, weights, t."""
        data, _, _ = rows(point, 3, "point")
        location = _native.Location()
        location.struct_size = ctypes.sizeof(location)
        cell = ctypes.c_int32(int(hint))
        check(lib.tp_store_locate(self._live(), data, ctypes.byref(cell), ctypes.byref(location)))
        return {
            "cell": location.cell,
            "kind": "outer" if location.cell_kind == _native.CELL_OUTER else "inner",
            "steps": location.steps,
            "fallback": bool(location.fallback),
            "probes": list(location.probes),
            "weights": list(location.weights),
            "t": location.t,
            "hint": cell.value,
        }

    def __repr__(self):
        if not self._handle:
            return "<tetprobe.Store closed>"
        info = self.info()
        return "<tetprobe.Store %d probes, %d cells, %d bytes>" % (info["probes"], info["cells"], info["bytes"])
