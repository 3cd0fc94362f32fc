// Layer 3: automatic probe placement and probes inside geometry (full library only).
using System;
using System.Threading;
#if UNITY_5_3_OR_NEWER
using Vector3 = UnityEngine.Vector3;
#endif

namespace TetProbe
{
    /// <summary>Where placement's candidates stand (TP_PLACEMENT_*).</summary>
    public enum PlacementMode
    {
        /// <summary>A lattice over the scene's bounds.</summary>
        Whole = 0,
        /// <summary>Columns of the lattice across a height band above every upward-facing surface (the scene's up).</summary>
        Walkable = 1,
    }

    /// <summary>What FixInsideProbes does with probes inside geometry (TP_INSIDE_*).</summary>
    public enum InsideProbeFix
    {
        /// <summary>Leave them out (the others keep their order).</summary>
        Drop = 0,
        /// <summary>Move each to the nearest free point at least the margin from every surface.</summary>
        Push = 1,
    }

    /// <summary>Options of Placement.PlaceProbes (tp_placement_options); a new instance holds the library's defaults.
    /// Distances are world units.</summary>
    public sealed class PlacementOptions
    {
        public PlacementMode Mode;
        /// <summary>Candidate lattice spacing (positive).</summary>
        public float Spacing;
        /// <summary>Least distance of a probe from every surface.</summary>
        public float Margin;
        /// <summary>Walkable mode: the height band above the floor.</summary>
        public float WalkMinHeight, WalkMaxHeight;
        /// <summary>Placement stops at this many probes (0 = no target; set ErrorBound to 0 as well to reach it
        /// whatever the error).</summary>
        public int TargetCount;
        /// <summary>Without a target, placement stops at the fewest probes whose estimated error (luminance irradiance
        /// at validation points relative to its mean, the bake's noise taken out) is at most this (0 = no bound).</summary>
        public float ErrorBound;
        /// <summary>Rays per candidate of the low-sample bake (at least 2: it is baked in two halves), and its bounces.</summary>
        public int Rays, Bounces;
        /// <summary>The same seed gives the same probes whatever the thread count.</summary>
        public ulong Seed;
        /// <summary>0 = all cores.</summary>
        public int Threads;
        /// <summary>Points closer than this to a point or spot light do not count in the error (0 = all count).</summary>
        public float LightClearance;

        public PlacementOptions()
        {
            NativePlacementOptions defaults = NativeProxy.DefaultPlacementOptions();
            Mode = (PlacementMode)defaults.mode;
            Spacing = defaults.spacing;
            Margin = defaults.margin;
            WalkMinHeight = defaults.walk_min_height;
            WalkMaxHeight = defaults.walk_max_height;
            TargetCount = (int)defaults.target_count;
            ErrorBound = defaults.error_bound;
            Rays = (int)defaults.rays;
            Bounces = (int)defaults.bounces;
            Seed = defaults.seed;
            Threads = (int)defaults.threads;
            LightClearance = defaults.light_clearance;
        }

        internal NativePlacementOptions ToNative()
        {
            if (TargetCount < 0) throw new ArgumentOutOfRangeException("TargetCount", TargetCount, "TargetCount must be >= 0");
            if (Rays < 0) throw new ArgumentOutOfRangeException("Rays", Rays, "Rays must be >= 0");
            if (Bounces < 0) throw new ArgumentOutOfRangeException("Bounces", Bounces, "Bounces must be >= 0");
            if (Threads < 0) throw new ArgumentOutOfRangeException("Threads", Threads, "Threads must be >= 0");
            NativePlacementOptions options = NativeProxy.DefaultPlacementOptions();
            options.mode = (uint)Mode;
            options.spacing = Spacing;
            options.margin = Margin;
            options.walk_min_height = WalkMinHeight;
            options.walk_max_height = WalkMaxHeight;
            options.target_count = (uint)TargetCount;
            options.error_bound = ErrorBound;
            options.rays = (uint)Rays;
            options.bounces = (uint)Bounces;
            options.seed = Seed;
            options.threads = (uint)Threads;
            options.light_clearance = LightClearance;
            return options;
        }
    }

    /// <summary>One point of placement's error curve: the estimated error (see PlacementOptions.ErrorBound) of the
    /// first Probes probes chosen.</summary>
    public struct PlacementErrorPoint
    {
        public int Probes;
        public float Error;
    }

    /// <summary>Placed probes in the order chosen (refined at the target: a smaller target's set need not be a prefix; an error-bound result and large targets are the greedy's order) and the error curve, one
    /// point per round with counts increasing to them (empty when every candidate is returned unchosen).</summary>
    public sealed class PlacementResult
    {
        public readonly Vector3[] Positions;
        public readonly PlacementErrorPoint[] ErrorCurve;

        internal PlacementResult(Vector3[] positions, float[] curve)
        {
            Positions = positions;
            ErrorCurve = new PlacementErrorPoint[curve.Length / 2];
            for (int i = 0; i < ErrorCurve.Length; ++i)
                ErrorCurve[i] = new PlacementErrorPoint { Probes = (int)curve[2 * i], Error = curve[2 * i + 1] };
        }
    }

    /// <summary>Probes proposed from a scene, and a user's probes found inside geometry (the back of a one-sided
    /// triangle, or the inside of a closed two-sided mesh; see capi/tetprobe.h).</summary>
    public static class Placement
    {
        /// <summary>Places probes: candidates on a lattice (options.Mode), none inside geometry or within the margin of a
        /// surface (and connected to the scene's playable seeds when it has some), baked with options.Rays, then chosen by
        /// greedy insertion up to options.TargetCount or options.ErrorBound (see tp_place_probes).
        /// progress receives fractions in [0, 1] on the calling thread; cancelling `cancel` stops with
        /// OperationCanceledException.</summary>
        public static PlacementResult PlaceProbes(Scene scene, PlacementOptions options = null, IProgress<float> progress = null,
                                                  CancellationToken cancel = default(CancellationToken))
        {
            if (scene == null) throw new ArgumentNullException("scene");
            float[] curve;
            Vector3[] positions = NativeProxy.PlaceProbes(scene.Live(), (options ?? new PlacementOptions()).ToNative(), progress,
                                                          cancel, out curve);
            return new PlacementResult(positions, curve);
        }

        /// <summary>The most probes PlaceProbes returns for these options (the points the inside and margin tests are
        /// applied to); throws as PlaceProbes does on bad options.</summary>
        public static int MaxProbes(Scene scene, PlacementOptions options = null)
        {
            if (scene == null) throw new ArgumentNullException("scene");
            return NativeProxy.PlacementBound(scene.Live(), (options ?? new PlacementOptions()).ToNative());
        }

        /// <summary>Indices (ascending) of the positions inside the scene's geometry.</summary>
        public static int[] FindInsideProbes(Scene scene, Vector3[] positions)
        {
            if (scene == null) throw new ArgumentNullException("scene");
            if (positions == null) throw new ArgumentNullException("positions");
            uint[] found = NativeProxy.FindInsideProbes(scene.Live(), positions);
            var indices = new int[found.Length];
            for (int i = 0; i < found.Length; ++i) indices[i] = (int)found[i];
            return indices;
        }

        /// <summary>The positions with those inside geometry dropped (InsideProbeFix.Drop) or each moved to the nearest
        /// free point at least `margin` from every surface (InsideProbeFix.Push, every probe kept in order). A probe that
        /// cannot be pushed out throws TetProbeException(Scene) naming it.</summary>
        public static Vector3[] FixInsideProbes(Scene scene, Vector3[] positions, InsideProbeFix fix, float margin = 0.1f)
        {
            if (scene == null) throw new ArgumentNullException("scene");
            if (positions == null) throw new ArgumentNullException("positions");
            return NativeProxy.FixInsideProbes(scene.Live(), positions, (uint)fix, margin);
        }
    }
}
