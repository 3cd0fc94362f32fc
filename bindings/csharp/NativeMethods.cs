// Layer 1: the raw C ABI of capi/tetprobe.h as P/Invoke declarations, one per exported function,
// and the structs that cross it. Nothing here checks a status; see NativeProxy.
using System;
using System.Runtime.InteropServices;

namespace TetProbe
{
    [UnmanagedFunctionPointer(CallingConvention.Cdecl)]
    internal delegate int ProgressCallback(IntPtr user, float fraction, IntPtr stage);

    [StructLayout(LayoutKind.Sequential)]
    internal struct BuildOptions
    {
        public uint struct_size;
        public uint flags;
        public double merge_tolerance;
        public double flat_tolerance;
        public IntPtr progress;
        public IntPtr progress_user;
        // Format 4 scene data (tp_build_options_init writes the whole struct, so the layout must match).
        public IntPtr occlusion;
        public UIntPtr occlusion_stride;
        public uint occlusion_lights;
        public IntPtr scene;
    }

    [StructLayout(LayoutKind.Sequential)]
    internal struct NativeStoreInfo
    {
        public uint struct_size;
        public uint format_version;
        public uint dimension;
        public uint probes;
        public uint input_probes;
        public uint merged_probes;
        public uint cells;
        public uint inner_cells;
        public uint outer_cells;
        public uint index_bits;
        public uint flags;
        public uint grid_x, grid_y, grid_z;
        public ulong bytes;
        public double origin_x, origin_y, origin_z;
        public Vector3 bounds_min;
        public Vector3 bounds_max;
    }

    /// <summary>tp_batch_options: flags (TP_BATCH_*) and the threads a batch query may use (0 or 1 = the caller's).</summary>
    [StructLayout(LayoutKind.Sequential)]
    internal struct TpBatchOptions
    {
        public uint struct_size;
        public uint flags;
        public uint threads;
    }

    [StructLayout(LayoutKind.Sequential)]
    internal struct NativeLocation
    {
        public uint struct_size;
        public int cell;
        public uint cell_kind;
        public uint steps;
        public uint fallback;
        public uint probe0, probe1, probe2, probe3;
        public float weight0, weight1, weight2, weight3;
        public float t;
    }

    internal static class NativeMethods
    {
        const string Library = "tetprobe";

        public const uint BuildNoExtrapolation = 1;
        public const uint BuildIndex32 = 2;
        public const uint BuildCompact = 4;
        public const uint BatchChainHints = 1;
        public const uint CellOuter = 1;
        public const uint LightDirectional = 0;
        public const uint LightPoint = 1;
        public const uint LightSpot = 2;

        [DllImport(Library, CallingConvention = CallingConvention.Cdecl)]
        public static extern uint tp_version();

        [DllImport(Library, CallingConvention = CallingConvention.Cdecl)]
        public static extern IntPtr tp_last_error();

        [DllImport(Library, CallingConvention = CallingConvention.Cdecl)]
        public static extern IntPtr tp_status_name(int status);

        [DllImport(Library, CallingConvention = CallingConvention.Cdecl)]
        public static extern int tp_build_options_init(ref BuildOptions options);

        [DllImport(Library, CallingConvention = CallingConvention.Cdecl)]
        public static extern int tp_store_build([In] Vector3[] positions, UIntPtr position_stride,
            [In] SphericalHarmonicsL2[] sh, UIntPtr sh_stride, UIntPtr probe_count, ref BuildOptions options,
            out StoreHandle store);

        [DllImport(Library, CallingConvention = CallingConvention.Cdecl)]
        public static extern int tp_store_load([In] byte[] data, UIntPtr size, out StoreHandle store);

        [DllImport(Library, CallingConvention = CallingConvention.Cdecl)]
        public static extern int tp_store_load_file([In] byte[] path, out StoreHandle store);

        [DllImport(Library, CallingConvention = CallingConvention.Cdecl)]
        public static extern int tp_store_save_file(StoreHandle store, [In] byte[] path);

        [DllImport(Library, CallingConvention = CallingConvention.Cdecl)]
        public static extern int tp_store_blob(StoreHandle store, out IntPtr data, out UIntPtr size);

        [DllImport(Library, CallingConvention = CallingConvention.Cdecl)]
        public static extern int tp_store_release(IntPtr store);

        [DllImport(Library, CallingConvention = CallingConvention.Cdecl)]
        public static extern int tp_store_get_info(StoreHandle store, ref NativeStoreInfo info);

        [DllImport(Library, CallingConvention = CallingConvention.Cdecl)]
        public static extern int tp_store_probe_sh(StoreHandle store, uint probe, out SphericalHarmonicsL2 sh);

        [DllImport(Library, CallingConvention = CallingConvention.Cdecl)]
        public static extern int tp_store_interpolate(StoreHandle store, ref Vector3 position, ref int cell_hint,
            out SphericalHarmonicsL2 sh);

        [DllImport(Library, CallingConvention = CallingConvention.Cdecl)]
        public static extern int tp_batch_options_init(ref TpBatchOptions options);

        // Two declarations of each batch call: options by reference, or IntPtr.Zero for the defaults.
        [DllImport(Library, CallingConvention = CallingConvention.Cdecl)]
        public static extern int tp_store_interpolate_batch(StoreHandle store, UIntPtr count, [In] Vector3[] positions,
            UIntPtr position_stride, [In, Out] int[] hints, UIntPtr hint_stride, [Out] SphericalHarmonicsL2[] sh,
            UIntPtr sh_stride, ref TpBatchOptions options);

        [DllImport(Library, CallingConvention = CallingConvention.Cdecl)]
        public static extern int tp_store_interpolate_batch(StoreHandle store, UIntPtr count, [In] Vector3[] positions,
            UIntPtr position_stride, [In, Out] int[] hints, UIntPtr hint_stride, [Out] SphericalHarmonicsL2[] sh,
            UIntPtr sh_stride, IntPtr options);

        [DllImport(Library, CallingConvention = CallingConvention.Cdecl)]
        public static extern int tp_store_weights(StoreHandle store, ref Vector3 position, ref int cell_hint,
            [Out] uint[] probes, [Out] float[] weights);

        [DllImport(Library, CallingConvention = CallingConvention.Cdecl)]
        public static extern int tp_store_weights_batch(StoreHandle store, UIntPtr count, [In] Vector3[] positions,
            UIntPtr position_stride, [In, Out] int[] hints, UIntPtr hint_stride, [Out] uint[] probes,
            UIntPtr probes_stride, [Out] float[] weights, UIntPtr weights_stride, ref TpBatchOptions options);

        [DllImport(Library, CallingConvention = CallingConvention.Cdecl)]
        public static extern int tp_store_weights_batch(StoreHandle store, UIntPtr count, [In] Vector3[] positions,
            UIntPtr position_stride, [In, Out] int[] hints, UIntPtr hint_stride, [Out] uint[] probes,
            UIntPtr probes_stride, [Out] float[] weights, UIntPtr weights_stride, IntPtr options);

        [DllImport(Library, CallingConvention = CallingConvention.Cdecl)]
        public static extern int tp_store_locate(StoreHandle store, ref Vector3 position, ref int cell_hint,
            ref NativeLocation location);

        [DllImport(Library, CallingConvention = CallingConvention.Cdecl)]
        public static extern int tp_sh_eval_radiance(ref SphericalHarmonicsL2 sh, ref Vector3 direction, out Vector3 rgb);

        [DllImport(Library, CallingConvention = CallingConvention.Cdecl)]
        public static extern int tp_sh_eval_irradiance(ref SphericalHarmonicsL2 sh, ref Vector3 normal, out Vector3 rgb);

        [DllImport(Library, CallingConvention = CallingConvention.Cdecl)]
        public static extern int tp_sh_add_ambient(ref SphericalHarmonicsL2 sh, ref Vector3 rgb);

        [DllImport(Library, CallingConvention = CallingConvention.Cdecl)]
        public static extern int tp_sh_add_directional(ref SphericalHarmonicsL2 sh, ref Vector3 direction, ref Vector3 rgb);

        [DllImport(Library, CallingConvention = CallingConvention.Cdecl)]
        public static extern UIntPtr tp_shadow_caster_volume_bound(UIntPtr plane_count);

        [DllImport(Library, CallingConvention = CallingConvention.Cdecl)]
        public static extern int tp_shadow_caster_volume([In] float[] planes, UIntPtr plane_count, uint light_type,
            ref Vector3 light_vector, [Out] float[] out_planes, UIntPtr capacity, out UIntPtr out_count);

        [DllImport(Library, CallingConvention = CallingConvention.Cdecl)]
        public static extern int tp_volume_test_aabb([In] float[] planes, UIntPtr plane_count, ref Vector3 box_min,
            ref Vector3 box_max, out int intersects);

        [DllImport(Library, CallingConvention = CallingConvention.Cdecl)]
        public static extern int tp_volume_test_sphere([In] float[] planes, UIntPtr plane_count, ref Vector3 center,
            float radius, out int intersects);
    }
}
