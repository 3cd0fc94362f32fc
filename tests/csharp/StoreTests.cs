// ProbeStore additions: BuildOptions, build progress and cancellation, Locate's diagnostics, batches on spans,
// UTF-8 paths and messages.
using System;
using System.IO;
using System.Threading;
using TetProbe;

static class StoreTests
{
    static Vector3[] Grid(int n)
    {
        var points = new Vector3[n * n * n];
        int k = 0;
        for (int x = 0; x < n; ++x)
            for (int y = 0; y < n; ++y)
                for (int z = 0; z < n; ++z) points[k++] = new Vector3(x + 0.01f * ((y * 7 + z * 3) % 5), y, z);
        return points;
    }

    static SphericalHarmonicsL2[] Lit(Vector3[] positions)
    {
        var sh = new SphericalHarmonicsL2[positions.Length];
        for (int i = 0; i < sh.Length; ++i) sh[i].AddAmbientLight(positions[i].x, positions[i].y, 1 + positions[i].z);
        return sh;
    }

    public static void Run(string scratch)
    {
        Vector3[] positions = Grid(5);
        SphericalHarmonicsL2[] sh = Lit(positions);

        var defaults = new BuildOptions();
        Tests.Check(defaults.Extrapolate && !defaults.Compact && defaults.MergeTolerance == 1e-6, "BuildOptions defaults from the library");
        using (ProbeStore compact = ProbeStore.Build(positions, sh, new BuildOptions { Compact = true, Index32 = true }))
            Tests.Check(compact.Info.Compact && compact.Info.IndexBits == 32 && compact.Info.Extrapolation, "compact, 32-bit indices");
        using (ProbeStore closed = ProbeStore.Build(positions, sh, new BuildOptions { Extrapolate = false }))
            Tests.Check(!closed.Info.Extrapolation && closed.Info.OuterCells == 0, "no extrapolation from BuildOptions");
        using (ProbeStore merged = ProbeStore.Build(new[] { new Vector3(0, 0, 0), new Vector3(1, 0, 0), new Vector3(0.4f, 0, 0) }, null,
                                                    new BuildOptions { MergeTolerance = 0.5 }))
            Tests.Check(merged.Info.MergedProbes == 1, "MergeTolerance reaches the build (" + merged.Info.MergedProbes + " merged)");

        float last = -1;
        int reports = 0;
        var progress = new Reporter(f => { last = f; ++reports; });
        using (ProbeStore.Build(positions, sh, null, progress)) { }
        Tests.Check(reports > 0 && last == 1.0f, "build progress reaches 1 (" + reports + " reports)");
        using (var source = new CancellationTokenSource())
        {
            Tests.Throws<OperationCanceledException>(() => ProbeStore.Build(positions, sh, null, new Reporter(f => source.Cancel()),
                                                                              source.Token), "build cancelled from progress");
        }

        using (ProbeStore store = ProbeStore.Build(positions, sh))
        {
            int hint = -1;
            ProbeLocation inside = store.Locate(new Vector3(1.5f, 1.5f, 1.5f), ref hint);
            Tests.Check(!inside.Outer && !inside.Fallback && inside.T == 0 && hint == inside.Cell && inside.Probes.Length == 4,
                        "locate inside: inner cell, no fallback, t 0");
            int far = -1;
            ProbeLocation outside = store.Locate(new Vector3(9, 2, 2), ref far);
            Tests.Check(outside.Outer && outside.T > 0, "locate outside: outer cell, t " + outside.T);
            float sum = 0;
            foreach (float w in inside.Weights) sum += w;
            Tests.Check(Math.Abs(sum - 1) < 1e-6, "located weights sum to 1");

#if TETPROBE_SPAN
            var points = new Vector3[100];
            for (int i = 0; i < points.Length; ++i) points[i] = new Vector3(0.04f * i, 0.03f * i, 4 - 0.035f * i);
            var arrayResults = new SphericalHarmonicsL2[points.Length];
            var arrayHints = new int[points.Length];
            for (int i = 0; i < arrayHints.Length; ++i) arrayHints[i] = -1;
            var spanHints = (int[])arrayHints.Clone();
            store.Interpolate(points, arrayHints, arrayResults);
            var spanResults = new SphericalHarmonicsL2[points.Length + 10];
            store.Interpolate(new ReadOnlySpan<Vector3>(points), new Span<int>(spanHints), new Span<SphericalHarmonicsL2>(spanResults, 10, 100));
            bool same = true;
            for (int i = 0; i < points.Length; ++i) same &= spanResults[10 + i] == arrayResults[i] && spanHints[i] == arrayHints[i];
            Tests.Check(same && spanResults[0] == new SphericalHarmonicsL2(), "span batch into a slice equals the array batch, hints too");
            var noHints = new SphericalHarmonicsL2[points.Length];
            store.Interpolate(points.AsSpan(), Span<int>.Empty, noHints.AsSpan(), 2);
            Tests.Check(noHints[42] == arrayResults[42], "span batch without hints");
            var probes = new uint[4 * points.Length];
            var weights = new float[4 * points.Length];
            var arrayProbes = new uint[4 * points.Length];
            var arrayWeights = new float[4 * points.Length];
            store.Weights(points.AsSpan(), Span<int>.Empty, probes.AsSpan(), weights.AsSpan(), 1, true);
            store.Weights(points, null, arrayProbes, arrayWeights, 1, true);
            bool sameWeights = true;
            for (int i = 0; i < probes.Length; ++i) sameWeights &= probes[i] == arrayProbes[i] && weights[i] == arrayWeights[i];
            Tests.Check(sameWeights, "span Weights equal the array Weights");
            store.Interpolate(ReadOnlySpan<Vector3>.Empty, Span<int>.Empty, Span<SphericalHarmonicsL2>.Empty);
            Tests.Throws<ArgumentException>(() => store.Interpolate(points.AsSpan(), Span<int>.Empty, noHints.AsSpan(0, 99)),
                                            "span results too short");
            Tests.Throws<ArgumentException>(() => store.Interpolate(points.AsSpan(), new int[5].AsSpan(), noHints.AsSpan()),
                                            "span hints too short");
            Tests.Throws<ArgumentException>(() => store.Weights(points.AsSpan(), Span<int>.Empty, probes.AsSpan(0, 8), weights.AsSpan()),
                                            "span probes too short");
#endif

            // Paths and messages are UTF-8 both ways.
            string path = Path.Combine(scratch, "störe_é.tpb");
            store.Save(path);
            Tests.Check(File.Exists(path), "saved under a non-ASCII name");
            using (ProbeStore again = ProbeStore.Load(path))
                Tests.Check(again.Info.Bytes == store.Info.Bytes, "loaded from a non-ASCII name");
            Tests.Throws<TetProbeException>(() => ProbeStore.Load(Path.Combine(scratch, "störe_missing_é.tpb")),
                                            "the message names a non-ASCII path intact",
                                            e => e.Status == TetProbeStatus.IO && e.Message.Contains("störe_missing_é.tpb"));

            // The load cap, and only regular files.
            ulong size = (ulong)new FileInfo(path).Length;
            Tests.Throws<TetProbeException>(() => ProbeStore.Load(path, size - 1), "a file above the load cap is refused",
                                            e => e.Status == TetProbeStatus.IO && e.Message.Contains("above the load cap"));
            using (ProbeStore again = ProbeStore.Load(path, size))
                Tests.Check((ulong)again.Info.Bytes == size, "a file at the load cap loads");
            Tests.Throws<TetProbeException>(() => ProbeStore.Load(scratch), "a directory is refused",
                                            e => e.Status == TetProbeStatus.IO && e.Message.Contains("not a regular file"));
        }
        DisposedDuringCopy(positions, sh);
    }

    /// <summary>Save() copies out of memory the store owns: a Dispose that lands between tp_store_blob and the copy (as from
    /// another thread) must wait for the copy. Were the store freed there, the allocator would reuse the blob's first bytes
    /// and the copy would differ from the blob (or the process would fault).</summary>
    static void DisposedDuringCopy(Vector3[] positions, SphericalHarmonicsL2[] sh)
    {
        var store = ProbeStore.Build(positions, sh);
        byte[] expected = store.Save();
        try
        {
            NativeProxy.BeforeBorrowedCopy = handle => store.Dispose();
            byte[] copied = store.Save();
            bool same = copied.Length == expected.Length;
            for (int i = 0; same && i < copied.Length; ++i) same = copied[i] == expected[i];
            Tests.Check(same, "a Dispose between tp_store_blob and the copy waits for the copy (" + copied.Length +
                        " bytes, the same: " + same + ")");
        }
        finally
        {
            NativeProxy.BeforeBorrowedCopy = null;
        }
        Tests.Throws<ObjectDisposedException>(() => store.Save(), "the store is released once the copy is done");
    }

    sealed class Reporter : IProgress<float>
    {
        readonly Action<float> report;
        public Reporter(Action<float> report) { this.report = report; }
        public void Report(float value) { report(value); }
    }
}
