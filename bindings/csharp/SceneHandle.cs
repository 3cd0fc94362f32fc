// The native tp_scene* in a SafeHandle: released exactly once, even when the owner is never disposed.
using System;
using System.Runtime.InteropServices;

namespace TetProbe
{
    internal sealed class SceneHandle : SafeHandle
    {
        public SceneHandle() : base(IntPtr.Zero, true) { }

        public override bool IsInvalid { get { return handle == IntPtr.Zero; } }

        protected override bool ReleaseHandle()
        {
            return NativeMethods.tp_scene_release(handle) == 0;
        }
    }
}
