"""The loaded native library: where it was found, its version, and the names of its statuses."""

from ._arrays import integer
from ._native import library_path, lib

__all__ = ["library_path", "library_version", "status_name"]


def library_version():
    """The loaded library's version as a (major, minor, patch) tuple of ints (tp_version)."""
    version = lib.tp_version()
    return (version >> 16) & 0xFFFF, (version >> 8) & 0xFF, version & 0xFF


def status_name(status):
    """The C constant name of a status (a Status or an int), e.g. "TP_ERROR_INVALID_BLOB", from the library.

    An int the library does not know gets the library's own answer for it (tp_status_name)."""
    return lib.tp_status_name(integer(status, "status", -2 ** 31, 2 ** 31 - 1)).decode("ascii", "replace")
