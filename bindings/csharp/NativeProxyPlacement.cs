// Layer 2 for probe placement and probes inside geometry: statuses into exceptions, output buffers sized by the
// library's bound, progress and cancellation.
using System;
using System.Threading;
#if UNITY_5_3_OR_NEWER
using Vector3 = UnityEngine.Vector3;
#endif

namespace TetProbe
{
    internal static partial class NativeProxy
    {
        public static NativePlacementOptions DefaultPlacementOptions()
        {
            EnsureVersion();
            var options = new NativePlacementOptions();
            Check(NativeMethods.tp_placement_options_init(ref options));
            return options;
        }

        public static int PlacementBound(SceneHandle scene, NativePlacementOptions options)
        {
            UIntPtr bound;
            Check(NativeMethods.tp_place_probes_bound(scene, ref options, out bound));
            return checked((int)bound.ToUInt64());
        }

        /// <summary>tp_place_probes into buffers of tp_place_probes_bound's size; curve receives (probe count, error)
        /// pairs, two floats each.</summary>
        public static Vector3[] PlaceProbes(SceneHandle scene, NativePlacementOptions options, IProgress<float> progress,
                                            CancellationToken cancel, out float[] curve)
        {
            int bound = PlacementBound(scene, options);
            var positions = new Vector3[Math.Max(bound, 1)];
            var points = new float[2 * (bound + 1)];
            UIntPtr count, curvePoints;
            using (var bridge = ProgressBridge.Start(progress, cancel))
            {
                options.progress = bridge.Callback;
                options.progress_user = bridge.User;
                int status = NativeMethods.tp_place_probes(scene, ref options, positions, (UIntPtr)bound, out count, points,
                    (UIntPtr)(bound + 1), out curvePoints);
                bridge.Finish(status);
            }
            var placed = new Vector3[(int)count.ToUInt64()];
            Array.Copy(positions, placed, placed.Length);
            curve = new float[2 * (int)curvePoints.ToUInt64()];
            Array.Copy(points, curve, curve.Length);
            return placed;
        }

        public static uint[] FindInsideProbes(SceneHandle scene, Vector3[] positions)
        {
            EnsureVersion();
            var indices = new uint[Math.Max(positions.Length, 1)];
            UIntPtr found;
            Check(NativeMethods.tp_find_inside_probes(scene, positions, PositionStride, (UIntPtr)positions.Length, indices,
                (UIntPtr)positions.Length, out found));
            var result = new uint[(int)found.ToUInt64()];
            Array.Copy(indices, result, result.Length);
            return result;
        }

        public static Vector3[] FixInsideProbes(SceneHandle scene, Vector3[] positions, uint mode, float margin)
        {
            EnsureVersion();
            var output = new Vector3[Math.Max(positions.Length, 1)];
            UIntPtr count;
            Check(NativeMethods.tp_fix_inside_probes(scene, positions, PositionStride, (UIntPtr)positions.Length, mode, margin,
                output, (UIntPtr)positions.Length, out count));
            var result = new Vector3[(int)count.ToUInt64()];
            Array.Copy(output, result, result.Length);
            return result;
        }
    }
}
