// Layer 3: the lighting bake. BakeOptions, the EffectsPlan of what a bake will simulate, and Baker (SH and
// occlusion probes).
using System;
using System.Threading;
#if UNITY_5_3_OR_NEWER
using Vector3 = UnityEngine.Vector3;
#endif

namespace TetProbe
{
    /// <summary>Options of the bake (tp_bake_options); a new instance holds the library's defaults.</summary>
    public sealed class BakeOptions
    {
        /// <summary>Rays per probe.</summary>
        public int Rays;
        /// <summary>Surface reflections between an emitter and the probe (0 = only light arriving directly).</summary>
        public int Bounces;
        /// <summary>The same seed gives the same bytes whatever the thread count.</summary>
        public ulong Seed;
        /// <summary>Threads of the bake (0 = all cores).</summary>
        public int Threads;
        /// <summary>Test aid: every mesh occludes every light (no shadow caster culling).</summary>
        public bool NoCulling;

        public BakeOptions()
        {
            NativeBakeOptions defaults = NativeProxy.DefaultBakeOptions();
            Rays = (int)defaults.rays;
            Bounces = (int)defaults.bounces;
            Seed = defaults.seed;
            Threads = (int)defaults.threads;
            NoCulling = (defaults.flags & NativeMethods.BakeNoCulling) != 0;
        }

        internal NativeBakeOptions ToNative()
        {
            if (Rays < 0) throw new ArgumentOutOfRangeException("Rays", Rays, "Rays must be >= 0");
            if (Bounces < 0) throw new ArgumentOutOfRangeException("Bounces", Bounces, "Bounces must be >= 0");
            if (Threads < 0) throw new ArgumentOutOfRangeException("Threads", Threads, "Threads must be >= 0");
            NativeBakeOptions options = NativeProxy.DefaultBakeOptions();
            options.rays = (uint)Rays;
            options.bounces = (uint)Bounces;
            options.seed = Seed;
            options.threads = (uint)Threads;
            options.flags = NoCulling ? NativeMethods.BakeNoCulling : 0u;
            return options;
        }
    }

    /// <summary>What a bake of a scene will simulate (tp_effects_plan), with the library's one-line summary.</summary>
    public sealed class EffectsPlan
    {
        public int Lights, DirectLights, RealtimeLights, OutOfRangeLights, EmissiveMeshes, Bounces, Meshes;
        /// <summary>Sum over shadowing lights of the meshes kept in its occlusion set, and of those considered.</summary>
        public int ShadowCasters, ShadowCasterCandidates;
        /// <summary>Probes of the given positions inside geometry (the summary lists their indices).</summary>
        public int InsideProbes;
        /// <summary>True if the scene has a non-black sky.</summary>
        public bool Sky;
        /// <summary>True if any simulated light casts shadows.</summary>
        public bool Shadows;
        /// <summary>e.g. "direct: 2 lights (1 out of range); sky: off; emissive: 3 meshes; bounces: 2; ...".</summary>
        public string Summary;

        internal EffectsPlan(NativeEffectsPlan n, string summary)
        {
            Lights = (int)n.lights;
            DirectLights = (int)n.direct_lights;
            RealtimeLights = (int)n.realtime_lights;
            OutOfRangeLights = (int)n.out_of_range_lights;
            EmissiveMeshes = (int)n.emissive_meshes;
            Bounces = (int)n.bounces;
            Meshes = (int)n.meshes;
            ShadowCasters = (int)n.shadow_casters;
            ShadowCasterCandidates = (int)n.shadow_caster_candidates;
            InsideProbes = (int)n.inside_probes;
            Sky = n.sky != 0;
            Shadows = n.shadows != 0;
            Summary = summary;
        }

        public override string ToString() { return Summary; }
    }

    /// <summary>Bakes the SH of incoming radiance at probe positions of a scene (full library only).</summary>
    public static class Baker
    {
        /// <summary>What Bake(scene, positions, options) will simulate, without baking.</summary>
        public static EffectsPlan Plan(Scene scene, Vector3[] positions, BakeOptions options = null)
        {
            Check(scene, positions);
            string text;
            NativeEffectsPlan plan = NativeProxy.Plan(scene.Live(), positions, (options ?? new BakeOptions()).ToNative(), out text);
            return new EffectsPlan(plan, text);
        }

        /// <summary>Bakes one SH per position (the contract of capi/tetprobe.h). progress receives fractions in [0, 1]
        /// on the calling thread; cancelling `cancel` stops the bake with OperationCanceledException.</summary>
        public static SphericalHarmonicsL2[] Bake(Scene scene, Vector3[] positions, BakeOptions options = null,
                                                  IProgress<float> progress = null,
                                                  CancellationToken cancel = default(CancellationToken))
        {
            Check(scene, positions);
            return NativeProxy.Bake(scene.Live(), positions, (options ?? new BakeOptions()).ToNative(), progress, cancel);
        }

        /// <summary>Occlusion probes: per position, the visibility of each of the scene's mixed lights (LightMode.Mixed, in
        /// the order added; one shadow ray each, so 0 or 255) and 255 for channels without a light. Give the result to
        /// BuildOptions.Occlusion. progress and cancel as Bake.</summary>
        public static OcclusionProbes BakeOcclusion(Scene scene, Vector3[] positions, IProgress<float> progress = null,
                                                    CancellationToken cancel = default(CancellationToken))
        {
            Check(scene, positions);
            int mixedLights;
            ProbeOcclusion[] probes = NativeProxy.BakeOcclusion(scene.Live(), positions, NativeProxy.DefaultBakeOptions(), progress,
                                                                cancel, out mixedLights);
            return new OcclusionProbes(probes, mixedLights);
        }

        static void Check(Scene scene, Vector3[] positions)
        {
            if (scene == null) throw new ArgumentNullException("scene");
            if (positions == null) throw new ArgumentNullException("positions");
        }
    }
}
