// The native tp_store* in a SafeHandle: released exactly once, even when the owner is never disposed.
using System;
using System.Runtime.InteropServices;

namespace TetProbe
{
    internal sealed class StoreHandle : SafeHandle
    {
        public StoreHandle() : base(IntPtr.Zero, true) { }

        public override bool IsInvalid { get { return handle == IntPtr.Zero; } }

        protected override bool ReleaseHandle()
        {
            return NativeMethods.tp_store_release(handle) == 0;
        }
    }
}
