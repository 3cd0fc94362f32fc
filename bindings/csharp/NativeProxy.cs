// Layer 2: calls into NativeMethods that turn a failing tp_status into a TetProbeException carrying
// the library's message, check the library version once, and marshal strings and strides.
using System;
using System.Runtime.InteropServices;
using System.Text;
using System.Threading;
#if UNITY_5_3_OR_NEWER
using Vector3 = UnityEngine.Vector3;
using Vector4 = UnityEngine.Vector4;
#endif

namespace TetProbe
{
    internal static partial class NativeProxy
    {
        /// <summary>The version this binding was written for; the library's major.minor must match.</summary>
        public const uint BindingVersionMajor = 0, BindingVersionMinor = 8;

        /// <summary>Where the library's version comes from; tests put a fake library version here.</summary>
        internal static Func<uint> VersionSource = () => NativeMethods.tp_version();

        static volatile bool versionChecked;

        static readonly UIntPtr PositionStride = (UIntPtr)12;
        static readonly UIntPtr HintStride = (UIntPtr)4;
        static readonly UIntPtr ShStride = (UIntPtr)108;
        static readonly UIntPtr FourStride = (UIntPtr)16;

        public static void Check(int status)
        {
            if (status != 0)
                throw new TetProbeException((TetProbeStatus)status, Utf8String(NativeMethods.tp_last_error()));
        }

        /// <summary>A NUL-terminated UTF-8 string of the library (messages, names), decoded as UTF-8 on every platform.</summary>
        internal static string Utf8String(IntPtr text)
        {
            if (text == IntPtr.Zero) return "";
            int length = 0;
            while (Marshal.ReadByte(text, length) != 0) ++length;
            var bytes = new byte[length];
            Marshal.Copy(text, bytes, 0, length);
            return Encoding.UTF8.GetString(bytes);
        }

        /// <summary>Checks once that the native library is there and of the binding's major.minor; until a check
        /// succeeds every call into the library repeats it and throws TetProbeException(Version) or
        /// DllNotFoundException with what to do.</summary>
        public static void EnsureVersion()
        {
            if (versionChecked) return;
            uint version;
            try
            {
                version = VersionSource();
            }
            catch (DllNotFoundException e)
            {
                throw new DllNotFoundException("the tetprobe native library '" + NativeMethods.Library + "' was not found: put " +
                    "the plugin (lib" + NativeMethods.Library + ".so, " + NativeMethods.Library + ".dll or lib" +
                    NativeMethods.Library + ".dylib) where the runtime looks for native libraries", e);
            }
            catch (EntryPointNotFoundException e)
            {
                // A library of that name without tp_version: an old tetprobe or another library altogether.
                throw new TetProbeException(TetProbeStatus.Version, "the native library '" + NativeMethods.Library + "' has no " +
                    "tp_version: it is not a tetprobe plugin of this release (this binding needs " + BindingVersionMajor + "." +
                    BindingVersionMinor + ".x): ship the binding and the plugin of the same release", e);
            }
            uint major = version >> 16, minor = (version >> 8) & 0xFF;
            if (major != BindingVersionMajor || minor != BindingVersionMinor)
                throw new TetProbeException(TetProbeStatus.Version, "the native library '" + NativeMethods.Library + "' is version " +
                    major + "." + minor + "." + (version & 0xFF) + " but this TetProbe binding needs " + BindingVersionMajor + "." +
                    BindingVersionMinor + ".x: ship the binding and the plugin of the same release");
            versionChecked = true;
        }

        /// <summary>Forgets a successful version check (tests that change VersionSource).</summary>
        internal static void ResetVersionCheck()
        {
            versionChecked = false;
        }

        internal static byte[] Utf8Path(string path)
        {
            if (path == null) throw new ArgumentNullException("path");
            return Encoding.UTF8.GetBytes(path + "\0");
        }

        public static NativeBuildOptions DefaultBuildOptions()
        {
            EnsureVersion();
            var options = new NativeBuildOptions();
            Check(NativeMethods.tp_build_options_init(ref options));
            return options;
        }

        /// <summary>tp_store_build. scene (leak control) and occlusion (occlusion probes of occlusionLights mixed lights)
        /// may be null; the scene stays referenced and the occlusion bytes pinned for the call.</summary>
        public static StoreHandle Build(Vector3[] positions, SphericalHarmonicsL2[] sh, NativeBuildOptions options,
                                        SceneHandle scene, ProbeOcclusion[] occlusion, int occlusionLights,
                                        IProgress<float> progress, CancellationToken cancel)
        {
            EnsureVersion();
            bool sceneReferenced = false;
            GCHandle pinned = default(GCHandle);
            try
            {
                if (scene != null)
                {
                    scene.DangerousAddRef(ref sceneReferenced);
                    options.scene = scene.DangerousGetHandle();
                }
                if (occlusion != null)
                {
                    pinned = GCHandle.Alloc(occlusion, GCHandleType.Pinned);
                    options.occlusion = pinned.AddrOfPinnedObject();
                    options.occlusion_stride = (UIntPtr)4;
                    options.occlusion_lights = (uint)occlusionLights;
                }
                using (var bridge = ProgressBridge.Start(progress, cancel))
                {
                    options.progress = bridge.Callback;
                    options.progress_user = bridge.User;
                    StoreHandle store;
                    int status = NativeMethods.tp_store_build(positions, PositionStride, sh, ShStride,
                        (UIntPtr)positions.Length, ref options, out store);
                    bridge.Finish(status);
                    return store;
                }
            }
            finally
            {
                if (pinned.IsAllocated) pinned.Free();
                if (sceneReferenced) scene.DangerousRelease();
            }
        }

        public static StoreHandle Load(byte[] data)
        {
            EnsureVersion();
            StoreHandle store;
            Check(NativeMethods.tp_store_load(data.Length > 0 ? data : new byte[1], (UIntPtr)data.Length, out store));
            return store;
        }

        public static StoreHandle LoadFile(string path)
        {
            EnsureVersion();
            StoreHandle store;
            Check(NativeMethods.tp_store_load_file(Utf8Path(path), out store));
            return store;
        }

        public static StoreHandle LoadFile(string path, ulong maxFileBytes)
        {
            EnsureVersion();
            var options = new TpStoreLoadOptions();
            Check(NativeMethods.tp_store_load_options_init(ref options));
            options.max_file_bytes = maxFileBytes;
            StoreHandle store;
            Check(NativeMethods.tp_store_load_file_ex(Utf8Path(path), ref options, out store));
            return store;
        }

        public static void SaveFile(StoreHandle store, string path)
        {
            EnsureVersion();
            Check(NativeMethods.tp_store_save_file(store, Utf8Path(path)));
        }

        /// <summary>Tests only: runs between a call that returns a pointer into a handle's object and the copy out of it.
        /// </summary>
        internal static Action<SafeHandle> BeforeBorrowedCopy = null;

        /// <summary>The store's blob, copied. tp_store_blob points into the store: the handle stays referenced until the
        /// copy is done, so a Dispose on another thread meanwhile defers the release instead of freeing what is read.</summary>
        public static byte[] Blob(StoreHandle store)
        {
            bool referenced = false;
            try
            {
                store.DangerousAddRef(ref referenced);
                IntPtr data;
                UIntPtr size;
                Check(NativeMethods.tp_store_blob(store, out data, out size));
                if (BeforeBorrowedCopy != null) BeforeBorrowedCopy(store);
                var bytes = new byte[(long)size.ToUInt64()];
                Marshal.Copy(data, bytes, 0, bytes.Length);
                return bytes;
            }
            finally
            {
                if (referenced) store.DangerousRelease();
            }
        }

        public static NativeStoreInfo Info(StoreHandle store)
        {
            var info = new NativeStoreInfo();
            info.struct_size = (uint)Marshal.SizeOf(typeof(NativeStoreInfo));
            Check(NativeMethods.tp_store_get_info(store, ref info));
            return info;
        }

        public static SphericalHarmonicsL2 ProbeSh(StoreHandle store, int probe)
        {
            if (probe < 0) throw new ArgumentOutOfRangeException("probe");
            SphericalHarmonicsL2 sh;
            Check(NativeMethods.tp_store_probe_sh(store, (uint)probe, out sh));
            return sh;
        }

        public static void Interpolate(StoreHandle store, Vector3 position, ref int hint, out SphericalHarmonicsL2 sh)
        {
            Check(NativeMethods.tp_store_interpolate(store, ref position, ref hint, out sh));
        }

        /// <summary>tp_batch_options for TP_BATCH_CHAIN_HINTS; threads is passed on but ignored by the library (deprecated).</summary>
        public static TpBatchOptions BatchOptions(int threads, bool chainHints)
        {
            if (threads < 0) throw new ArgumentOutOfRangeException("threads", threads, "threads must be >= 0");
            var options = new TpBatchOptions();
            Check(NativeMethods.tp_batch_options_init(ref options));
            options.threads = (uint)threads;
            options.flags = chainHints ? NativeMethods.BatchChainHints : 0u;
            return options;
        }

        /// <summary>Batch interpolation with the library's default options (NULL).</summary>
        public static void InterpolateBatch(StoreHandle store, Vector3[] positions, int[] hints, SphericalHarmonicsL2[] results)
        {
            Check(NativeMethods.tp_store_interpolate_batch(store, (UIntPtr)positions.Length, positions, PositionStride,
                hints, HintStride, results, ShStride, IntPtr.Zero));
        }

        public static void InterpolateBatch(StoreHandle store, Vector3[] positions, int[] hints, SphericalHarmonicsL2[] results,
            TpBatchOptions options)
        {
            Check(NativeMethods.tp_store_interpolate_batch(store, (UIntPtr)positions.Length, positions, PositionStride,
                hints, HintStride, results, ShStride, ref options));
        }

        public static void InterpolateOcclusion(StoreHandle store, Vector3 position, ref int hint, out SphericalHarmonicsL2 sh,
                                                out Vector4 occlusion)
        {
            Check(NativeMethods.tp_store_interpolate_occlusion(store, ref position, ref hint, out sh, out occlusion));
        }

        public static void InterpolateOcclusionBatch(StoreHandle store, Vector3[] positions, int[] hints,
            SphericalHarmonicsL2[] sh, Vector4[] occlusion, TpBatchOptions options)
        {
            Check(NativeMethods.tp_store_interpolate_occlusion_batch(store, (UIntPtr)positions.Length, positions, PositionStride,
                hints, HintStride, sh, ShStride, occlusion, FourStride, ref options));
        }

        public static void Weights(StoreHandle store, Vector3 position, ref int hint, uint[] probes, float[] weights)
        {
            Check(NativeMethods.tp_store_weights(store, ref position, ref hint, probes, weights));
        }

        public static void WeightsBatch(StoreHandle store, Vector3[] positions, int[] hints, uint[] probes, float[] weights,
            TpBatchOptions options)
        {
            Check(NativeMethods.tp_store_weights_batch(store, (UIntPtr)positions.Length, positions, PositionStride, hints,
                HintStride, probes, FourStride, weights, FourStride, ref options));
        }

        public static NativeLocation Locate(StoreHandle store, Vector3 position, ref int hint)
        {
            var location = new NativeLocation();
            location.struct_size = (uint)Marshal.SizeOf(typeof(NativeLocation));
            Check(NativeMethods.tp_store_locate(store, ref position, ref hint, ref location));
            return location;
        }

        public static NativeVolumeLayout VolumeLayout()
        {
            var layout = new NativeVolumeLayout();
            Check(NativeMethods.tp_volume_layout_init(ref layout));
            return layout;
        }

        public static void SampleVolume(StoreHandle store, Vector3 origin, Vector3 cellSize, uint[] dims, ref int hint,
            NativeVolumeLayout layout, float[] output)
        {
            Check(NativeMethods.tp_store_sample_volume(store, ref origin, ref cellSize, dims, ref hint, ref layout, output));
        }

        public static void ShAddAmbient(ref SphericalHarmonicsL2 sh, float r, float g, float b)
        {
            EnsureVersion();
            var rgb = new Vector3(r, g, b);
            Check(NativeMethods.tp_sh_add_ambient(ref sh, ref rgb));
        }

        public static void ShAddDirectional(ref SphericalHarmonicsL2 sh, Vector3 direction, float r, float g, float b)
        {
            EnsureVersion();
            var rgb = new Vector3(r, g, b);
            Check(NativeMethods.tp_sh_add_directional(ref sh, ref direction, ref rgb));
        }

        public static Vector3 ShEvalRadiance(ref SphericalHarmonicsL2 sh, Vector3 direction)
        {
            EnsureVersion();
            Vector3 rgb;
            Check(NativeMethods.tp_sh_eval_radiance(ref sh, ref direction, out rgb));
            return rgb;
        }

        public static Vector3 ShEvalIrradiance(ref SphericalHarmonicsL2 sh, Vector3 normal)
        {
            EnsureVersion();
            Vector3 rgb;
            Check(NativeMethods.tp_sh_eval_irradiance(ref sh, ref normal, out rgb));
            return rgb;
        }

        public static Vector3 ShEvalIrradiance(ref SphericalHarmonicsL2 sh, Vector3 normal, ShEvalOptions options)
        {
            EnsureVersion();
            options = options.Sized();
            Vector3 rgb;
            Check(NativeMethods.tp_sh_eval_irradiance_ex(ref sh, ref normal, ref options, out rgb));
            return rgb;
        }

        public static void ShApplyOptions(ref SphericalHarmonicsL2 sh, ShEvalOptions options)
        {
            EnsureVersion();
            options = options.Sized();
            Check(NativeMethods.tp_sh_apply_options(ref sh, ref options));
        }

        public static Vector3 ShMinIrradiance(ref SphericalHarmonicsL2 sh, ShEvalOptions options, out Vector3 normal)
        {
            EnsureVersion();
            options = options.Sized();
            Vector3 rgb;
            Check(NativeMethods.tp_sh_min_irradiance(ref sh, ref options, out rgb, out normal));
            return rgb;
        }

        public static float ShNonNegativeWindowStrength(ref SphericalHarmonicsL2 sh, ShOrder order)
        {
            EnsureVersion();
            ShEvalOptions options = new ShEvalOptions { Order = order }.Sized();
            float strength;
            Check(NativeMethods.tp_sh_nonnegative_window_strength(ref sh, ref options, out strength));
            return strength;
        }

        public static float[] ShadowCasterVolume(float[] planes, uint lightType, Vector3 lightVector)
        {
            EnsureVersion();
            UIntPtr planeCount = (UIntPtr)(planes.Length / 4);
            UIntPtr capacity = NativeMethods.tp_shadow_caster_volume_bound(planeCount);
            var output = new float[4 * Math.Max(1, (int)capacity.ToUInt64())];
            UIntPtr count;
            Check(NativeMethods.tp_shadow_caster_volume(planes, planeCount, lightType, ref lightVector, output, capacity,
                out count));
            var result = new float[4 * (int)count.ToUInt64()];
            Array.Copy(output, result, result.Length);
            return result;
        }

        public static bool VolumeTestAabb(float[] planes, Vector3 min, Vector3 max)
        {
            EnsureVersion();
            int hit;
            Check(NativeMethods.tp_volume_test_aabb(planes, (UIntPtr)(planes.Length / 4), ref min, ref max, out hit));
            return hit != 0;
        }

        public static bool VolumeTestSphere(float[] planes, Vector3 center, float radius)
        {
            EnsureVersion();
            int hit;
            Check(NativeMethods.tp_volume_test_sphere(planes, (UIntPtr)(planes.Length / 4), ref center, radius, out hit));
            return hit != 0;
        }
    }
}
