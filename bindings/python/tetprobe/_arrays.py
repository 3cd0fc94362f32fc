"""numpy arrays as (array, row stride) pairs for the C ABI, copying only when the layout demands it."""

import numpy as np

from ._native import ProgressFn


#: The array kinds accepted for each target dtype: numbers convert to float32, only integers to indices.
_ACCEPTED_KINDS = {np.dtype(np.float32): "fiu", np.dtype(np.int32): "iu", np.dtype(np.uint32): "iu"}


def as_array(values, name, dtype=np.float32):
    """values as a numpy array of dtype, or TypeError/ValueError naming the parameter.

    Floats, ints and unsigned ints convert to float32; only integer arrays convert to int32/uint32, and
    their values must fit (no silent wrap-around)."""
    try:
        data = np.asarray(values)
    except ValueError as error:  # ragged nested lists
        raise ValueError("%s must be a rectangular array of numbers (%s)" % (name, error)) from None
    target = np.dtype(dtype)
    if data.dtype.kind not in _ACCEPTED_KINDS[target]:
        wanted = "numbers" if target.kind == "f" else "integers"
        raise TypeError("%s must be an array of %s, converted to %s (got dtype %s)" %
                        (name, wanted, target, data.dtype))
    if target.kind in "iu" and data.size and data.dtype != target:
        info = np.iinfo(target)
        low, high = data.min(), data.max()
        if low < info.min or high > info.max:
            raise ValueError("%s must lie in [%d, %d] (got values from %d to %d)" %
                             (name, info.min, info.max, low, high))
    return data.astype(target, copy=False)


def rows(array, width, name, dtype=np.float32):
    """Returns (array[M, width] of dtype, row stride in bytes, single) for a [M, width] or [width] input.

    A strided view whose rows are packed elements of the right type passes through without a copy."""
    data = as_array(array, name, dtype)
    single = data.ndim == 1
    if single:
        data = data.reshape(1, -1)
    if data.ndim != 2 or data.shape[1] != width:
        raise ValueError("%s must have shape [M, %d] or [%d] (got %s)" % (name, width, width, np.shape(array)))
    itemsize = data.dtype.itemsize
    if data.shape[0] > 0 and (data.strides[1] != itemsize or data.strides[0] < width * itemsize):
        data = np.ascontiguousarray(data)
    stride = data.strides[0] if data.shape[0] > 1 else width * itemsize
    return data, stride, single


def vector(values, width, name, dtype=np.float32):
    """A contiguous 1-D array of exactly width values."""
    data = np.ascontiguousarray(as_array(values, name, dtype)).reshape(-1)
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
