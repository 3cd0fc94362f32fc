"""numpy arrays as (array, row stride) pairs for the C ABI, copying only when the layout demands it."""

import numpy as np

from ._native import ProgressFn


def rows(array, width, name, dtype=np.float32):
    """Returns (array[M, width] of dtype, row stride in bytes, single) for a [M, width] or [width] input.

    A strided view whose rows are packed elements of the right type passes through without a copy."""
    data = np.asarray(array, dtype=dtype)
    single = data.ndim == 1
    if single:
        data = data.reshape(1, -1)
    if data.ndim != 2 or data.shape[1] != width:
        raise ValueError("%s must have shape [M, %d] (got %s)" % (name, width, np.shape(array)))
    itemsize = data.dtype.itemsize
    if data.shape[0] > 0 and (data.strides[1] != itemsize or data.strides[0] < width * itemsize):
        data = np.ascontiguousarray(data)
    stride = data.strides[0] if data.shape[0] > 1 else width * itemsize
    return data, stride, single


def vector(values, width, name, dtype=np.float32):
    """A contiguous 1-D array of exactly width values."""
    data = np.ascontiguousarray(values, dtype=dtype).reshape(-1)
    if data.shape[0] != width:
        raise ValueError("%s must have %d values (got %d)" % (name, width, data.shape[0]))
    return data


class Progress:
    """Wraps a Python callable(fraction, stage) -> truthy-to-cancel as a tp_progress_fn.

    An exception raised by the callable cancels the C call and is re-raised after it returns."""

    def __init__(self, callback):
        self.callback = callback
        self.error = None
        self.function = ProgressFn(self._call) if callback is not None else ProgressFn()

    def _call(self, user, fraction, stage):
        try:
            return 1 if self.callback(float(fraction), (stage or b"").decode("utf-8", "replace")) else 0
        except BaseException as error:  # noqa: B902 - handed back to the caller after the C call
            self.error = error
            return 1

    def reraise(self):
        if self.error is not None:
            error, self.error = self.error, None
            raise error
