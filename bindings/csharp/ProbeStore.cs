// Layer 3: ProbeStore, the idiomatic API over a native store. Immutable once built or loaded; any
// number of threads may query one store, each moving object keeping its own int hint (-1 = none).
using System;
using System.Threading;
#if UNITY_5_3_OR_NEWER
using Vector3 = UnityEngine.Vector3;
using Vector4 = UnityEngine.Vector4;
#endif

namespace TetProbe
{
    /// <summary>Counts and layout of a store (tp_store_info).</summary>
    public struct ProbeStoreInfo
    {
        public int FormatVersion, Dimension, Probes, InputProbes, MergedProbes, Cells, InnerCells, OuterCells, IndexBits;
        /// <summary>The blob's TP_BUILD_* bits (1 no extrapolation, 2 32-bit indices, 4 compact layout).</summary>
        public uint Flags;
        /// <summary>False for the no-outer-cells build.</summary>
        public bool Extrapolation;
        /// <summary>True for the compact layout (smallest blob), false for the fast one.</summary>
        public bool Compact;
        public long Bytes;
        public Vector3 BoundsMin, BoundsMax;
        /// <summary>How the cells are kept (BuildOptions.Layout).</summary>
        public StoreLayout Layout;
        /// <summary>How the SH are kept (BuildOptions.ShEncoding).</summary>
        public ShEncoding ShEncoding;
        /// <summary>Positions in 16 bits per axis (BuildOptions.QuantizePositions).</summary>
        public bool QuantizedPositions;
        /// <summary>Quantised positions: the largest gap between stored values per axis (a stored probe lies within
        /// half of it of its input); zero for float positions.</summary>
        public Vector3 PositionStep;
        /// <summary>Probes on the hull (those whose normals the store keeps).</summary>
        public int HullProbes;
        /// <summary>Bytes of each part of the blob; they add up to Bytes.</summary>
        public StoreSectionBytes SectionBytes;
        /// <summary>Mixed lights with occlusion probes (0 = none).</summary>
        public int OcclusionLights;
        /// <summary>Probe pairs that cannot see each other, kept for leak control (0 = built without a scene).</summary>
        public int LeakEdges;
    }

    /// <summary>Where one query ended and what it blended (tp_location).</summary>
    public struct ProbeLocation
    {
        public int Cell;
        /// <summary>True for an outer cell (beyond the probes' hull), false for a tetrahedron.</summary>
        public bool Outer;
        /// <summary>Cells the walk visited after its start cell.</summary>
        public int Steps;
        /// <summary>True if the walk handed the decision to the exhaustive search (only outside the hull).</summary>
        public bool Fallback;
        /// <summary>Input probe indices as Weights (unused slots weigh 0 and repeat a used probe).</summary>
        public uint[] Probes;
        public float[] Weights;
        /// <summary>Outer cells: the ray parameter of the point (0 on the hull).</summary>
        public float T;
    }

    /// <summary>What ProbeStore.SampleVolume writes per point (TP_VOLUME_*).</summary>
    public enum VolumeFormat
    {
        /// <summary>27 floats: our SH (SphericalHarmonicsL2's layout).</summary>
        ShL2 = 0,
        /// <summary>12 floats: bands 0 and 1, 4 per channel.</summary>
        ShL1 = 1,
        /// <summary>3 float4: unity_SHAr, unity_SHAg, unity_SHAb of the L1 SH (a Light Probe Proxy Volume's texels).</summary>
        UnityL1 = 2,
        /// <summary>7 float4: unity_SHAr, SHAg, SHAb, SHBr, SHBg, SHBb, SHC (ShadeSH9's constants).</summary>
        UnityL2 = 3,
    }

    /// <summary>Options of ProbeStore.Build (tp_build_options); a new instance holds the library's defaults.</summary>
    public sealed class BuildOptions
    {
        /// <summary>False: no outer cells; queries outside the probes' hull throw with TetProbeStatus.Outside.</summary>
        public bool Extrapolate = true;
        /// <summary>The smallest blob (neighbours rebuilt on load); answers as the fast layout (same cells, weights
        /// within 1e-6).</summary>
        public bool Compact;
        /// <summary>32-bit indices even where 16 bits would do.</summary>
        public bool Index32;
        /// <summary>Probes closer than this fraction of the set's bounding-box diagonal are merged.</summary>
        public double MergeTolerance;
        /// <summary>A set thinner than this fraction of its diagonal is treated as flat (or as a line).</summary>
        public double FlatTolerance;
        /// <summary>How the SH are kept: Half (the default, 54 bytes a probe), Unorm8 (L0 in halves, the rest as 8-bit
        /// ratios to L0: 30 bytes), or the L1 variants (band 2 dropped: zeros in queries).</summary>
        public ShEncoding ShEncoding = ShEncoding.Half;
        /// <summary>Positions in 16 bits per axis over the probes' bounds, quantised before the tessellation (so a query at a
        /// stored probe still weighs it exactly 1); probes that quantise to one point merge.</summary>
        public bool QuantizePositions;
        /// <summary>How the cells are kept: Fast (the default), Compact (as Compact = true), or Rebuilt (no cells stored:
        /// rebuilt from the positions when loaded, the same cells and answers; the smallest blob). Compact = true
        /// with Rebuilt is refused.</summary>
        public StoreLayout Layout = StoreLayout.Fast;
        /// <summary>Leak control (null = none): probe pairs of a cell that cannot see each other in this scene are
        /// stored, and queries weigh down the probe behind the wall. Full library only.</summary>
        public Scene Scene;
        /// <summary>Occlusion probes (Baker.BakeOcclusion, one per position; null = none): the store then answers
        /// InterpolateOcclusion with their blended visibility.</summary>
        public OcclusionProbes Occlusion;

        public BuildOptions()
        {
            NativeBuildOptions defaults = NativeProxy.DefaultBuildOptions();
            MergeTolerance = defaults.merge_tolerance;
            FlatTolerance = defaults.flat_tolerance;
        }

        internal NativeBuildOptions ToNative()
        {
            NativeBuildOptions options = NativeProxy.DefaultBuildOptions();
            options.flags = (Extrapolate ? 0u : NativeMethods.BuildNoExtrapolation) |
                            (Compact ? NativeMethods.BuildCompact : 0u) | (Index32 ? NativeMethods.BuildIndex32 : 0u);
            options.merge_tolerance = MergeTolerance;
            options.flat_tolerance = FlatTolerance;
            options.sh_encoding = (uint)ShEncoding;
            options.quantize_positions = QuantizePositions ? 1u : 0u;
            options.layout = (uint)Layout;
            return options;
        }
    }

    public sealed partial class ProbeStore : IDisposable
    {
        readonly StoreHandle handle;

        ProbeStore(StoreHandle handle)
        {
            this.handle = handle;
        }

        /// <summary>The loaded library's version as (major &lt;&lt; 16) | (minor &lt;&lt; 8) | patch.</summary>
        public static uint LibraryVersion { get { return NativeProxy.VersionSource(); } }

        /// <summary>Builds a store from probe positions and their SH (null = zeros). extrapolate = false builds no
        /// outer cells: queries outside the probes' hull then throw with TetProbeStatus.Outside. compact = true writes
        /// the compact layout (the smallest blob, neighbours rebuilt on load) that answers like the default fast one
        /// (the same cells, weights within 1e-6).</summary>
        public static ProbeStore Build(Vector3[] positions, SphericalHarmonicsL2[] sh, bool extrapolate = true,
                                       bool compact = false)
        {
            return Build(positions, sh, new BuildOptions { Extrapolate = extrapolate, Compact = compact });
        }

        /// <summary>Builds a store with options (null = defaults). progress receives fractions in [0, 1] on the calling
        /// thread; cancelling `cancel` stops the build with OperationCanceledException.</summary>
        public static ProbeStore Build(Vector3[] positions, SphericalHarmonicsL2[] sh, BuildOptions options,
                                       IProgress<float> progress = null, CancellationToken cancel = default(CancellationToken))
        {
            if (positions == null) throw new ArgumentNullException("positions");
            if (sh != null && sh.Length != positions.Length)
                throw new ArgumentException("sh has " + sh.Length + " entries for " + positions.Length + " positions", "sh");
            options = options ?? new BuildOptions();
            OcclusionProbes occlusion = options.Occlusion;
            if (occlusion != null && occlusion.Probes.Length != positions.Length)
                throw new ArgumentException("Occlusion has " + occlusion.Probes.Length + " probes for " + positions.Length +
                                            " positions", "options");
            return new ProbeStore(NativeProxy.Build(positions, sh, options.ToNative(),
                options.Scene == null ? null : options.Scene.Live(), occlusion == null ? null : occlusion.Probes,
                occlusion == null ? 0 : occlusion.MixedLights, progress, cancel));
        }

        /// <summary>Loads and validates a store file (a regular file of at most 1 GiB).</summary>
        public static ProbeStore Load(string path)
        {
            return new ProbeStore(NativeProxy.LoadFile(path));
        }

        /// <summary>Loads and validates a store file; a file larger than maxFileBytes, or one that is not a regular
        /// file, throws TetProbeException with status IO.</summary>
        public static ProbeStore Load(string path, ulong maxFileBytes)
        {
            return new ProbeStore(NativeProxy.LoadFile(path, maxFileBytes));
        }

        /// <summary>Loads and validates a store blob (copied; safe for untrusted bytes).</summary>
        public static ProbeStore Load(byte[] data)
        {
            if (data == null) throw new ArgumentNullException("data");
            return new ProbeStore(NativeProxy.Load(data));
        }

        /// <summary>Writes the store to path atomically (a temporary file next to it, then a rename; a symbolic link is
        /// written through and an existing file keeps its permissions).</summary>
        public void Save(string path)
        {
            NativeProxy.SaveFile(Live(), path);
        }

        /// <summary>The store's blob.</summary>
        public byte[] Save()
        {
            return NativeProxy.Blob(Live());
        }

        public ProbeStoreInfo Info
        {
            get
            {
                NativeStoreInfo n = NativeProxy.Info(Live());
                return new ProbeStoreInfo
                {
                    FormatVersion = (int)n.format_version, Dimension = (int)n.dimension, Probes = (int)n.probes,
                    InputProbes = (int)n.input_probes, MergedProbes = (int)n.merged_probes, Cells = (int)n.cells,
                    InnerCells = (int)n.inner_cells, OuterCells = (int)n.outer_cells, IndexBits = (int)n.index_bits,
                    Flags = n.flags, Extrapolation = (n.flags & NativeMethods.BuildNoExtrapolation) == 0,
                    Compact = (n.flags & NativeMethods.BuildCompact) != 0, Bytes = (long)n.bytes,
                    BoundsMin = n.bounds_min, BoundsMax = n.bounds_max,
                    Layout = (StoreLayout)n.layout, ShEncoding = (ShEncoding)n.sh_encoding,
                    QuantizedPositions = n.quantized_positions != 0,
                    PositionStep = new Vector3((float)n.position_step_x, (float)n.position_step_y, (float)n.position_step_z),
                    HullProbes = (int)n.hull_probes, SectionBytes = new StoreSectionBytes(n.section_bytes),
                    OcclusionLights = (int)n.occlusion_lights, LeakEdges = (int)n.leak_edges,
                };
            }
        }

        /// <summary>The stored SH of input probe `probe`, decoded (what a query at the probe returns).</summary>
        public SphericalHarmonicsL2 ProbeSh(int probe)
        {
            return NativeProxy.ProbeSh(Live(), probe);
        }

        /// <summary>Interpolated SH at position; hint is the object's cell from last frame (-1 = none), updated.</summary>
        public void Interpolate(Vector3 position, ref int hint, out SphericalHarmonicsL2 sh)
        {
            NativeProxy.Interpolate(Live(), position, ref hint, out sh);
        }

        /// <summary>Batch form: results[i] at positions[i]; hints (null = none) are read and updated. Positions
        /// outside a store built without extrapolation throw TetProbeStatus.Outside naming the first.</summary>
        public void Interpolate(Vector3[] positions, int[] hints, SphericalHarmonicsL2[] results)
        {
            CheckBatch(positions, hints, results == null ? -1 : results.Length, "results", 1, false);
            NativeProxy.InterpolateBatch(Live(), positions, hints, results);
        }

        /// <summary>Batch form; threads is deprecated and ignored: the batch runs on the calling thread (split a
        /// frame by calling the batch on disjoint ranges from your own threads, each range with its own hints).
        /// chainHints (only with hints == null): each query starts from the cell the previous one ended in, for
        /// objects given in a spatially coherent order.</summary>
        public void Interpolate(Vector3[] positions, int[] hints, SphericalHarmonicsL2[] results, int threads,
                                bool chainHints = false)
        {
            CheckBatch(positions, hints, results == null ? -1 : results.Length, "results", 1, chainHints);
            NativeProxy.InterpolateBatch(Live(), positions, hints, results, NativeProxy.BatchOptions(threads, chainHints));
        }

        /// <summary>Interpolated SH and occlusion at position (Unity's CalculateInterpolatedLightAndOcclusionProbes):
        /// occlusion.x..w is the visibility in [0, 1] of mixed lights 0..3 blended from the probes' occlusion (1 for
        /// channels without a light, and for a store built without occlusion); hint as Interpolate.</summary>
        public void InterpolateOcclusion(Vector3 position, ref int hint, out SphericalHarmonicsL2 sh, out Vector4 occlusion)
        {
            NativeProxy.InterpolateOcclusion(Live(), position, ref hint, out sh, out occlusion);
        }

        /// <summary>Batch form of InterpolateOcclusion: sh[i] and occlusion[i] at positions[i]; hints, threads and
        /// chainHints as the batch Interpolate.</summary>
        public void InterpolateOcclusion(Vector3[] positions, int[] hints, SphericalHarmonicsL2[] sh, Vector4[] occlusion,
                                         int threads = 1, bool chainHints = false)
        {
            CheckBatch(positions, hints, sh == null ? -1 : sh.Length, "sh", 1, chainHints);
            CheckBatch(positions, hints, occlusion == null ? -1 : occlusion.Length, "occlusion", 1, chainHints);
            NativeProxy.InterpolateOcclusionBatch(Live(), positions, hints, sh, occlusion,
                                                  NativeProxy.BatchOptions(threads, chainHints));
        }

        /// <summary>Batch form of Weights: probes[4 i .. 4 i + 3] and weights[4 i .. 4 i + 3] for positions[i];
        /// hints, threads and chainHints as the batch Interpolate.</summary>
        public void Weights(Vector3[] positions, int[] hints, uint[] probes, float[] weights, int threads = 1,
                            bool chainHints = false)
        {
            CheckBatch(positions, hints, probes == null ? -1 : probes.Length, "probes", 4, chainHints);
            CheckBatch(positions, hints, weights == null ? -1 : weights.Length, "weights", 4, chainHints);
            NativeProxy.WeightsBatch(Live(), positions, hints, probes, weights, NativeProxy.BatchOptions(threads, chainHints));
        }

        static void CheckBatch(Vector3[] positions, int[] hints, int outputLength, string output, int perPosition,
                               bool chainHints)
        {
            if (positions == null) throw new ArgumentNullException("positions");
            if (outputLength < 0) throw new ArgumentNullException(output);
            if (outputLength < perPosition * (long)positions.Length)
                throw new ArgumentException(output + " holds " + outputLength + " for " + positions.Length + " positions", output);
            if (hints != null && hints.Length < positions.Length)
                throw new ArgumentException("hints holds " + hints.Length + " for " + positions.Length + " positions", "hints");
            if (hints != null && chainHints)
                throw new ArgumentException("chainHints applies only to batches without hints", "hints");
        }

        /// <summary>The four input probes and weights a query at position blends (unused slots weigh 0).</summary>
        public void Weights(Vector3 position, ref int hint, uint[] probes, float[] weights)
        {
            if (probes == null || probes.Length < 4) throw new ArgumentException("probes must hold 4", "probes");
            if (weights == null || weights.Length < 4) throw new ArgumentException("weights must hold 4", "weights");
            NativeProxy.Weights(Live(), position, ref hint, probes, weights);
        }

        /// <summary>Diagnostics of one query: its cell, kind, walk steps, probes and weights.</summary>
        public ProbeLocation Locate(Vector3 position, ref int hint)
        {
            NativeLocation n = NativeProxy.Locate(Live(), position, ref hint);
            return new ProbeLocation
            {
                Cell = n.cell, Outer = n.cell_kind == NativeMethods.CellOuter, Steps = (int)n.steps,
                Fallback = n.fallback != 0, T = n.t,
                Probes = new[] { n.probe0, n.probe1, n.probe2, n.probe3 },
                Weights = new[] { n.weight0, n.weight1, n.weight2, n.weight3 },
            };
        }

        /// <summary>A probe volume (Unity's Light Probe Proxy Volume): the SH at origin + (x, y, z) * cellSize for
        /// x &lt; nx, y &lt; ny, z &lt; nz (each 1..32) into output, packed [z][y][x] with the format's floats per point
        /// (27, 12, 3 x 4 or 7 x 4; see VolumeFormat), each point bit for bit what Interpolate gives there in the
        /// volume's walk (tp_store_sample_volume). hint: the cell to start from (-1 = none), updated to the cell of
        /// point (0, 0, 0) for the next frame.</summary>
        public void SampleVolume(Vector3 origin, Vector3 cellSize, int nx, int ny, int nz, VolumeFormat format,
                                 float[] output, ref int hint)
        {
            SampleVolume(origin, cellSize, nx, ny, nz, format, output, ref hint, 0, 0, 0, 0);
        }

        /// <summary>SampleVolume with byte strides into output (0 = packed): point (x, y, z) starts at
        /// x pointStride + y rowStride + z sliceStride bytes, a Unity format's float4 k at k vectorStride bytes after
        /// that. With 16, 64 nx, 64 nx ny and 16 nx, VolumeFormat.UnityL1 fills a Light Probe Proxy Volume's
        /// RGBAFloat atlas (4 nx by ny by nz texels: SHAr, SHAg, SHAb, and a fourth block left as it is).</summary>
        public void SampleVolume(Vector3 origin, Vector3 cellSize, int nx, int ny, int nz, VolumeFormat format,
                                 float[] output, ref int hint, long pointStride, long rowStride, long sliceStride,
                                 long vectorStride)
        {
            if (output == null) throw new ArgumentNullException("output");
            int[] sides = { nx, ny, nz };
            for (int a = 0; a < 3; ++a)
                if (sides[a] < 1 || sides[a] > NativeMethods.VolumeMaxSide)
                    throw new ArgumentOutOfRangeException("n" + "xyz"[a], sides[a], "a volume has 1 to 32 points a side");
            if (pointStride < 0 || rowStride < 0 || sliceStride < 0 || vectorStride < 0)
                throw new ArgumentException("strides must not be negative");
            bool unity = format == VolumeFormat.UnityL1 || format == VolumeFormat.UnityL2;
            long unit = format == VolumeFormat.ShL2 ? 108 : format == VolumeFormat.ShL1 ? 48 : 16;
            long units = format == VolumeFormat.UnityL2 ? 7 : format == VolumeFormat.UnityL1 ? 3 : 1;
            // The bytes the library writes, with its defaults for zero strides: they must lie inside output (the
            // library checks the strides themselves).
            long vector = vectorStride != 0 ? vectorStride : unit;
            long point = pointStride != 0 ? pointStride : units * unit;
            long row = rowStride != 0 ? rowStride : nx * point;
            long slice = sliceStride != 0 ? sliceStride : ny * row;
            const long limit = long.MaxValue / 8;
            if (point > limit || row > limit || slice > limit || vector > limit)
                throw new ArgumentException("a stride is too large for any array");
            long extent = (nx - 1) * point + (ny - 1) * row + (nz - 1) * slice + (units - 1) * vector + unit;
            if (extent > 4L * output.Length)
                throw new ArgumentException("output holds " + output.Length + " floats; the volume's layout needs " +
                                            (extent + 3) / 4, "output");
            NativeVolumeLayout layout = NativeProxy.VolumeLayout();
            layout.format = (uint)format;
            layout.point_stride = (UIntPtr)pointStride;
            layout.row_stride = (UIntPtr)rowStride;
            layout.slice_stride = (UIntPtr)sliceStride;
            layout.vector_stride = unity ? (UIntPtr)vectorStride : UIntPtr.Zero;
            NativeProxy.SampleVolume(Live(), origin, cellSize, new[] { (uint)nx, (uint)ny, (uint)nz }, ref hint, layout,
                                     output);
        }

        StoreHandle Live()
        {
            if (handle.IsClosed) throw new ObjectDisposedException("ProbeStore");
            return handle;
        }

        public void Dispose()
        {
            handle.Dispose();
        }
    }
}
