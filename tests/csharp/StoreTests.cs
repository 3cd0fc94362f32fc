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

        // Format 5: each SH encoding, with and without quantised positions, reaches the build and the info.
        Tests.Check(defaults.ShEncoding == ShEncoding.Half && !defaults.QuantizePositions, "half SH, float positions by default");
        foreach (ShEncoding encoding in new[] { ShEncoding.Half, ShEncoding.Unorm8, ShEncoding.HalfL1, ShEncoding.Unorm8L1 })
            foreach (bool quantize in new[] { false, true })
                using (ProbeStore small = ProbeStore.Build(positions, sh, new BuildOptions { ShEncoding = encoding, QuantizePositions = quantize,
                                                                                              Compact = true }))
                {
                    ProbeStoreInfo info = small.Info;
                    bool l1 = encoding == ShEncoding.HalfL1 || encoding == ShEncoding.Unorm8L1;
                    SphericalHarmonicsL2 stored = small.ProbeSh(7);
                    Tests.Check(info.FormatVersion == 6 && info.ShEncoding == encoding && info.QuantizedPositions == quantize &&
                                info.Layout == StoreLayout.Compact && info.SectionBytes.Total == info.Bytes &&
                                info.SectionBytes.Positions == positions.Length * (quantize ? 6 : 12) && info.HullProbes > 0 &&
                                (quantize ? info.PositionStep.x > 0 : info.PositionStep.x == 0) &&
                                Math.Abs(stored[0, 0] - sh[7][0, 0]) <= 1e-3f * Math.Abs(sh[7][0, 0]) &&
                                (!l1 || stored[1, 6] == 0),
                                encoding + (quantize ? " with quantised positions" : "") + ": " + info.Bytes + " bytes, " +
                                info.SectionBytes.Sh + " of SH");
                }

        // The rebuilt layout: no cells stored, the compact layout's answers exactly.
        Tests.Check(defaults.Layout == StoreLayout.Fast, "fast layout by default");
        using (ProbeStore compact = ProbeStore.Build(positions, sh, new BuildOptions { Layout = StoreLayout.Compact }))
        using (ProbeStore rebuilt = ProbeStore.Build(positions, sh, new BuildOptions { Layout = StoreLayout.Rebuilt }))
        {
            bool same = true;
            for (int i = 0; i < 40; ++i)
            {
                var p = new Vector3(0.1f * i - 0.5f, 0.07f * i, 3 - 0.09f * i);
                int ha = -1, hb = -1;
                ProbeLocation a = compact.Locate(p, ref ha), b = rebuilt.Locate(p, ref hb);
                same &= ha == hb;
                for (int k = 0; k < 4; ++k) same &= a.Probes[k] == b.Probes[k] && a.Weights[k] == b.Weights[k];
            }
            Tests.Check(rebuilt.Info.Layout == StoreLayout.Rebuilt && rebuilt.Info.SectionBytes.Cells == 0 &&
                        rebuilt.Info.Cells == compact.Info.Cells && rebuilt.Info.Bytes < compact.Info.Bytes && same,
                        "rebuilt layout: " + rebuilt.Info.Bytes + " bytes against compact's " + compact.Info.Bytes + ", same answers");
        }
        Tests.Throws<TetProbeException>(() => ProbeStore.Build(positions, sh, new BuildOptions { Layout = StoreLayout.Rebuilt, Compact = true }),
                                        "Compact with the rebuilt layout is refused", e => e.Status == TetProbeStatus.InvalidArgument);

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

            // A probe volume: each point the single query replayed in the documented walk with the carried hint.
            {
                int nx = 5, ny = 4, nz = 3;
                var origin = new Vector3(-0.7f, -0.3f, 0.2f);
                var cell = new Vector3(1.1f, 1.3f, 1.7f);
                var volume = new float[27 * nx * ny * nz];
                int volumeHint = -1, replayHint = -1, firstCell = -2, row = 0;
                store.SampleVolume(origin, cell, nx, ny, nz, VolumeFormat.ShL2, volume, ref volumeHint);
                bool equal = true;
                for (int z = 0; z < nz; ++z)
                    for (int j = 0; j < ny; ++j, ++row)
                    {
                        int y = z % 2 == 1 ? ny - 1 - j : j;
                        for (int i = 0; i < nx; ++i)
                        {
                            int x = row % 2 == 1 ? nx - 1 - i : i;
                            var p = new Vector3((float)((double)origin.x + x * (double)cell.x),
                                                (float)((double)origin.y + y * (double)cell.y),
                                                (float)((double)origin.z + z * (double)cell.z));
                            SphericalHarmonicsL2 single;
                            store.Interpolate(p, ref replayHint, out single);
                            if (row == 0 && i == 0) firstCell = replayHint;
                            int at = 27 * (x + nx * (y + ny * z));
                            for (int c = 0; c < 3; ++c)
                                for (int k = 0; k < 9; ++k) equal &= volume[at + 9 * c + k] == single[c, k];
                        }
                    }
                Tests.Check(equal && volumeHint == firstCell, "SampleVolume equals the single queries of its walk");
                var atlas = new float[4 * 4 * nx * ny * nz];
                for (int i = 0; i < atlas.Length; ++i) atlas[i] = -3;
                int atlasHint = -1;
                store.SampleVolume(origin, cell, nx, ny, nz, VolumeFormat.UnityL1, atlas, ref atlasHint, 16, 64 * nx,
                                   64 * nx * ny, 16 * nx);
                bool occlusionUntouched = true;
                for (int t = 0; t < atlas.Length / 4; ++t)
                    if (t % (4 * nx) >= 3 * nx) occlusionUntouched &= atlas[4 * t] == -3 && atlas[4 * t + 3] == -3;
                Tests.Check(occlusionUntouched && atlas[3] != -3, "SampleVolume into a proxy volume atlas leaves its fourth block");
                Tests.Throws<ArgumentException>(() => store.SampleVolume(origin, cell, nx, ny, nz, VolumeFormat.ShL2,
                                                                         new float[27 * nx * ny * nz - 1], ref volumeHint),
                                                "SampleVolume refuses an output that is too small");
                Tests.Throws<ArgumentException>(() => store.SampleVolume(origin, cell, nx, ny, nz, VolumeFormat.UnityL1, atlas,
                                                                         ref volumeHint, 16, 64 * nx, 64 * nx * ny + 64, 16 * nx),
                                                "SampleVolume refuses strides that run past the output");
                Tests.Throws<ArgumentOutOfRangeException>(() => store.SampleVolume(origin, cell, 33, ny, nz, VolumeFormat.ShL2,
                                                                                   volume, ref volumeHint),
                                                          "SampleVolume refuses 33 points a side");
                Tests.Throws<TetProbeException>(() => store.SampleVolume(origin, new Vector3(0, 1, 1), 1, 1, 1,
                                                                         VolumeFormat.ShL2, volume, ref volumeHint),
                                                "SampleVolume: the library refuses a zero cell size",
                                                e => e.Status == TetProbeStatus.InvalidArgument && e.Message.Contains("cell_size"));
            }

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
