// The binding compiled with TETPROBE_RUNTIME loads libtetprobe_runtime (stores and queries, no TetGen, no Embree).
// Compiled twice: without the define it builds a store with the full library and writes the blob and the expected
// answers; with it, it checks the plugin name, loads that blob and answers the same, the whole header check passes,
// and every build, scene and bake call is refused with TetProbeStatus.Unsupported and a message saying why.
using System;
using System.IO;
using TetProbe;

static class RuntimeTests
{
    static readonly Vector3[] Queries = { new Vector3(0.1f, 0.2f, 0.3f), new Vector3(-0.7f, 0.4f, 0.9f), new Vector3(3, 0, 0) };

    static int Main(string[] args)
    {
        string scratch = args[0];
        Directory.CreateDirectory(scratch);
        string blobPath = Path.Combine(scratch, "runtime_store.tpb"), answersPath = Path.Combine(scratch, "runtime_answers.bin");
#if !TETPROBE_RUNTIME
        var random = new Random(7);
        var positions = new Vector3[40];
        var sh = new SphericalHarmonicsL2[positions.Length];
        for (int i = 0; i < positions.Length; ++i)
        {
            positions[i] = new Vector3((float)random.NextDouble() * 2 - 1, (float)random.NextDouble() * 2 - 1, (float)random.NextDouble() * 2 - 1);
            sh[i].AddAmbientLight(positions[i].x + 1, positions[i].y + 1, positions[i].z + 1);
        }
        using (ProbeStore store = ProbeStore.Build(positions, sh))
        using (var answers = new BinaryWriter(File.Create(answersPath)))
        {
            store.Save(blobPath);
            foreach (Vector3 q in Queries)
            {
                int hint = -1;
                SphericalHarmonicsL2 value;
                store.Interpolate(q, ref hint, out value);
                for (int c = 0; c < 3; ++c)
                    for (int k = 0; k < 9; ++k) answers.Write(value[c, k]);
            }
        }
        Console.WriteLine("wrote " + blobPath);
        return 0;
#else
        Tests.Check(NativeMethods.Library == "tetprobe_runtime", "TETPROBE_RUNTIME loads tetprobe_runtime");
        using (ProbeStore store = ProbeStore.Load(blobPath))
        using (var answers = new BinaryReader(File.OpenRead(answersPath)))
        {
            bool same = true;
            foreach (Vector3 q in Queries)
            {
                int hint = -1;
                SphericalHarmonicsL2 value;
                store.Interpolate(q, ref hint, out value);
                for (int c = 0; c < 3; ++c)
                    for (int k = 0; k < 9; ++k) same &= answers.ReadSingle() == value[c, k];
            }
            Tests.Check(same, "the run-time library answers a blob of the full library with the same bytes");
            var batch = new SphericalHarmonicsL2[Queries.Length];
            store.Interpolate(Queries, null, batch, 1);
            Tests.Check(batch[2] != new SphericalHarmonicsL2(), "batch queries in the run-time library");
        }
        Func<TetProbeException, bool> unsupported = e => e.Status == TetProbeStatus.Unsupported && e.Message.Contains("run-time library");
        Tests.Throws<TetProbeException>(() => ProbeStore.Build(Queries, null), "Build refused", unsupported);
        Tests.Throws<TetProbeException>(() => new Scene(), "Scene refused", unsupported);
        Tests.Throws<TetProbeException>(() => Scene.Load("any.json"), "Scene.Load refused", unsupported);
        var sky = new SphericalHarmonicsL2();
        sky.AddAmbientLight(1, 1, 1);
        Tests.Check(sky.EvaluateIrradiance(new Vector3(0, 0, 1)).x > 3.14f, "SH helpers in the run-time library");
        HeaderCheck.Run(args[1]);
        return Tests.Summary();
#endif
    }
}
