// Batch queries on Span<T>/ReadOnlySpan<T> (compiled with TETPROBE_SPAN: Mono 6, .NET Core 2.1+, Unity 2021.2+):
// engine-owned buffers go to the library in place, without copies.
// Span overloads on by themselves wherever the runtime has Span<T> in its core library.
#if UNITY_2021_2_OR_NEWER || NETCOREAPP2_1_OR_GREATER || NETSTANDARD2_1_OR_GREATER
#define TETPROBE_SPAN
#endif
#if TETPROBE_SPAN
using System;
using System.Runtime.InteropServices;
#if UNITY_5_3_OR_NEWER
using Vector3 = UnityEngine.Vector3;
using Vector4 = UnityEngine.Vector4;
#endif

namespace TetProbe
{
    public sealed partial class ProbeStore
    {
        static readonly UIntPtr SpanPositionStride = (UIntPtr)12, SpanHintStride = (UIntPtr)4, SpanShStride = (UIntPtr)108,
                                SpanFourStride = (UIntPtr)16;

        /// <summary>Batch form on spans: results[i] at positions[i]; hints (empty = none) are read and updated; threads
        /// and chainHints as the array form.</summary>
        public void Interpolate(ReadOnlySpan<Vector3> positions, Span<int> hints, Span<SphericalHarmonicsL2> results,
                                int threads = 1, bool chainHints = false)
        {
            CheckSpans(positions.Length, hints.Length, results.Length, "results", 1, chainHints);
            TpBatchOptions options = NativeProxy.BatchOptions(threads, chainHints);
            StoreHandle store = Live();
            if (positions.Length == 0) return;
            int status = hints.Length > 0
                ? NativeMethods.tp_store_interpolate_batch(store, (UIntPtr)positions.Length,
                      ref MemoryMarshal.GetReference(positions), SpanPositionStride, ref MemoryMarshal.GetReference(hints),
                      SpanHintStride, ref MemoryMarshal.GetReference(results), SpanShStride, ref options)
                : NativeMethods.tp_store_interpolate_batch(store, (UIntPtr)positions.Length,
                      ref MemoryMarshal.GetReference(positions), SpanPositionStride, IntPtr.Zero, SpanHintStride,
                      ref MemoryMarshal.GetReference(results), SpanShStride, ref options);
            NativeProxy.Check(status);
        }

        /// <summary>Batch Weights on spans: probes[4 i .. 4 i + 3] and weights[4 i .. 4 i + 3] for positions[i].</summary>
        public void Weights(ReadOnlySpan<Vector3> positions, Span<int> hints, Span<uint> probes, Span<float> weights,
                            int threads = 1, bool chainHints = false)
        {
            CheckSpans(positions.Length, hints.Length, probes.Length, "probes", 4, chainHints);
            CheckSpans(positions.Length, hints.Length, weights.Length, "weights", 4, chainHints);
            TpBatchOptions options = NativeProxy.BatchOptions(threads, chainHints);
            StoreHandle store = Live();
            if (positions.Length == 0) return;
            int status = hints.Length > 0
                ? NativeMethods.tp_store_weights_batch(store, (UIntPtr)positions.Length, ref MemoryMarshal.GetReference(positions),
                      SpanPositionStride, ref MemoryMarshal.GetReference(hints), SpanHintStride,
                      ref MemoryMarshal.GetReference(probes), SpanFourStride, ref MemoryMarshal.GetReference(weights),
                      SpanFourStride, ref options)
                : NativeMethods.tp_store_weights_batch(store, (UIntPtr)positions.Length, ref MemoryMarshal.GetReference(positions),
                      SpanPositionStride, IntPtr.Zero, SpanHintStride, ref MemoryMarshal.GetReference(probes), SpanFourStride,
                      ref MemoryMarshal.GetReference(weights), SpanFourStride, ref options);
            NativeProxy.Check(status);
        }

        /// <summary>Batch InterpolateOcclusion on spans: sh[i] and occlusion[i] at positions[i]; hints (empty = none),
        /// threads and chainHints as the array form.</summary>
        public void InterpolateOcclusion(ReadOnlySpan<Vector3> positions, Span<int> hints, Span<SphericalHarmonicsL2> sh,
                                         Span<Vector4> occlusion, int threads = 1, bool chainHints = false)
        {
            CheckSpans(positions.Length, hints.Length, sh.Length, "sh", 1, chainHints);
            CheckSpans(positions.Length, hints.Length, occlusion.Length, "occlusion", 1, chainHints);
            TpBatchOptions options = NativeProxy.BatchOptions(threads, chainHints);
            StoreHandle store = Live();
            if (positions.Length == 0) return;
            int status = hints.Length > 0
                ? NativeMethods.tp_store_interpolate_occlusion_batch(store, (UIntPtr)positions.Length,
                      ref MemoryMarshal.GetReference(positions), SpanPositionStride, ref MemoryMarshal.GetReference(hints),
                      SpanHintStride, ref MemoryMarshal.GetReference(sh), SpanShStride, ref MemoryMarshal.GetReference(occlusion),
                      SpanFourStride, ref options)
                : NativeMethods.tp_store_interpolate_occlusion_batch(store, (UIntPtr)positions.Length,
                      ref MemoryMarshal.GetReference(positions), SpanPositionStride, IntPtr.Zero, SpanHintStride,
                      ref MemoryMarshal.GetReference(sh), SpanShStride, ref MemoryMarshal.GetReference(occlusion), SpanFourStride,
                      ref options);
            NativeProxy.Check(status);
        }

        static void CheckSpans(int positions, int hints, int outputLength, string output, int perPosition, bool chainHints)
        {
            if (outputLength < perPosition * (long)positions)
                throw new ArgumentException(output + " holds " + outputLength + " for " + positions + " positions", output);
            if (hints != 0 && hints < positions)
                throw new ArgumentException("hints holds " + hints + " for " + positions + " positions (empty = none)", "hints");
            if (hints != 0 && chainHints)
                throw new ArgumentException("chainHints applies only to batches without hints", "hints");
        }
    }
}
#endif
