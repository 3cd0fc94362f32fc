"""tetprobe.Error: every failure of the library, with its status and message."""

import enum


class Status(enum.IntEnum):
    """The C ABI's tp_status values (TP_ERROR_<name>): Error.status is one of them; OK (0) is never raised."""
    OK = 0
    INVALID_ARGUMENT = 1
    OUT_OF_MEMORY = 2
    IO = 3
    INVALID_BLOB = 4
    VERSION = 5
    DEGENERATE = 6
    TETGEN = 7
    CANCELLED = 8
    OUTSIDE = 9
    SCENE = 10
    UNSUPPORTED = 11
    BUFFER_TOO_SMALL = 12
    INTERNAL = 13


class Error(RuntimeError):
    """A tetprobe call failed: .status is a Status (or the raw int), .message the library's text."""

    def __init__(self, status, message):
        try:
            status = Status(status)
        except ValueError:
            pass
        self.status = status
        self.message = message
        if isinstance(status, Status):
            name = "TP_OK" if status == Status.OK else "TP_ERROR_" + status.name
        else:
            name = "status %d" % status
        super().__init__("%s: %s" % (name, message) if message else name)
