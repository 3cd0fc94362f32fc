// Progress callbacks of long native work (bake, build) into IProgress<float> and a CancellationToken.
using System;
using System.Runtime.ExceptionServices;
using System.Runtime.InteropServices;
using System.Threading;

namespace TetProbe
{
    [UnmanagedFunctionPointer(CallingConvention.Cdecl)]
    internal delegate int ProgressCallback(IntPtr user, float fraction, IntPtr stage);

    /// <summary>Marks a static method that native code calls back (IL2CPP and Mono AOT look for this name).</summary>
    [AttributeUsage(AttributeTargets.Method)]
    internal sealed class MonoPInvokeCallbackAttribute : Attribute
    {
        public MonoPInvokeCallbackAttribute(Type type) { }
    }

    /// <summary>One native call's progress: the library calls a static callback (alive for the whole process, so it
    /// can never be collected during a call) with a GCHandle to this object as its user pointer. The callback reports
    /// to the IProgress and returns non-zero once the token is cancelled; an exception thrown by the IProgress also
    /// cancels the native work and is rethrown by Finish, never thrown through native frames.</summary>
    internal sealed class ProgressBridge : IDisposable
    {
        static readonly ProgressCallback Trampoline = OnProgress;
        static readonly IntPtr TrampolinePointer = Marshal.GetFunctionPointerForDelegate(Trampoline);

        readonly IProgress<float> progress;
        readonly CancellationToken cancel;
        GCHandle self;
        Exception failure;

        ProgressBridge(IProgress<float> progress, CancellationToken cancel)
        {
            this.progress = progress;
            this.cancel = cancel;
            if (progress != null || cancel.CanBeCanceled) self = GCHandle.Alloc(this);
        }

        /// <summary>Throws OperationCanceledException at once if the token is already cancelled.</summary>
        public static ProgressBridge Start(IProgress<float> progress, CancellationToken cancel)
        {
            cancel.ThrowIfCancellationRequested();
            return new ProgressBridge(progress, cancel);
        }

        /// <summary>The tp_progress_fn to pass (NULL when there is nothing to report or cancel).</summary>
        public IntPtr Callback { get { return self.IsAllocated ? TrampolinePointer : IntPtr.Zero; } }

        public IntPtr User { get { return self.IsAllocated ? GCHandle.ToIntPtr(self) : IntPtr.Zero; } }

        [MonoPInvokeCallback(typeof(ProgressCallback))]
        static int OnProgress(IntPtr user, float fraction, IntPtr stage)
        {
            var bridge = (ProgressBridge)GCHandle.FromIntPtr(user).Target;
            try
            {
                if (bridge.progress != null) bridge.progress.Report(fraction);
                return bridge.cancel.IsCancellationRequested ? 1 : 0;
            }
            catch (Exception e)
            {
                bridge.failure = e;
                return 1;
            }
        }

        /// <summary>Turns the call's status into the caller's exception: the IProgress's own, OperationCanceledException
        /// for a cancelled token, TetProbeException otherwise.</summary>
        public void Finish(int status)
        {
            if (failure != null) ExceptionDispatchInfo.Capture(failure).Throw();
            if (status == (int)TetProbeStatus.Cancelled && cancel.IsCancellationRequested)
                throw new OperationCanceledException("the tetprobe call was cancelled: " +
                    NativeProxy.Utf8String(NativeMethods.tp_last_error()), cancel);
            NativeProxy.Check(status);
        }

        public void Dispose()
        {
            if (self.IsAllocated) self.Free();
        }
    }
}
