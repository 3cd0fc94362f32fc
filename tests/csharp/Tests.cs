// Tests of the C# binding against the real library: exactness at probes, a linear field reproduced,
// batch = single, hints, blob and file round trips, errors as TetProbeException, SH layout, the compact
// layout, batch threads and chained hints, format-2 blobs refused.
using System;
using System.IO;
using System.Runtime.InteropServices;
using TetProbe;

static class Tests
{
    static int passed, failed;

    internal static void Check(bool condition, string what)
    {
        if (condition) { ++passed; return; }
        ++failed;
        Console.WriteLine("FAIL: " + what);
    }

    internal static void Throws<E>(Action action, string what, Func<E, bool> accept = null) where E : Exception
    {
        try
        {
            action();
            ++failed;
            Console.WriteLine("FAIL: " + what + " did not throw " + typeof(E).Name);
        }
        catch (E e)
        {
            Check(accept == null || accept(e), what + " (" + e.Message + ")");
        }
        catch (Exception e)
        {
            ++failed;
            Console.WriteLine("FAIL: " + what + " threw " + e.GetType().Name + ": " + e.Message);
        }
    }

    static float Field(int k, Vector3 p)
    {
        return 0.5f + 0.1f * (k % 7) + 0.3f * p.x * ((k % 3) - 1) + 0.2f * p.y * ((k % 5) - 2) - 0.1f * p.z * ((k % 4) - 1.5f);
    }

    static SphericalHarmonicsL2 FieldSh(Vector3 p)
    {
        var sh = new SphericalHarmonicsL2();
        for (int c = 0; c < 3; ++c)
            for (int i = 0; i < 9; ++i) sh[c, i] = Field(c * 9 + i, p);
        return sh;
    }

    static double MaxDifference(SphericalHarmonicsL2 a, SphericalHarmonicsL2 b, bool relative)
    {
        double worst = 0;
        for (int c = 0; c < 3; ++c)
            for (int i = 0; i < 9; ++i)
            {
                double d = Math.Abs(a[c, i] - b[c, i]);
                if (relative) d /= Math.Abs(b[c, i]) + 0.05;
                worst = Math.Max(worst, d);
            }
        return worst;
    }

    static Vector3[] Cloud(int n, Random random)
    {
        var positions = new Vector3[n];
        for (int i = 0; i < n; ++i)
        {
            if (i < 8) positions[i] = new Vector3((i & 1) != 0 ? 1 : -1, (i & 2) != 0 ? 1 : -1, (i & 4) != 0 ? 1 : -1);
            else positions[i] = new Vector3((float)(random.NextDouble() * 2 - 1), (float)(random.NextDouble() * 2 - 1),
                                            (float)(random.NextDouble() * 2 - 1));
        }
        return positions;
    }

    static void Layout()
    {
        Check(Marshal.SizeOf(typeof(SphericalHarmonicsL2)) == 108, "SphericalHarmonicsL2 is 27 floats");
        Check(Marshal.SizeOf(typeof(Vector3)) == 12, "Vector3 is 3 floats");
        var sh = new SphericalHarmonicsL2();
        sh[1, 3] = 7.0f;
        sh[2, 8] = -2.0f;
        Check(sh.shg3 == 7.0f && sh.shb8 == -2.0f, "indexer [rgb, coefficient] is channel-major");
        Check(Marshal.OffsetOf(typeof(SphericalHarmonicsL2), "shg3").ToInt32() == 4 * 12, "shg3 at float 12");
        Throws<IndexOutOfRangeException>(() => { sh[3, 0] = 1; }, "indexer rejects rgb 3");
        Throws<IndexOutOfRangeException>(() => { float v = sh[0, 9]; }, "indexer rejects coefficient 9");
        Check(ProbeStore.LibraryVersion >> 8 == ((NativeProxyVersion.Major << 8) | NativeProxyVersion.Minor),
              "library major.minor matches the binding");
    }

    static void ShHelpers()
    {
        var sh = new SphericalHarmonicsL2();
        sh.AddAmbientLight(0.5f, 1.0f, 2.0f);
        Vector3 radiance = sh.EvaluateRadiance(new Vector3(0, 0, 1));
        Check(Math.Abs(radiance.x - 0.5f) < 1e-5 && Math.Abs(radiance.z - 2.0f) < 1e-5, "ambient radiance");
        Vector3 irradiance = sh.EvaluateIrradiance(new Vector3(1, 0, 0));
        Check(Math.Abs(irradiance.y - Math.PI) < 1e-4, "ambient irradiance is pi L");
        var sun = new SphericalHarmonicsL2();
        sun.AddDirectionalLight(new Vector3(0, 0, -1), 1, 1, 1);
        Check(Math.Abs(sun.EvaluateIrradiance(new Vector3(0, 0, 1)).x - 1.0625) < 1e-4, "directional light, L2 lobe");
        Throws<TetProbeException>(() => sh.EvaluateRadiance(new Vector3(float.NaN, 0, 1)), "NaN direction",
                                  e => e.Status == TetProbeStatus.InvalidArgument);
        foreach (TetProbeStatus status in Enum.GetValues(typeof(TetProbeStatus)))
        {
            // TP_OK, TP_ERROR_INVALID_ARGUMENT for InvalidArgument, ...: the same letters once underscores are dropped.
            string key = status == TetProbeStatus.Ok ? "TPOK" : "TPERROR" + status.ToString().ToUpperInvariant();
            string name = TetProbeException.StatusName(status);
            Check(name.StartsWith("TP_") && name.Replace("_", "") == key, "status name of " + status + " (" + name + ")");
        }
    }

    /// <summary>The SH evaluation options: L2 without a window is the plain evaluation, L1 and Sloan's window are the
    /// rewrites capi/tetprobe.h states (bit for bit), the minimum is a true lower bound reached at its normal, and the
    /// non-negative window leaves no negative irradiance.</summary>
    static void ShOptions()
    {
        var random = new Random(11);
        var sh = new SphericalHarmonicsL2();
        sh.AddAmbientLight(0.003f, 0.003f, 0.003f);  // too little to lift the L2 lobe's ring (about -0.04 of the light)
        sh.AddDirectionalLight(new Vector3(0.48f, -0.6f, 0.64f), 3, 2, 1);
        var normals = new Vector3[400];
        for (int i = 0; i < normals.Length; ++i)
        {
            Vector3 v;
            do v = new Vector3((float)random.NextDouble() * 2 - 1, (float)random.NextDouble() * 2 - 1, (float)random.NextDouble() * 2 - 1);
            while (v.x * v.x + v.y * v.y + v.z * v.z < 0.01 || v.x * v.x + v.y * v.y + v.z * v.z > 1);
            float m = (float)Math.Sqrt(v.x * v.x + v.y * v.y + v.z * v.z);
            normals[i] = new Vector3(v.x / m, v.y / m, v.z / m);
        }

        ShEvalOptions plain = ShEvalOptions.Create();
        Check(plain.Order == ShOrder.L2 && plain.Window == ShWindow.None && plain.WindowStrength == 0, "options default to L2, no window");
        bool same = true;
        foreach (Vector3 n in normals)
        {
            Vector3 a = sh.EvaluateIrradiance(n, plain), b = sh.EvaluateIrradiance(n), d = sh.EvaluateIrradiance(n, default(ShEvalOptions));
            same &= a.Equals(b) && d.Equals(b);
        }
        SphericalHarmonicsL2 unchanged = sh;
        unchanged.ApplyOptions(plain);
        Check(same && unchanged == sh, "L2 without a window: the plain evaluation, bit for bit, and ApplyOptions changes nothing");

        SphericalHarmonicsL2 l1 = sh;
        l1.ApplyOptions(ShEvalOptions.Create(ShOrder.L1));
        bool bands = true;
        for (int c = 0; c < 3; ++c)
            for (int i = 0; i < 9; ++i) bands &= l1[c, i] == (i < 4 ? sh[c, i] : 0);
        bool l1Same = true;
        foreach (Vector3 n in normals) l1Same &= sh.EvaluateIrradiance(n, ShEvalOptions.Create(ShOrder.L1)).Equals(l1.EvaluateIrradiance(n));
        Check(bands && l1Same, "L1: band 2 zeroed, bands 0 and 1 kept; evaluating with L1 = the plain evaluation of the rewrite");

        // Sloan's window at s: band l times 1 / (1 + s (l (l + 1))^2) computed in double, each product rounded once to float.
        const float s = 0.05f;
        SphericalHarmonicsL2 windowed = sh;
        windowed.ApplyOptions(ShEvalOptions.Create(ShOrder.L2, ShWindow.Sloan, s));
        int[] band = { 0, 1, 1, 1, 2, 2, 2, 2, 2 };
        bool exact = true;
        for (int c = 0; c < 3; ++c)
            for (int i = 0; i < 9; ++i)
            {
                double laplacian = band[i] * (band[i] + 1.0);
                double window = band[i] == 0 ? 1.0 : 1.0 / (1.0 + (double)s * laplacian * laplacian);
                exact &= windowed[c, i] == (float)(sh[c, i] * window);
            }
        Check(exact, "Sloan's window scales each band by 1 / (1 + s (l (l + 1))^2)");

        // The directional light's L2 lobe rings negative behind it: the minimum is at most every sample, reached at its normal.
        Vector3 where;
        Vector3 min = sh.MinIrradiance(plain, out where);
        double lowest = double.MaxValue;
        bool bounded = true;
        foreach (Vector3 n in normals)
        {
            Vector3 e = sh.EvaluateIrradiance(n);
            bounded &= e.x >= min.x - 1e-6 && e.y >= min.y - 1e-6 && e.z >= min.z - 1e-6;
            lowest = Math.Min(lowest, Math.Min(e.x, Math.Min(e.y, e.z)));
        }
        Vector3 at = sh.EvaluateIrradiance(where);
        double smallest = Math.Min(min.x, Math.Min(min.y, min.z));
        Check(bounded && smallest < 0 && Math.Abs(Math.Min(at.x, Math.Min(at.y, at.z)) - smallest) < 1e-5 && lowest - smallest < 0.05,
              "MinIrradiance: " + min + " at " + where + ", below every sample (lowest " + lowest + ") and reached there");

        float strength = sh.NonNegativeWindowStrength();
        SphericalHarmonicsL2 lifted = sh;
        lifted.ApplyOptions(ShEvalOptions.Create(ShOrder.L2, ShWindow.Sloan, strength));
        Vector3 liftedMin = lifted.MinIrradiance(plain, out where);
        Vector3 viaWindow = sh.MinIrradiance(ShEvalOptions.Create(ShOrder.L2, ShWindow.NonNegative), out where);
        Check(strength > 0 && liftedMin.x >= 0 && liftedMin.y >= 0 && liftedMin.z >= 0 && viaWindow.Equals(liftedMin),
              "the non-negative window's strength " + strength + " leaves the minimum " + liftedMin + " >= 0");
        SphericalHarmonicsL2 smaller = sh;
        smaller.ApplyOptions(ShEvalOptions.Create(ShOrder.L2, ShWindow.Sloan, strength * 0.5f));
        Vector3 smallerMin = smaller.MinIrradiance(plain, out where);
        Check(Math.Min(smallerMin.x, Math.Min(smallerMin.y, smallerMin.z)) < 0, "half that strength still rings negative");

        Throws<TetProbeException>(() => sh.EvaluateIrradiance(new Vector3(0, 0, 1), ShEvalOptions.Create(ShOrder.L2, ShWindow.Sloan, -1)),
                                  "a negative window strength", e => e.Status == TetProbeStatus.InvalidArgument);
        var unknown = ShEvalOptions.Create();
        unknown.Order = (ShOrder)7;
        Throws<TetProbeException>(() => sh.ApplyOptions(unknown), "an unknown order", e => e.Status == TetProbeStatus.InvalidArgument);
    }

    static void Queries()
    {
        var random = new Random(5);
        Vector3[] positions = Cloud(150, random);
        var sh = new SphericalHarmonicsL2[positions.Length];
        for (int i = 0; i < positions.Length; ++i) sh[i] = FieldSh(positions[i]);
        using (ProbeStore store = ProbeStore.Build(positions, sh))
        {
            ProbeStoreInfo info = store.Info;
            Check(info.Probes == 150 && info.Cells == info.InnerCells + info.OuterCells && info.IndexBits == 16,
                  "info counts");
            Check(info.Dimension == 3 && info.Extrapolation, "info dimension and extrapolation");

            double worst = 0;
            for (int i = 0; i < positions.Length; ++i)
            {
                int hint = -1;
                SphericalHarmonicsL2 value;
                store.Interpolate(positions[i], ref hint, out value);
                worst = Math.Max(worst, MaxDifference(value, store.ProbeSh(i), false));
                Check(hint >= 0, "hint set at probe " + i);
            }
            Check(worst < 1e-5, "exact at every probe (worst " + worst + ")");

            int moving = -1, totalSteps = 0;
            double linear = 0;
            var path = new Vector3[300];
            for (int f = 0; f < path.Length; ++f)
            {
                path[f] = new Vector3(-0.9f + 1.8f * f / 299f, 0.4f * (float)Math.Sin(f * 0.05), 0.2f);
                SphericalHarmonicsL2 value;
                store.Interpolate(path[f], ref moving, out value);
                linear = Math.Max(linear, MaxDifference(value, FieldSh(path[f]), true));
                int probeHint = moving;
                if (f > 0) totalSteps += store.Locate(path[f], ref probeHint).Steps;
            }
            Check(linear < 2e-3, "linear field reproduced inside the hull (worst relative " + linear + ")");
            Check(totalSteps / 299.0 < 1.0, "a hinted query at the same cell takes no steps");

            var batch = new SphericalHarmonicsL2[path.Length];
            var hints = new int[path.Length];
            for (int i = 0; i < hints.Length; ++i) hints[i] = -1;
            store.Interpolate(path, hints, batch);
            bool same = true;
            for (int f = 0; f < path.Length; ++f)
            {
                int h = -1;
                SphericalHarmonicsL2 single;
                store.Interpolate(path[f], ref h, out single);
                same &= single == batch[f] && h == hints[f];
            }
            Check(same, "batch equals single queries, hints included");
            var noHints = new SphericalHarmonicsL2[path.Length];
            store.Interpolate(path, null, noHints);
            Check(noHints[17] == batch[17], "batch without hints");

            var probes = new uint[4];
            var weights = new float[4];
            int wh = -1;
            store.Weights(new Vector3(0.1f, 0.2f, 0.3f), ref wh, probes, weights);
            Check(Math.Abs(weights[0] + weights[1] + weights[2] + weights[3] - 1) < 1e-5, "weights sum to 1");
            int outside = -1;
            Check(store.Locate(new Vector3(4, 0, 0), ref outside).Outer, "outside the hull: an outer cell");

            Throws<TetProbeException>(() => { int h = -1; SphericalHarmonicsL2 v; store.Interpolate(new Vector3(float.NaN, 0, 0), ref h, out v); },
                                      "NaN query", e => e.Status == TetProbeStatus.InvalidArgument);
            Throws<ArgumentException>(() => store.Interpolate(path, new int[3], batch), "short hints array");
            Throws<ArgumentException>(() => store.Interpolate(path, null, new SphericalHarmonicsL2[2]), "short results array");
            Throws<TetProbeException>(() => store.ProbeSh(150), "probe index out of range",
                                      e => e.Status == TetProbeStatus.InvalidArgument);
        }

        using (ProbeStore closed = ProbeStore.Build(positions, sh, false))
        {
            Check(closed.Info.OuterCells == 0, "no outer cells without extrapolation");
            Throws<TetProbeException>(() => { int h = -1; SphericalHarmonicsL2 v; closed.Interpolate(new Vector3(4, 0, 0), ref h, out v); },
                                      "outside without extrapolation", e => e.Status == TetProbeStatus.Outside);
        }
    }

    static void RoundTrips(string scratch)
    {
        var random = new Random(9);
        Vector3[] positions = Cloud(60, random);
        var sh = new SphericalHarmonicsL2[positions.Length];
        for (int i = 0; i < positions.Length; ++i) sh[i] = FieldSh(positions[i]);
        ProbeStore store = ProbeStore.Build(positions, sh);
        byte[] blob = store.Save();
        Check(blob.Length == store.Info.Bytes, "blob size equals info bytes");
        string path = Path.Combine(scratch, "store.tpb");
        store.Save(path);
        Check(File.Exists(path) && File.ReadAllBytes(path).Length == blob.Length, "file written");
        using (ProbeStore fromFile = ProbeStore.Load(path))
        using (ProbeStore fromBytes = ProbeStore.Load(blob))
        {
            bool same = true;
            byte[] a = fromFile.Save(), b = fromBytes.Save();
            for (int i = 0; i < blob.Length; ++i) same &= a[i] == blob[i] && b[i] == blob[i];
            Check(same && a.Length == blob.Length && b.Length == blob.Length, "file and bytes round trips are byte-identical");
            int h1 = -1, h2 = -1;
            SphericalHarmonicsL2 x, y;
            store.Interpolate(new Vector3(0.3f, 0.1f, -0.2f), ref h1, out x);
            fromFile.Interpolate(new Vector3(0.3f, 0.1f, -0.2f), ref h2, out y);
            Check(x == y, "loaded store answers the same");
        }
        Throws<TetProbeException>(() => ProbeStore.Load(Path.Combine(scratch, "missing.tpb")), "missing file",
                                  e => e.Status == TetProbeStatus.IO);
        var truncated = new byte[blob.Length / 2];
        Array.Copy(blob, truncated, truncated.Length);
        Throws<TetProbeException>(() => ProbeStore.Load(truncated), "truncated blob", e => e.Status == TetProbeStatus.InvalidBlob);
        Throws<TetProbeException>(() => ProbeStore.Load(new byte[0]), "empty blob", e => e.Status == TetProbeStatus.InvalidBlob);
        var corrupt = (byte[])blob.Clone();
        corrupt[corrupt.Length / 2] ^= 0xFF;
        Throws<TetProbeException>(() => ProbeStore.Load(corrupt), "corrupt blob", e => e.Status == TetProbeStatus.InvalidBlob);
        Throws<TetProbeException>(() => store.Save("/nonexistent-dir/x.tpb"), "unwritable path", e => e.Status == TetProbeStatus.IO);
        Throws<TetProbeException>(() => ProbeStore.Build(new Vector3[0], null), "no probes", e => e.Status == TetProbeStatus.Degenerate);
        Throws<TetProbeException>(() => ProbeStore.Build(new[] { new Vector3(float.NaN, 0, 0) }, null), "NaN probe",
                                  e => e.Status == TetProbeStatus.InvalidArgument);
        Throws<ArgumentException>(() => ProbeStore.Build(positions, new SphericalHarmonicsL2[3]), "SH count mismatch");
        Throws<ArgumentNullException>(() => ProbeStore.Build(null, null), "null positions");
        store.Dispose();
        store.Dispose();
        Throws<ObjectDisposedException>(() => { var i = store.Info; }, "use after Dispose");
    }

    static Vector3[] Scattered(int n, Random random, float low, float high)
    {
        var points = new Vector3[n];
        for (int i = 0; i < n; ++i)
            points[i] = new Vector3(low + (high - low) * (float)random.NextDouble(), low + (high - low) * (float)random.NextDouble(),
                                    low + (high - low) * (float)random.NextDouble());
        return points;
    }

    static int[] Fresh(int n)
    {
        var hints = new int[n];
        for (int i = 0; i < n; ++i) hints[i] = -1;
        return hints;
    }

    static bool SameSh(SphericalHarmonicsL2[] a, SphericalHarmonicsL2[] b)
    {
        if (a.Length != b.Length) return false;
        for (int i = 0; i < a.Length; ++i)
            if (!(a[i] == b[i])) return false;
        return true;
    }

    static bool SameInts(int[] a, int[] b)
    {
        if (a.Length != b.Length) return false;
        for (int i = 0; i < a.Length; ++i)
            if (a[i] != b[i]) return false;
        return true;
    }

    // Weight of `probe` in query i (slots that repeat a probe add up).
    static double WeightOf(uint[] probes, float[] weights, int i, uint probe)
    {
        double sum = 0;
        for (int k = 0; k < 4; ++k)
            if (probes[4 * i + k] == probe) sum += weights[4 * i + k];
        return sum;
    }

    static void LayoutsAndBatchOptions()
    {
        var random = new Random(13);
        Vector3[] positions = Cloud(400, random);
        var sh = new SphericalHarmonicsL2[positions.Length];
        for (int i = 0; i < positions.Length; ++i) sh[i] = FieldSh(positions[i]);
        using (ProbeStore fast = ProbeStore.Build(positions, sh))
        using (ProbeStore compact = ProbeStore.Build(positions, sh, true, true))
        {
            ProbeStoreInfo fi = fast.Info, ci = compact.Info;
            Check(fi.FormatVersion == 6 && ci.FormatVersion == 6, "format version 6");
            Check(!fi.Compact && ci.Compact && (ci.Flags & 4u) != 0 && (fi.Flags & 4u) == 0, "compact flag in info");
            Check(ci.Bytes < fi.Bytes, "compact blob is smaller (" + ci.Bytes + " < " + fi.Bytes + ")");
            Check(ci.Cells == fi.Cells && ci.InnerCells == fi.InnerCells, "same cells in both layouts");

            // Inside and outside the cube [-1, 1]^3 the probes span.
            Vector3[] points = Scattered(3000, random, -1.6f, 1.6f);
            int[] fastHints = Fresh(points.Length), compactHints = Fresh(points.Length);
            var fastProbes = new uint[4 * points.Length];
            var compactProbes = new uint[4 * points.Length];
            var fastWeights = new float[4 * points.Length];
            var compactWeights = new float[4 * points.Length];
            fast.Weights(points, fastHints, fastProbes, fastWeights);
            compact.Weights(points, compactHints, compactProbes, compactWeights);
            Check(SameInts(fastHints, compactHints), "compact and fast layouts find the same cells");
            double worst = 0;
            for (int i = 0; i < points.Length; ++i)
                for (int k = 0; k < 4; ++k)
                {
                    worst = Math.Max(worst, Math.Abs(WeightOf(fastProbes, fastWeights, i, fastProbes[4 * i + k]) -
                                                     WeightOf(compactProbes, compactWeights, i, fastProbes[4 * i + k])));
                    worst = Math.Max(worst, Math.Abs(WeightOf(fastProbes, fastWeights, i, compactProbes[4 * i + k]) -
                                                     WeightOf(compactProbes, compactWeights, i, compactProbes[4 * i + k])));
                }
            Check(worst <= 1e-6, "compact and fast weights within 1e-6 (worst " + worst + ")");
            using (ProbeStore reloaded = ProbeStore.Load(compact.Save()))
                Check(reloaded.Info.Compact && reloaded.Info.Bytes == ci.Bytes, "a compact blob loads as compact");

            // Threads: a batch large enough to be split gives the same answers as one thread.
            Vector3[] many = Scattered(10000, random, -1.3f, 1.3f);
            var one = new SphericalHarmonicsL2[many.Length];
            var two = new SphericalHarmonicsL2[many.Length];
            int[] oneHints = Fresh(many.Length), twoHints = Fresh(many.Length);
            fast.Interpolate(many, oneHints, one, 1);
            fast.Interpolate(many, twoHints, two, 2);
            Check(SameSh(one, two) && SameInts(oneHints, twoHints), "threads = 2 equals threads = 1");
            var defaults = new SphericalHarmonicsL2[many.Length];
            fast.Interpolate(many, null, defaults);
            Check(SameSh(one, defaults), "default options (null) equal threads = 1");

            // Chained hints without a hint array answer like cold starts: the same bytes inside the hull, where
            // the cell holding a point is decided exactly; outer cells accept a point within a weight tolerance,
            // so near the face two of them share the start decides which answers (continuously).
            var inner = new bool[many.Length];
            for (int i = 0; i < many.Length; ++i)
            {
                int h = -1;
                inner[i] = !fast.Locate(many[i], ref h).Outer;
            }
            var chained = new SphericalHarmonicsL2[many.Length];
            fast.Interpolate(many, null, chained, 2, true);
            var chainedProbes = new uint[4 * many.Length];
            var chainedWeights = new float[4 * many.Length];
            var coldProbes = new uint[4 * many.Length];
            var coldWeights = new float[4 * many.Length];
            fast.Weights(many, null, chainedProbes, chainedWeights, 1, true);
            fast.Weights(many, null, coldProbes, coldWeights);
            bool sameInner = true;
            int innerCount = 0;
            double worstOuter = 0;
            for (int i = 0; i < many.Length; ++i)
            {
                if (inner[i])
                {
                    ++innerCount;
                    sameInner &= one[i] == chained[i];
                    for (int k = 0; k < 4; ++k)
                        sameInner &= coldProbes[4 * i + k] == chainedProbes[4 * i + k] &&
                                     coldWeights[4 * i + k] == chainedWeights[4 * i + k];
                }
                else
                {
                    worstOuter = Math.Max(worstOuter, MaxDifference(one[i], chained[i], false));
                }
            }
            Check(innerCount > 1000 && innerCount < many.Length - 1000, "chained batch: points inside and outside");
            Check(sameInner, "chained hints give the same answers inside the hull");
            Check(worstOuter <= 1e-4, "chained hints within 1e-4 in outer cells (worst " + worstOuter + ")");
            Throws<ArgumentException>(() => fast.Interpolate(many, Fresh(many.Length), chained, 1, true),
                                      "chainHints with a hint array");
            Throws<ArgumentOutOfRangeException>(() => fast.Interpolate(many, null, chained, -1), "negative threads");
            Throws<ArgumentException>(() => fast.Weights(many, null, new uint[4], chainedWeights), "short probes array");

            // Format-2 to format-4 blobs: only the version field changed (not even the checksum); refused as a version.
            byte[] blob = fast.Save();
            Check(BitConverter.ToUInt32(blob, 8) == 6, "format version at byte 8");
            foreach (byte version in new byte[] { 2, 3, 4 })
            {
                var old = (byte[])blob.Clone();
                old[8] = version; old[9] = 0; old[10] = 0; old[11] = 0;
                Throws<TetProbeException>(() => ProbeStore.Load(old), "format-" + version + " blob",
                                          e => e.Status == TetProbeStatus.Version && e.Message.ToLowerInvariant().Contains("rebuild"));
            }
        }

        using (ProbeStore closed = ProbeStore.Build(positions, sh, false))
        {
            Vector3[] points = Scattered(50, random, -0.5f, 0.5f);
            points[23] = new Vector3(5, 0, 0);
            points[41] = new Vector3(0, -5, 0);
            var results = new SphericalHarmonicsL2[points.Length];
            Throws<TetProbeException>(() => closed.Interpolate(points, null, results, 2), "outside batch",
                                      e => e.Status == TetProbeStatus.Outside &&
                                           System.Text.RegularExpressions.Regex.IsMatch(e.Message, "\\b23\\b"));
            bool zeros = true;
            for (int k = 0; k < 27; ++k) zeros &= results[23][k / 9, k % 9] == 0 && results[41][k / 9, k % 9] == 0;
            Check(zeros, "outside queries of a batch get zero SH");
            Check(!(results[0] == new SphericalHarmonicsL2()), "inside queries of a failed batch are answered");
        }
    }

    static void Volumes()
    {
        float[] cube = { 1, 0, 0, 1, -1, 0, 0, 1, 0, 1, 0, 1, 0, -1, 0, 1, 0, 0, 1, 1, 0, 0, -1, 1 };
        float[] volume = ShadowCasterVolume.Build(cube, ShadowLight.Point, new Vector3(0, 5, 0));
        Check(volume.Length >= 20 && volume.Length % 4 == 0, "volume planes");
        Check(ShadowCasterVolume.TestSphere(volume, new Vector3(0, 3, 0), 0.1f), "sphere between light and box");
        Check(!ShadowCasterVolume.TestSphere(volume, new Vector3(0, 7, 0), 0.5f), "sphere behind the light");
        Check(!ShadowCasterVolume.TestAabb(volume, new Vector3(3, -1, 3), new Vector3(4, 0, 4)), "box beside the volume");
        float[] sunVolume = ShadowCasterVolume.Build(cube, ShadowLight.Directional, new Vector3(0, -1, 0));
        Check(ShadowCasterVolume.TestSphere(sunVolume, new Vector3(0, 500, 0), 1), "directional volume reaches up");
        Throws<ArgumentException>(() => ShadowCasterVolume.Build(new float[5], ShadowLight.Point, new Vector3(0, 5, 0)),
                                  "planes not a multiple of 4");
    }

#if !TETPROBE_RUNTIME_TESTS
    static int Main(string[] args)
    {
        string scratch = args.Length > 0 ? args[0] : Path.GetTempPath();
        string header = args.Length > 1 ? args[1] : "capi/tetprobe.h";
        string scenes = args.Length > 2 ? args[2] : "samples/scenes";
        Directory.CreateDirectory(scratch);
        foreach (Action<string> test in new Action<string>[] {
                     s => Layout(), s => ShHelpers(), s => ShOptions(), s => Queries(), s => LayoutsAndBatchOptions(), RoundTrips,
                     s => Volumes(), s => HeaderCheck.Run(header), s => SceneTests.Run(scenes), StoreTests.Run,
                     s => PlacementTests.Run(), s => VersionTests.Run() })
        {
            try
            {
                test(scratch);
            }
            catch (Exception e)
            {
                ++failed;
                Console.WriteLine("FAIL: unexpected " + e.GetType().Name + ": " + e.Message);
            }
        }
        return Summary();
    }
#endif

    /// <summary>Prints "N passed, N failed"; the exit code.</summary>
    internal static int Summary()
    {
        Console.WriteLine(passed + " passed, " + failed + " failed");
        return failed == 0 ? 0 : 1;
    }
}

static class NativeProxyVersion
{
    public const uint Major = 0, Minor = 8;
}
