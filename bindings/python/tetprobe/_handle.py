"""NativeHandle: owns one native object and releases it exactly once (close, `with`, or collection)."""

import ctypes

from .errors import Error, Status


class NativeHandle:
    """Base of the classes that wrap a tp_* handle; subclasses name their release function and noun."""

    _release = None  # the tp_*_release function, looked up on the subclass
    _noun = "object"

    def _adopt(self, handle):
        self._handle = ctypes.c_void_p(handle)

    def close(self):
        """Releases the native object now (also done when the Python object is collected)."""
        if getattr(self, "_handle", None):
            type(self)._release(self._handle)
            self._handle = None

    def __del__(self):
        self.close()

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.close()

    def _live(self):
        if not getattr(self, "_handle", None):
            raise Error(Status.INVALID_ARGUMENT, "the %s is closed" % self._noun)
        return self._handle
