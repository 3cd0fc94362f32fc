// Failures of the library: the tp_status as TetProbeStatus, with the library's message.
using System;

namespace TetProbe
{
    /// <summary>The C ABI's tp_status values.</summary>
    public enum TetProbeStatus
    {
        Ok = 0,
        InvalidArgument = 1,
        OutOfMemory = 2,
        IO = 3,
        InvalidBlob = 4,
        Version = 5,
        Degenerate = 6,
        TetGen = 7,
        Cancelled = 8,
        Outside = 9,
        Scene = 10,
        Unsupported = 11,
        BufferTooSmall = 12,
        Internal = 13,
    }

    /// <summary>Thrown when a tetprobe call fails; Status says how, Message says what and where.</summary>
    public class TetProbeException : Exception
    {
        public TetProbeStatus Status { get; private set; }

        public TetProbeException(TetProbeStatus status, string message)
            : base(status + ": " + message)
        {
            Status = status;
        }

        /// <summary>A failure found through another exception (e.g. a plugin without an expected entry point).</summary>
        public TetProbeException(TetProbeStatus status, string message, Exception inner)
            : base(status + ": " + message, inner)
        {
            Status = status;
        }

        /// <summary>The library's constant name of a status, e.g. "TP_ERROR_INVALID_BLOB" (tp_status_name).</summary>
        public static string StatusName(TetProbeStatus status)
        {
            NativeProxy.EnsureVersion();
            return NativeProxy.Utf8String(NativeMethods.tp_status_name((int)status));
        }
    }
}
