"""Arguments checked for the C ABI: numpy arrays as (array, row stride) pairs, copying only when the layout
demands it, and scalars, names, paths and callbacks, each failure a TypeError or ValueError naming the
parameter."""

import numbers
import os

import numpy as np

from ._native import ProgressFn


#: The array kinds accepted for each target dtype: numbers convert to float32, only integers to indices.
_ACCEPTED_KINDS = {np.dtype(np.float32): "fiu", np.dtype(np.int32): "iu", np.dtype(np.uint32): "iu",
                   np.dtype(np.uint8): "iu"}


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


def _type_name(value):
    return type(value).__name__


def number(value, name):
    """value as a float: any real number (Python, numpy) but a bool; TypeError naming the parameter."""
    if isinstance(value, (bool, np.bool_)) or not isinstance(value, numbers.Real):
        raise TypeError("%s must be a number (got %s)" % (name, _type_name(value)))
    return float(value)


def integer(value, name, low=None, high=None):
    """value as an int in [low, high] (None = unbounded): any integer (Python, numpy) but a bool; TypeError
    or ValueError naming the parameter."""
    if isinstance(value, (bool, np.bool_)) or not isinstance(value, numbers.Integral):
        raise TypeError("%s must be an integer (got %s)" % (name, _type_name(value)))
    value = int(value)
    if (low is not None and value < low) or (high is not None and value > high):
        raise ValueError("%s must lie in [%s, %s] (got %d)" % (name, low, "inf" if high is None else high, value))
    return value


#: The largest value of a uint32_t / uint64_t parameter.
UINT32_MAX, UINT64_MAX = 0xFFFFFFFF, 0xFFFFFFFFFFFFFFFF


def flag(value, name):
    """value as a bool: True, False (Python or numpy) or the integers 0 and 1; TypeError naming the parameter."""
    if isinstance(value, (bool, np.bool_)):
        return bool(value)
    if isinstance(value, numbers.Integral) and value in (0, 1):
        return bool(value)
    raise TypeError("%s must be True or False (got %r)" % (name, value))


def choice(value, table, name):
    """The table's value for the name `value` (case-insensitive): TypeError if it is not a string, ValueError
    naming the parameter and the choices if the table does not hold it."""
    if not isinstance(value, str):
        raise TypeError("%s must be one of %s (got %s)" % (name, ", ".join(repr(k) for k in table), _type_name(value)))
    if value.lower() not in table:
        raise ValueError("%s must be one of %s (got %r)" % (name, ", ".join(repr(k) for k in table), value))
    return table[value.lower()]


def path(value, name):
    """A file path (str, bytes or os.PathLike) encoded for the C ABI; TypeError naming the parameter."""
    if not isinstance(value, (str, bytes, os.PathLike)):
        raise TypeError("%s must be a path: str, bytes or os.PathLike (got %s)" % (name, _type_name(value)))
    return os.fsencode(value)


class Progress:
    """Wraps a Python callable(fraction, stage) -> truthy-to-cancel as a tp_progress_fn.

    An exception raised by the callable cancels the C call and is re-raised after it returns."""

    def __init__(self, callback, name="progress"):
        if callback is not None and not callable(callback):
            raise TypeError("%s must be a callable progress(fraction, stage) or None (got %s)" %
                            (name, _type_name(callback)))
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
