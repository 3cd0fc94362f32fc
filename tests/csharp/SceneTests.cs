// Scenes and the bake from C#: meshes (one material and per triangle), lights of each type, the sky (colour and
// SH), probes, the effects plan, the bake against analytic answers, progress, cancellation, errors.
using System;
using System.Collections.Generic;
using System.IO;
using System.Threading;
using TetProbe;

static class SceneTests
{
    /// <summary>Reports synchronously on the calling thread (System.Progress would post to a context).</summary>
    sealed class Recorder : IProgress<float>
    {
        public readonly List<float> Fractions = new List<float>();
        public Action<float> OnReport;
        public void Report(float value)
        {
            Fractions.Add(value);
            if (OnReport != null) OnReport(value);
        }
    }

    static readonly Vector3[] Square = { new Vector3(-5, -1, -5), new Vector3(5, -1, -5), new Vector3(5, -1, 5), new Vector3(-5, -1, 5) };
    static readonly int[] SquareIndices = { 0, 2, 1, 0, 3, 2 };

    static double MaxDifference(SphericalHarmonicsL2 a, SphericalHarmonicsL2 b)
    {
        double worst = 0;
        for (int c = 0; c < 3; ++c)
            for (int i = 0; i < 9; ++i) worst = Math.Max(worst, Math.Abs(a[c, i] - b[c, i]));
        return worst;
    }

    public static void Run(string scenes)
    {
        var probes = new[] { new Vector3(0, 0, 0), new Vector3(1, 2, 3), new Vector3(-2, 0.5f, 1) };

        // A constant sky and nothing else: every probe holds exactly that ambient radiance (any direction sees the sky).
        using (var sky = new Scene())
        {
            sky.SetSky(new Vector3(0.5f, 1, 2));
            var options = new BakeOptions { Rays = 64, Bounces = 2 };
            EffectsPlan plan = Baker.Plan(sky, probes, options);
            Tests.Check(plan.Sky && plan.Lights == 0 && plan.Meshes == 0 && plan.Summary.Contains("sky"),
                        "plan of a sky-only scene (" + plan + ")");
            SphericalHarmonicsL2[] baked = Baker.Bake(sky, probes, options);
            var ambient = new SphericalHarmonicsL2();
            ambient.AddAmbientLight(0.5f, 1, 2);
            double worst = 0;
            foreach (SphericalHarmonicsL2 sh in baked) worst = Math.Max(worst, MaxDifference(sh, ambient));
            Tests.Check(baked.Length == 3 && worst < 0.02, "constant sky bakes to the ambient SH (worst " + worst + ")");

            var skySh = new SphericalHarmonicsL2();
            skySh.AddAmbientLight(0.25f, 0.25f, 0.25f);
            sky.SetSky(skySh);
            var half = new SphericalHarmonicsL2();
            half.AddAmbientLight(0.25f, 0.25f, 0.25f);
            Tests.Check(MaxDifference(Baker.Bake(sky, probes, options)[1], half) < 0.01, "SH sky bakes to itself");
        }

        // A sun over an open floor: direct light only is the directional delta; the floor below occludes nothing above.
        using (var scene = new Scene())
        {
            int mesh = scene.AddMesh(Square, SquareIndices, Material.Diffuse(new Vector3(0.5f, 0.5f, 0.5f)));
            int sun = scene.AddLight(TetProbe.Light.Directional(new Vector3(0, -1, 0), new Vector3(1, 0.5f, 0.25f), 2));
            Tests.Check(mesh == 0 && sun == 0, "first mesh and light ids are 0");
            var direct = new BakeOptions { Rays = 32, Bounces = 0 };
            EffectsPlan plan = Baker.Plan(scene, probes, direct);
            Tests.Check(plan.Lights == 1 && plan.DirectLights == 1 && plan.Meshes == 1 && !plan.Sky && plan.Bounces == 0,
                        "plan of a sun over a floor (" + plan.Summary + ")");
            SphericalHarmonicsL2[] baked = Baker.Bake(scene, probes, direct);
            var expected = new SphericalHarmonicsL2();
            expected.AddDirectionalLight(new Vector3(0, -1, 0), 2, 1, 0.5f);
            Tests.Check(MaxDifference(baked[0], expected) < 1e-4, "direct sun bakes to the directional delta (" +
                        MaxDifference(baked[0], expected) + ")");
            var bounced = Baker.Bake(scene, probes, new BakeOptions { Rays = 64, Bounces = 1 });
            Vector3 fromBelow = bounced[0].EvaluateIrradiance(new Vector3(0, -1, 0));
            Tests.Check(fromBelow.x > 0.5 * 0.5 * 2 * 0.5 && fromBelow.x < 0.5 * 2 * 1.5, "one bounce lights the probe from the floor (" +
                        fromBelow + ")");

            var recorder = new Recorder();
            Baker.Bake(scene, probes, direct, recorder);
            Tests.Check(recorder.Fractions.Count > 0 && recorder.Fractions[recorder.Fractions.Count - 1] == 1.0f,
                        "progress reaches 1 (" + recorder.Fractions.Count + " reports)");
            bool rising = true;
            for (int i = 1; i < recorder.Fractions.Count; ++i) rising &= recorder.Fractions[i] >= recorder.Fractions[i - 1];
            Tests.Check(rising, "progress never goes back");

            using (var source = new CancellationTokenSource())
            {
                var canceller = new Recorder { OnReport = f => source.Cancel() };
                var many = new Vector3[2000];
                for (int i = 0; i < many.Length; ++i) many[i] = new Vector3(i * 0.001f, 1, 0);
                Tests.Throws<OperationCanceledException>(() => Baker.Bake(scene, many, new BakeOptions { Rays = 256, Bounces = 2 },
                                                                           canceller, source.Token),
                                                         "cancelled from the progress callback", e => e.CancellationToken == source.Token);
                Tests.Throws<OperationCanceledException>(() => Baker.Bake(scene, probes, direct, null, source.Token),
                                                         "a cancelled token stops the bake before it starts");
            }
            var failing = new Recorder { OnReport = f => { throw new InvalidDataException("from the progress"); } };
            Tests.Throws<InvalidDataException>(() => Baker.Bake(scene, probes, direct, failing),
                                               "an exception in progress reaches the caller, not the native frames");

            scene.Probes = probes;
            Vector3[] back = scene.Probes;
            Tests.Check(back.Length == 3 && back[1].Equals(probes[1]) && back[2].Equals(probes[2]), "Probes set and get");

            // Per-triangle materials: one emissive triangle makes the mesh emissive.
            var materials = new[] { Material.Diffuse(new Vector3(0.2f, 0.2f, 0.2f)),
                                    Material.Diffuse(new Vector3(0, 0, 0), new Vector3(4, 4, 4)) };
            int second = scene.AddMesh(Square, SquareIndices, materials, new[] { 0, 1 });
            Tests.Check(second == 1 && Baker.Plan(scene, probes).EmissiveMeshes == 1, "per-triangle materials, one emissive mesh");
            scene.AddLight(TetProbe.Light.Point(new Vector3(0, 3, 0), new Vector3(1, 1, 1), 5, 2.0f, LightMode.Realtime));
            scene.AddLight(TetProbe.Light.Spot(new Vector3(0, 3, 0), new Vector3(0, -1, 0), new Vector3(1, 1, 1), 5, 100, 20, 40));
            EffectsPlan three = Baker.Plan(scene, probes);
            Tests.Check(three.Lights == 3 && three.RealtimeLights == 1, "point (realtime) and spot lights counted (" + three + ")");

            Tests.Throws<ArgumentException>(() => scene.AddMesh(Square, new[] { 0, 1 }, Material.Default), "indices not 3 per triangle");
            Tests.Throws<ArgumentOutOfRangeException>(() => scene.AddMesh(Square, new[] { 0, -1, 2 }, Material.Default), "negative index");
            Tests.Throws<ArgumentException>(() => scene.AddMesh(Square, SquareIndices, materials, new[] { 0 }),
                                            "triangleMaterials of the wrong length");
            Tests.Throws<TetProbeException>(() => scene.AddMesh(Square, new[] { 0, 1, 9 }, Material.Default), "index beyond the vertices",
                                            e => e.Status == TetProbeStatus.Scene && e.Message.Contains("index 9"));
            Tests.Throws<TetProbeException>(() => scene.AddMesh(Square, SquareIndices, materials, new[] { 0, 2 }),
                                            "material index beyond the materials", e => e.Status == TetProbeStatus.Scene);
            var bad = Material.Default;
            bad.Albedo = new Vector3(2, 0, 0);
            Tests.Throws<TetProbeException>(() => scene.AddMesh(Square, SquareIndices, bad), "albedo above 1");
            Tests.Throws<TetProbeException>(() => scene.AddLight(TetProbe.Light.Point(new Vector3(float.NaN, 0, 0), new Vector3(1, 1, 1))),
                                            "NaN light position");
            Tests.Throws<TetProbeException>(() => scene.AddLight(TetProbe.Light.Point(new Vector3(0, 3, 0), new Vector3(1, 1, 1), 1,
                                                                                      float.PositiveInfinity, LightMode.Baked, true, -1)),
                                            "negative near distance", e => e.Status == TetProbeStatus.Scene && e.Message.Contains("near distance"));
            Tests.Throws<ArgumentOutOfRangeException>(() => Baker.Bake(scene, probes, new BakeOptions { Rays = -1 }), "negative rays");
            Tests.Throws<ArgumentNullException>(() => Baker.Bake(null, probes), "null scene");
        }

        // A default(Material) still crosses with its struct_size set (black, one-sided).
        using (var scene = new Scene())
            Tests.Check(scene.AddMesh(Square, SquareIndices, default(Material)) == 0, "default(Material) is accepted");

        using (Scene loaded = Scene.Load(Path.Combine(scenes, "cornell_box.json")))
        {
            Vector3[] listed = loaded.Probes;
            EffectsPlan plan = Baker.Plan(loaded, listed);
            Tests.Check(listed.Length > 0 && plan.Meshes > 0 && plan.EmissiveMeshes > 0, "cornell_box.json loads (" + listed.Length +
                        " probes; " + plan + ")");
        }
        Tests.Throws<TetProbeException>(() => Scene.Load(Path.Combine(scenes, "no_such_scené.json")), "missing scene file",
                                        e => e.Message.Contains("no_such_scené.json"));

        // Scene files through Assimp: the glTF two rooms, its up and unit as options, the notes, bad files.
        using (Scene rooms = Scene.Load(Path.Combine(scenes, "two_rooms.gltf")))
        {
            Tests.Check(rooms.Up == UpAxis.PosY && rooms.Notes.Length == 0 && rooms.Probes.Length == 0,
                        "two_rooms.gltf: y-up, no notes, no probes (" + rooms.Up + ", " + rooms.Notes.Length + " notes)");
            EffectsPlan plan = Baker.Plan(rooms, new[] { new Vector3(2, 1, 2) });
            Tests.Check(plan.Meshes == 2 && plan.Lights == 2, "two_rooms.gltf: the rooms and the table, the sun and the lamp (" + plan + ")");
            rooms.Up = UpAxis.NegZ;
            Tests.Check(rooms.Up == UpAxis.NegZ, "Up can be set");
            Tests.Throws<TetProbeException>(() => rooms.Up = UpAxis.File, "Up = File is refused", e => e.Status == TetProbeStatus.InvalidArgument);
        }
        var zUp = new SceneLoadOptions { Up = UpAxis.PosZ, Scale = 2 };
        Tests.Check(new SceneLoadOptions().Scale == 0 && new SceneLoadOptions().Up == UpAxis.File, "SceneLoadOptions' defaults");
        using (Scene rooms = Scene.Load(Path.Combine(scenes, "two_rooms.gltf"), zUp))
            Tests.Check(rooms.Up == UpAxis.PosZ, "the options' up wins over the file's");
        Tests.Throws<ArgumentOutOfRangeException>(() => Scene.Load(Path.Combine(scenes, "two_rooms.gltf"), new SceneLoadOptions { Scale = -1 }),
                                                  "a negative scale");
        string scratch = Path.Combine(Path.GetTempPath(), "tetprobe_csharp_" + System.Diagnostics.Process.GetCurrentProcess().Id);
        Directory.CreateDirectory(scratch);
        try
        {
            string bare = Path.Combine(scratch, "bare.obj");
            File.WriteAllText(bare, "v 0 0 0\nv 1 0 0\nv 0 0 1\nf 1 3 2\n");
            using (Scene loaded = Scene.Load(bare))
                Tests.Check(loaded.Notes.Length == 1 && loaded.Notes[0].Contains("bare.obj") && loaded.Notes[0].Contains("default"),
                            "an OBJ without materials notes the default material (" + string.Join(" | ", loaded.Notes) + ")");
            string laser = Path.Combine(scratch, "laser.gltf");
            File.WriteAllText(laser, "{\"asset\": {\"version\": \"2.0\"}, \"extensions\": {\"KHR_lights_punctual\": " +
                                     "{\"lights\": [{\"type\": \"laser\"}]}}}");
            Tests.Throws<TetProbeException>(() => Scene.Load(laser), "a glTF light of an unknown type",
                                            e => e.Status == TetProbeStatus.Scene && e.Message.Contains("laser.gltf") && e.Message.Contains("\"laser\""));
        }
        finally
        {
            Directory.Delete(scratch, true);
        }
        using (var built = new Scene())
            Tests.Check(built.Notes.Length == 0 && built.Up == UpAxis.PosY, "a scene built in code: no notes, +y up");

        var disposed = new Scene();
        disposed.Dispose();
        disposed.Dispose();
        Tests.Throws<ObjectDisposedException>(() => disposed.SetSky(new Vector3(1, 1, 1)), "scene used after Dispose");
        Tests.Throws<ObjectDisposedException>(() => Baker.Plan(disposed, probes), "plan of a disposed scene");

        // Probes copies out of memory the scene owns: a Dispose between tp_scene_probes and the copy (as from another thread)
        // must wait for the copy, else the allocator reuses the freed positions and the copy differs.
        var racingProbes = new Vector3[64];
        for (int i = 0; i < racingProbes.Length; ++i) racingProbes[i] = new Vector3(i, 0.5f * i, -i);
        var racing = new Scene();
        racing.Probes = racingProbes;
        try
        {
            NativeProxy.BeforeBorrowedCopy = handle => racing.Dispose();
            Vector3[] copied = racing.Probes;
            bool same = copied.Length == racingProbes.Length;
            for (int i = 0; same && i < racingProbes.Length; ++i) same = copied[i].Equals(racingProbes[i]);
            Tests.Check(same, "a Dispose between tp_scene_probes and the copy waits for the copy (the same: " + same + ")");
        }
        finally
        {
            NativeProxy.BeforeBorrowedCopy = null;
        }
        Tests.Throws<ObjectDisposedException>(() => { Vector3[] unused = racing.Probes; }, "the scene is released once the copy is done");
    }
}
