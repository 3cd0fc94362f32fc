// The C# surfaces of placement, probes inside geometry, occlusion probes and leak control, against the real library:
// probes placed in a closed room stay clear of its walls and out of its pillar, inside probes are found, dropped and
// pushed out, a mixed light behind a wall gives 0/1 occlusion that the store blends, and leak control weighs down the
// probes behind a wall.
using System;
using System.Collections.Generic;
using System.Linq;
using System.Threading;
using TetProbe;

static class PlacementTests
{
    static readonly Vector3 RoomLo = new Vector3(0, 0, 0), RoomHi = new Vector3(6, 3, 6);
    static readonly Vector3 PillarLo = new Vector3(2.5f, 0, 2.5f), PillarHi = new Vector3(3.5f, 3, 3.5f);
    // A box's 12 triangles over corners numbered by bits (x = 1, y = 2, z = 4), counter-clockwise seen from outside.
    static readonly int[] Box = { 0, 4, 6, 0, 6, 2, 1, 3, 7, 1, 7, 5, 0, 1, 5, 0, 5, 4, 2, 6, 7, 2, 7, 3, 0, 2, 3, 0, 3, 1,
                                  4, 5, 7, 4, 7, 6 };

    static Vector3[] Corners(Vector3 lo, Vector3 hi)
    {
        var corners = new Vector3[8];
        for (int c = 0; c < 8; ++c)
            corners[c] = new Vector3((c & 1) != 0 ? hi.x : lo.x, (c & 2) != 0 ? hi.y : lo.y, (c & 4) != 0 ? hi.z : lo.z);
        return corners;
    }

    static Material Surface(bool twoSided)
    {
        return Material.Diffuse(new Vector3(0.5f, 0.5f, 0.5f), default(Vector3), twoSided);
    }

    /// <summary>A 6 x 3 x 6 room seen from inside (one-sided faces turned in: outside is solid), a closed two-sided
    /// pillar (solid) and a lamp.</summary>
    static Scene Room()
    {
        var scene = new Scene();
        scene.AddMesh(Corners(RoomLo, RoomHi), Box.Reverse().ToArray(), Surface(false));
        scene.AddMesh(Corners(PillarLo, PillarHi), Box, Surface(true));
        scene.AddLight(Light.Point(new Vector3(0.6f, 2.4f, 0.6f), new Vector3(1, 1, 1), 30));
        return scene;
    }

    static bool InPillar(Vector3 p)
    {
        return p.x > PillarLo.x && p.x < PillarHi.x && p.y > PillarLo.y && p.y < PillarHi.y && p.z > PillarLo.z && p.z < PillarHi.z;
    }

    /// <summary>Distance to the room's walls and the pillar's surface, for a point in the room outside the pillar.</summary>
    static float Clearance(Vector3 p)
    {
        float walls = Math.Min(Math.Min(Math.Min(p.x - RoomLo.x, RoomHi.x - p.x), Math.Min(p.y - RoomLo.y, RoomHi.y - p.y)),
                               Math.Min(p.z - RoomLo.z, RoomHi.z - p.z));
        float dx = Math.Max(Math.Max(PillarLo.x - p.x, p.x - PillarHi.x), 0), dy = Math.Max(Math.Max(PillarLo.y - p.y, p.y - PillarHi.y), 0);
        float dz = Math.Max(Math.Max(PillarLo.z - p.z, p.z - PillarHi.z), 0);
        return Math.Min(walls, (float)Math.Sqrt(dx * dx + dy * dy + dz * dz));
    }

    public static void Run()
    {
        Placing();
        InsideProbes();
        OcclusionAndLeakControl();
    }

    static void Placing()
    {
        using (Scene room = Room())
        {
            var options = new PlacementOptions { Spacing = 0.75f, Margin = 0.2f, TargetCount = 40, ErrorBound = 0, Rays = 64,
                                                 Bounces = 1, Seed = 2 };
            var defaults = new PlacementOptions();
            Tests.Check(defaults.Mode == PlacementMode.Whole && defaults.Spacing == 1 && Math.Abs(defaults.Margin - 0.1f) < 1e-7 &&
                        defaults.Rays == 128 && Math.Abs(defaults.ErrorBound - 0.25f) < 1e-7 && defaults.LightClearance == 1,
                        "PlacementOptions defaults from the library");
            int bound = Placement.MaxProbes(room, options);
            var fractions = new List<float>();
            PlacementResult placed = Placement.PlaceProbes(room, options, new Recorder(fractions));
            Tests.Check(placed.Positions.Length == 40, "placement reaches its target (" + placed.Positions.Length + ")");
            Tests.Check(bound > 100, "MaxProbes bounds the candidates (" + bound + ")");
            float least = placed.Positions.Min(p => Clearance(p));
            Tests.Check(!placed.Positions.Any(InPillar) && least >= 0.2f,
                        "placed probes clear of the walls and the pillar by the margin (least " + least + ")");
            PlacementErrorPoint[] curve = placed.ErrorCurve;
            bool rising = true;
            for (int i = 1; i < curve.Length; ++i) rising &= curve[i].Probes > curve[i - 1].Probes;
            Tests.Check(curve[0].Probes < 40 && curve[curve.Length - 1].Probes == 40 && curve[curve.Length - 1].Error > 0 &&
                        curve[curve.Length - 1].Error < curve[0].Error && rising,
                        "error curve from the start up to the target, falling");
            Tests.Check(fractions.Count > 0 && fractions.All(f => f >= 0 && f <= 1), "placement reports progress");
            options.Threads = 1;
            PlacementResult again = Placement.PlaceProbes(room, options);
            Tests.Check(again.Positions.SequenceEqual(placed.Positions), "same seed, same probes on one thread");
            options.TargetCount = 25;
            PlacementResult fewer = Placement.PlaceProbes(room, options);
            PlacementErrorPoint[] rounds = fewer.ErrorCurve.Take(fewer.ErrorCurve.Length - 1).ToArray();
            Func<PlacementErrorPoint, long> bits = p => ((long)p.Probes << 32) | (uint)BitConverter.ToInt32(BitConverter.GetBytes(p.Error), 0);
            Tests.Check(fewer.Positions.Length == 25 && fewer.ErrorCurve[fewer.ErrorCurve.Length - 1].Probes == 25 &&
                        rounds.Length <= curve.Length && rounds.Select(bits).SequenceEqual(curve.Take(rounds.Length).Select(bits)),
                        "a smaller target gets its own set after the same greedy rounds, bit for bit");
            options.TargetCount = 40;

            var walkable = new PlacementOptions { Mode = PlacementMode.Walkable, Spacing = 0.75f, Margin = 0.2f, WalkMinHeight = 0,
                                                  WalkMaxHeight = 1, ErrorBound = 0, Rays = 32 };
            Vector3[] floor = Placement.PlaceProbes(room, walkable).Positions;
            Tests.Check(floor.Length > 20 && floor.All(p => p.y <= 1.0f), "walkable probes stand in the band above the floor");
            room.SetPlayableSeeds(new[] { new Vector3(1, 0.5f, 1) });
            Tests.Check(Placement.PlaceProbes(room, walkable).Positions.Length == floor.Length, "a seed in the room keeps its candidates");
            room.SetPlayableSeeds(new[] { new Vector3(50, 0.5f, 50) });
            Tests.Throws<TetProbeException>(() => Placement.PlaceProbes(room, walkable), "a seed that sees no candidate",
                                            e => e.Status == TetProbeStatus.Scene && e.Message.Contains("playable seeds"));
            room.SetPlayableSeeds(new Vector3[0]);

            Tests.Throws<TetProbeException>(() => Placement.PlaceProbes(room, new PlacementOptions { Spacing = 0 }), "zero spacing",
                                            e => e.Status == TetProbeStatus.InvalidArgument && e.Message.Contains("spacing"));
            Tests.Throws<TetProbeException>(() => Placement.PlaceProbes(room, new PlacementOptions { Spacing = 0.75f, TargetCount = 100000 }),
                                            "a target above the candidates", e => e.Message.Contains("target_count"));
            Tests.Throws<ArgumentOutOfRangeException>(() => Placement.PlaceProbes(room, new PlacementOptions { Rays = -1 }), "negative rays");
            var cancel = new CancellationTokenSource();
            options.TargetCount = 30;
            Tests.Throws<OperationCanceledException>(
                () => Placement.PlaceProbes(room, options, new Recorder(fractions, f => { if (f > 0.3f) cancel.Cancel(); }), cancel.Token),
                "cancelled placement");
        }
        using (var sheet = new Scene())
        {
            sheet.AddMesh(new[] { new Vector3(0, 0, 0), new Vector3(0, 0, 4), new Vector3(4, 0, 4), new Vector3(4, 0, 0) },
                          new[] { 0, 1, 2, 0, 2, 3 }, Surface(true));
            Tests.Throws<TetProbeException>(() => Placement.PlaceProbes(sheet), "a scene with no inside",
                                            e => e.Status == TetProbeStatus.Scene && e.Message.Contains("cannot be decided"));
        }
    }

    static void InsideProbes()
    {
        using (Scene room = Room())
        {
            var positions = new[] { new Vector3(1, 1, 1), new Vector3(3, 1.5f, 3), new Vector3(2.6f, 0.5f, 3.4f), new Vector3(5, 2, 5) };
            int[] inside = Placement.FindInsideProbes(room, positions);
            Tests.Check(inside.SequenceEqual(new[] { 1, 2 }), "the two probes in the pillar are found (" + string.Join(",", inside) + ")");
            EffectsPlan plan = Baker.Plan(room, positions, new BakeOptions { Rays = 16 });
            Tests.Check(plan.InsideProbes == 2 && plan.Summary.Contains("inside geometry: 2 probes (1, 2)"), "the plan counts them");
            Vector3[] kept = Placement.FixInsideProbes(room, positions, InsideProbeFix.Drop);
            Tests.Check(kept.SequenceEqual(new[] { positions[0], positions[3] }), "Drop keeps the others in order");
            Vector3[] pushed = Placement.FixInsideProbes(room, positions, InsideProbeFix.Push, 0.25f);
            Tests.Check(pushed.Length == 4 && pushed[0].Equals(positions[0]) && pushed[3].Equals(positions[3]), "Push moves only the inside ones");
            Tests.Check(!pushed.Any(InPillar) && pushed.All(p => Clearance(p) >= 0.25f), "pushed out by the margin");
            Tests.Check(Placement.FindInsideProbes(room, pushed).Length == 0 && Placement.FindInsideProbes(room, new Vector3[0]).Length == 0,
                        "nothing inside after the push");
            Tests.Throws<TetProbeException>(() => Placement.FixInsideProbes(room, positions, (InsideProbeFix)7), "unknown fix",
                                            e => e.Status == TetProbeStatus.InvalidArgument);
            Tests.Throws<ArgumentNullException>(() => Placement.FindInsideProbes(room, null), "null positions");
        }
    }

    /// <summary>A two-sided wall in the plane x = 0.37 (below y = 0.6) and a light travelling +x of the given mode.</summary>
    static Scene Wall(LightMode mode)
    {
        var scene = new Scene();
        scene.AddMesh(new[] { new Vector3(0.37f, -10, -10), new Vector3(0.37f, 0.6f, -10), new Vector3(0.37f, 0.6f, 10),
                              new Vector3(0.37f, -10, 10) }, new[] { 0, 1, 2, 0, 2, 3 }, Surface(true));
        scene.AddLight(Light.Directional(new Vector3(1, 0, 0), new Vector3(1, 1, 1), 1, mode));
        return scene;
    }

    static Vector3[] Lattice()
    {
        var points = new List<Vector3>();
        for (int x = -2; x <= 2; ++x)
            for (int y = -2; y <= 2; ++y)
                for (int z = -2; z <= 2; ++z) points.Add(new Vector3(x, y, z));
        return points.ToArray();
    }

    static void OcclusionAndLeakControl()
    {
        Vector3[] probes = Lattice();
        var random = new Random(3);
        var points = new Vector3[400];
        for (int i = 0; i < points.Length; ++i)
            points[i] = new Vector3((float)random.NextDouble() * 4 - 2, (float)random.NextDouble() * 4 - 2, (float)random.NextDouble() * 4 - 2);
        using (Scene wall = Wall(LightMode.Mixed))
        {
            OcclusionProbes occlusion = Baker.BakeOcclusion(wall, probes);
            Tests.Check(occlusion.MixedLights == 1 && occlusion.Probes.Length == probes.Length, "one mixed light, a byte set per probe");
            bool quantised = true;
            for (int i = 0; i < probes.Length; ++i)
            {
                bool behind = probes[i].x > 0.37f && probes[i].y < 0.6f;
                ProbeOcclusion o = occlusion.Probes[i];
                quantised &= o.Light0 == (behind ? 0 : 255) && o.Light1 == 255 && o.Light2 == 255 && o.Light3 == 255;
            }
            Tests.Check(quantised, "a probe behind the wall sees the mixed light 0, the others 255; channels without a light 255");
            EffectsPlan plan = Baker.Plan(wall, probes, new BakeOptions { Rays = 8 });
            Tests.Check(plan.RealtimeLights == 1 && plan.DirectLights == 0, "a mixed light is baked for its bounce only");

            using (ProbeStore store = ProbeStore.Build(probes, null, new BuildOptions { Occlusion = occlusion }))
            {
                Tests.Check(store.Info.OcclusionLights == 1, "the store keeps one occlusion channel");
                var sh = new SphericalHarmonicsL2[points.Length];
                var visible = new Vector4[points.Length];
                store.InterpolateOcclusion(points, null, sh, visible, 2);
                var hints = new int[points.Length];
                for (int i = 0; i < hints.Length; ++i) hints[i] = -1;
                var spanSh = new SphericalHarmonicsL2[points.Length];
                var spanVisible = new Vector4[points.Length];
#if TETPROBE_SPAN
                store.InterpolateOcclusion(new ReadOnlySpan<Vector3>(points), new Span<int>(hints), new Span<SphericalHarmonicsL2>(spanSh),
                                           new Span<Vector4>(spanVisible));
#else
                store.InterpolateOcclusion(points, hints, spanSh, spanVisible);
#endif
                bool blended = true, same = true;
                double worst = 0;
                var probeIndices = new uint[4];
                var weights = new float[4];
                for (int i = 0; i < points.Length; ++i)
                {
                    int hint = -1, weightHint = -1;
                    SphericalHarmonicsL2 one;
                    Vector4 single;
                    store.InterpolateOcclusion(points[i], ref hint, out one, out single);
                    store.Weights(points[i], ref weightHint, probeIndices, weights);
                    double expected = 0;
                    for (int k = 0; k < 4; ++k) expected += weights[k] * occlusion.Probes[probeIndices[k]].Light0 / 255.0;
                    expected = Math.Min(Math.Max(expected, 0), 1);
                    worst = Math.Max(worst, Math.Abs(single.x - expected));
                    blended &= single.y == 1 && single.z == 1 && single.w == 1;
                    same &= single.Equals(visible[i]) && single.Equals(spanVisible[i]) && one == sh[i] && hint == hints[i];
                }
                Tests.Check(worst <= 1e-6, "occlusion is the probes' visibility blended with the query's weights (worst " + worst + ")");
                Tests.Check(blended, "channels without a mixed light read 1");
                Tests.Check(same, "single, array batch and span batch agree, hints updated");
                Tests.Throws<ArgumentException>(() => store.InterpolateOcclusion(points, null, sh, new Vector4[3]), "short occlusion array");
            }
            using (ProbeStore plain = ProbeStore.Build(probes, null))
            {
                int hint = -1;
                SphericalHarmonicsL2 sh;
                Vector4 visible;
                plain.InterpolateOcclusion(new Vector3(0.5f, 0, 0), ref hint, out sh, out visible);
                Tests.Check(visible.Equals(new Vector4(1, 1, 1, 1)) && plain.Info.OcclusionLights == 0,
                            "a store without occlusion sees every light");
            }
            Tests.Throws<ArgumentException>(() => ProbeStore.Build(probes, null, new BuildOptions {
                                                Occlusion = new OcclusionProbes(new ProbeOcclusion[3], 1) }), "occlusion of another length");

            // Leak control: points beside the wall (x in [0.45, 0.9], below its top) blend probes behind it (x < 0.37)
            // much less with the scene than without.
            var beside = new Vector3[400];
            for (int i = 0; i < beside.Length; ++i)
                beside[i] = new Vector3(0.45f + 0.45f * (float)random.NextDouble(), -2 + 2 * (float)random.NextDouble(),
                                        -2 + 4 * (float)random.NextDouble());
            var behindWeight = new double[2];
            int run = 0;
            foreach (BuildOptions options in new[] { new BuildOptions(), new BuildOptions { Scene = wall } })
            {
                using (ProbeStore store = ProbeStore.Build(probes, null, options))
                {
                    var indices = new uint[4 * beside.Length];
                    var weights = new float[4 * beside.Length];
                    store.Weights(beside, null, indices, weights);
                    double sum = 0;
                    for (int k = 0; k < indices.Length; ++k) sum += probes[indices[k]].x < 0.37f ? weights[k] : 0;
                    behindWeight[run] = sum / beside.Length;
                    Tests.Check((store.Info.LeakEdges > 20) == (options.Scene != null), "leak edges only with a scene (" + store.Info.LeakEdges + ")");
                }
                ++run;
            }
            Tests.Check(behindWeight[0] > 0.2 && behindWeight[1] < 0.1 * behindWeight[0],
                        "leak control weighs down the probes behind the wall (" + behindWeight[0] + " -> " + behindWeight[1] + ")");
        }
        using (var scene = new Scene())
        {
            for (int i = 0; i < 4; ++i) scene.AddLight(Light.Point(new Vector3(i, 0, 0), new Vector3(1, 1, 1), 1, float.PositiveInfinity, LightMode.Mixed));
            Tests.Throws<TetProbeException>(() => scene.AddLight(Light.Point(new Vector3(5, 0, 0), new Vector3(1, 1, 1), 1,
                                                                             float.PositiveInfinity, LightMode.Mixed)),
                                            "a fifth mixed light", e => e.Status == TetProbeStatus.Scene && e.Message.Contains("fifth mixed light"));
            Tests.Check(Baker.BakeOcclusion(scene, new[] { new Vector3(0.5f, 1, 0) }).MixedLights == 4, "four mixed lights");
        }
    }

    /// <summary>Reports synchronously on the calling thread.</summary>
    sealed class Recorder : IProgress<float>
    {
        readonly List<float> into;
        readonly Action<float> then;
        public Recorder(List<float> into, Action<float> then = null) { this.into = into; this.then = then; }
        public void Report(float value)
        {
            into.Add(value);
            if (then != null) then(value);
        }
    }
}
