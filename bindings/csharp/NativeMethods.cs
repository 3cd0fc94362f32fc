// Layer 1: the raw C ABI of capi/tetprobe.h as P/Invoke declarations, one per exported function,
// and the structs that cross it. Nothing here checks a status; see NativeProxy. tests/csharp checks every
// declaration here against the header (names, parameter and return types, struct layouts).
// Span overloads on by themselves wherever the runtime has Span<T> in its core library.
#if UNITY_2021_2_OR_NEWER || NETCOREAPP2_1_OR_GREATER || NETSTANDARD2_1_OR_GREATER
#define TETPROBE_SPAN
#endif
using System;
using System.Runtime.InteropServices;
#if UNITY_5_3_OR_NEWER
using Vector3 = UnityEngine.Vector3;
using Vector4 = UnityEngine.Vector4;
#endif

namespace TetProbe
{
    /// <summary>tp_build_options.</summary>
    [StructLayout(LayoutKind.Sequential)]
    internal struct NativeBuildOptions
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
        // Format 5.
        public uint sh_encoding;
        public uint quantize_positions;
        public uint layout;
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
        public uint occlusion_lights;  // format 4: mixed lights with occlusion probes (0-4)
        public uint leak_edges;        // probe pairs kept for leak control
        // Format 5.
        public uint layout;
        public uint sh_encoding;
        public uint quantized_positions;
        public uint hull_probes;
        public double position_step_x, position_step_y, position_step_z;
        public NativeSectionBytes section_bytes;
    }

    /// <summary>tp_store_info.section_bytes: bytes of each part of the blob, by TP_STORE_SECTION_*.</summary>
    [StructLayout(LayoutKind.Sequential)]
    internal struct NativeSectionBytes
    {
        public ulong header, positions, normals, sh, probe_source, input_remap, cells, grid, occlusion, leak_offsets,
                     leak_edges, padding, unused12, unused13, unused14, unused15;
    }

    /// <summary>tp_store_load_options: the largest file tp_store_load_file_ex reads.</summary>
    [StructLayout(LayoutKind.Sequential)]
    internal struct TpStoreLoadOptions
    {
        public uint struct_size;
        public ulong max_file_bytes;
    }

    /// <summary>tp_batch_options: flags (TP_BATCH_*); threads is deprecated and ignored (batches run on the caller's thread).</summary>
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

    /// <summary>tp_volume_layout: the format (TP_VOLUME_*) and byte strides of a probe volume (0 = packed).</summary>
    [StructLayout(LayoutKind.Sequential)]
    internal struct NativeVolumeLayout
    {
        public uint struct_size;
        public uint format;
        public UIntPtr point_stride;
        public UIntPtr row_stride;
        public UIntPtr slice_stride;
        public UIntPtr vector_stride;
    }

    /// <summary>tp_scene_load_options.</summary>
    [StructLayout(LayoutKind.Sequential)]
    internal struct NativeSceneLoadOptions
    {
        public uint struct_size;
        public uint up;
        public float scale;
    }

    /// <summary>tp_bake_options.</summary>
    [StructLayout(LayoutKind.Sequential)]
    internal struct NativeBakeOptions
    {
        public uint struct_size;
        public uint flags;
        public uint rays;
        public uint bounces;
        public ulong seed;
        public uint threads;
        public IntPtr progress;
        public IntPtr progress_user;
    }

    /// <summary>tp_effects_plan.</summary>
    [StructLayout(LayoutKind.Sequential)]
    internal struct NativeEffectsPlan
    {
        public uint struct_size;
        public uint lights;
        public uint direct_lights;
        public uint realtime_lights;
        public uint out_of_range_lights;
        public int sky;
        public uint emissive_meshes;
        public uint bounces;
        public int shadows;
        public uint meshes;
        public uint shadow_casters;
        public uint shadow_caster_candidates;
        public uint inside_probes;
    }

    /// <summary>tp_placement_options.</summary>
    [StructLayout(LayoutKind.Sequential)]
    internal struct NativePlacementOptions
    {
        public uint struct_size;
        public uint mode;
        public float spacing;
        public float margin;
        public float walk_min_height;
        public float walk_max_height;
        public uint target_count;
        public float error_bound;
        public uint rays;
        public uint bounces;
        public ulong seed;
        public uint threads;
        public IntPtr progress;
        public IntPtr progress_user;
        public float light_clearance;
    }

    internal static class NativeMethods
    {
        // The plugin's name: the full library by default; the run-time library (stores and queries only) in a
        // player built with TETPROBE_RUNTIME; statically linked into the player on iOS. The editor always loads
        // the full library, which it needs to bake.
#if UNITY_IOS && !UNITY_EDITOR
        public const string Library = "__Internal";
#elif TETPROBE_RUNTIME && !UNITY_EDITOR
        public const string Library = "tetprobe_runtime";
#else
        public const string Library = "tetprobe";
#endif

        public const uint BuildNoExtrapolation = 1;
        public const uint BuildIndex32 = 2;
        public const uint BuildCompact = 4;
        public const uint BatchChainHints = 1;
        public const uint CellOuter = 1;
        public const uint LightDirectional = 0;
        public const uint LightPoint = 1;
        public const uint LightSpot = 2;
        public const uint LightModeBaked = 0;
        public const uint LightModeRealtime = 1;
        public const uint LightModeMixed = 2;
        public const uint CellInner = 0;
        public const uint PlacementWhole = 0;
        public const uint PlacementWalkable = 1;
        public const uint InsideDrop = 0;
        public const uint InsidePush = 1;
        public const uint BakeNoCulling = 1;
        public const uint ShOrderL2 = 0;
        public const uint ShOrderL1 = 1;
        public const uint ShOrderZh3 = 2;
        public const uint ShWindowNone = 0;
        public const uint ShWindowSloan = 1;
        public const uint ShWindowNonnegative = 2;
        public const uint VolumeMaxSide = 32;
        public const uint VolumeShL2 = 0;
        public const uint VolumeShL1 = 1;
        public const uint VolumeUnityL1 = 2;
        public const uint VolumeUnityL2 = 3;

        [DllImport(Library, CallingConvention = CallingConvention.Cdecl)]
        public static extern uint tp_version();

        [DllImport(Library, CallingConvention = CallingConvention.Cdecl)]
        public static extern IntPtr tp_last_error();

        [DllImport(Library, CallingConvention = CallingConvention.Cdecl)]
        public static extern IntPtr tp_status_name(int status);

        [DllImport(Library, CallingConvention = CallingConvention.Cdecl)]
        public static extern int tp_build_options_init(ref NativeBuildOptions options);

        [DllImport(Library, CallingConvention = CallingConvention.Cdecl)]
        public static extern int tp_store_build([In] Vector3[] positions, UIntPtr position_stride,
            [In] SphericalHarmonicsL2[] sh, UIntPtr sh_stride, UIntPtr probe_count, ref NativeBuildOptions options,
            out StoreHandle store);

        [DllImport(Library, CallingConvention = CallingConvention.Cdecl)]
        public static extern int tp_store_load([In] byte[] data, UIntPtr size, out StoreHandle store);

        [DllImport(Library, CallingConvention = CallingConvention.Cdecl)]
        public static extern int tp_store_load_options_init(ref TpStoreLoadOptions options);

        [DllImport(Library, CallingConvention = CallingConvention.Cdecl)]
        public static extern int tp_store_load_file([In] byte[] path, out StoreHandle store);

        [DllImport(Library, CallingConvention = CallingConvention.Cdecl)]
        public static extern int tp_store_load_file_ex([In] byte[] path, ref TpStoreLoadOptions options,
            out StoreHandle store);

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
        public static extern int tp_store_interpolate_occlusion(StoreHandle store, ref Vector3 position, ref int cell_hint,
            out SphericalHarmonicsL2 sh, out Vector4 occlusion);

        [DllImport(Library, CallingConvention = CallingConvention.Cdecl)]
        public static extern int tp_store_interpolate_occlusion_batch(StoreHandle store, UIntPtr count,
            [In] Vector3[] positions, UIntPtr position_stride, [In, Out] int[] hints, UIntPtr hint_stride,
            [Out] SphericalHarmonicsL2[] sh, UIntPtr sh_stride, [Out] Vector4[] occlusion, UIntPtr occlusion_stride,
            ref TpBatchOptions options);

        [DllImport(Library, CallingConvention = CallingConvention.Cdecl)]
        public static extern int tp_volume_layout_init(ref NativeVolumeLayout layout);

        [DllImport(Library, CallingConvention = CallingConvention.Cdecl)]
        public static extern int tp_store_sample_volume(StoreHandle store, ref Vector3 origin, ref Vector3 cell_size,
            [In] uint[] dims, ref int cell_hint, ref NativeVolumeLayout layout, [Out] float[] output);

        [DllImport(Library, CallingConvention = CallingConvention.Cdecl)]
        public static extern int tp_sh_eval_radiance(ref SphericalHarmonicsL2 sh, ref Vector3 direction, out Vector3 rgb);

        [DllImport(Library, CallingConvention = CallingConvention.Cdecl)]
        public static extern int tp_sh_eval_irradiance(ref SphericalHarmonicsL2 sh, ref Vector3 normal, out Vector3 rgb);

        [DllImport(Library, CallingConvention = CallingConvention.Cdecl)]
        public static extern int tp_sh_add_ambient(ref SphericalHarmonicsL2 sh, ref Vector3 rgb);

        [DllImport(Library, CallingConvention = CallingConvention.Cdecl)]
        public static extern int tp_sh_add_directional(ref SphericalHarmonicsL2 sh, ref Vector3 direction, ref Vector3 rgb);

        [DllImport(Library, CallingConvention = CallingConvention.Cdecl)]
        public static extern int tp_sh_eval_options_init(out ShEvalOptions options);

        [DllImport(Library, CallingConvention = CallingConvention.Cdecl)]
        public static extern int tp_sh_eval_irradiance_ex(ref SphericalHarmonicsL2 sh, ref Vector3 normal,
            ref ShEvalOptions options, out Vector3 rgb);

        [DllImport(Library, CallingConvention = CallingConvention.Cdecl)]
        public static extern int tp_sh_apply_options(ref SphericalHarmonicsL2 sh, ref ShEvalOptions options);

        [DllImport(Library, CallingConvention = CallingConvention.Cdecl)]
        public static extern int tp_sh_min_irradiance(ref SphericalHarmonicsL2 sh, ref ShEvalOptions options,
            out Vector3 min_rgb, out Vector3 normal);

        [DllImport(Library, CallingConvention = CallingConvention.Cdecl)]
        public static extern int tp_sh_nonnegative_window_strength(ref SphericalHarmonicsL2 sh, ref ShEvalOptions options,
            out float strength);

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
#if TETPROBE_SPAN
        // Batch calls on spans: the first element by reference (pinned for the call), hints as a reference or
        // IntPtr.Zero for none. Only called with count > 0.
        [DllImport(Library, CallingConvention = CallingConvention.Cdecl)]
        public static extern int tp_store_interpolate_batch(StoreHandle store, UIntPtr count, ref Vector3 positions,
            UIntPtr position_stride, ref int hints, UIntPtr hint_stride, ref SphericalHarmonicsL2 sh, UIntPtr sh_stride,
            ref TpBatchOptions options);

        [DllImport(Library, CallingConvention = CallingConvention.Cdecl)]
        public static extern int tp_store_interpolate_batch(StoreHandle store, UIntPtr count, ref Vector3 positions,
            UIntPtr position_stride, IntPtr hints, UIntPtr hint_stride, ref SphericalHarmonicsL2 sh, UIntPtr sh_stride,
            ref TpBatchOptions options);

        [DllImport(Library, CallingConvention = CallingConvention.Cdecl)]
        public static extern int tp_store_weights_batch(StoreHandle store, UIntPtr count, ref Vector3 positions,
            UIntPtr position_stride, ref int hints, UIntPtr hint_stride, ref uint probes, UIntPtr probes_stride,
            ref float weights, UIntPtr weights_stride, ref TpBatchOptions options);

        [DllImport(Library, CallingConvention = CallingConvention.Cdecl)]
        public static extern int tp_store_weights_batch(StoreHandle store, UIntPtr count, ref Vector3 positions,
            UIntPtr position_stride, IntPtr hints, UIntPtr hint_stride, ref uint probes, UIntPtr probes_stride,
            ref float weights, UIntPtr weights_stride, ref TpBatchOptions options);

        [DllImport(Library, CallingConvention = CallingConvention.Cdecl)]
        public static extern int tp_store_interpolate_occlusion_batch(StoreHandle store, UIntPtr count, ref Vector3 positions,
            UIntPtr position_stride, ref int hints, UIntPtr hint_stride, ref SphericalHarmonicsL2 sh, UIntPtr sh_stride,
            ref Vector4 occlusion, UIntPtr occlusion_stride, ref TpBatchOptions options);

        [DllImport(Library, CallingConvention = CallingConvention.Cdecl)]
        public static extern int tp_store_interpolate_occlusion_batch(StoreHandle store, UIntPtr count, ref Vector3 positions,
            UIntPtr position_stride, IntPtr hints, UIntPtr hint_stride, ref SphericalHarmonicsL2 sh, UIntPtr sh_stride,
            ref Vector4 occlusion, UIntPtr occlusion_stride, ref TpBatchOptions options);
#endif

        [DllImport(Library, CallingConvention = CallingConvention.Cdecl)]
        public static extern int tp_material_init(out Material material);

        [DllImport(Library, CallingConvention = CallingConvention.Cdecl)]
        public static extern int tp_light_init(out Light light);

        [DllImport(Library, CallingConvention = CallingConvention.Cdecl)]
        public static extern int tp_scene_create(out SceneHandle scene);

        [DllImport(Library, CallingConvention = CallingConvention.Cdecl)]
        public static extern int tp_scene_release(IntPtr scene);

        [DllImport(Library, CallingConvention = CallingConvention.Cdecl)]
        public static extern int tp_scene_load_file([In] byte[] path, out SceneHandle scene);

        [DllImport(Library, CallingConvention = CallingConvention.Cdecl)]
        public static extern int tp_scene_load_options_init(ref NativeSceneLoadOptions options);

        [DllImport(Library, CallingConvention = CallingConvention.Cdecl)]
        public static extern int tp_scene_load_file_ex([In] byte[] path, ref NativeSceneLoadOptions options, out SceneHandle scene);

        [DllImport(Library, CallingConvention = CallingConvention.Cdecl)]
        public static extern int tp_scene_notes(SceneHandle scene, [Out] byte[] text, UIntPtr text_capacity, out UIntPtr size);

        [DllImport(Library, CallingConvention = CallingConvention.Cdecl)]
        public static extern int tp_scene_up(SceneHandle scene, out uint up);

        [DllImport(Library, CallingConvention = CallingConvention.Cdecl)]
        public static extern int tp_scene_set_up(SceneHandle scene, uint up);

        [DllImport(Library, CallingConvention = CallingConvention.Cdecl)]
        public static extern int tp_scene_add_mesh(SceneHandle scene, [In] Vector3[] vertices, UIntPtr vertex_count,
            [In] uint[] indices, UIntPtr triangle_count, [In] Material[] materials, UIntPtr material_count,
            [In] uint[] triangle_materials, out uint mesh);

        [DllImport(Library, CallingConvention = CallingConvention.Cdecl)]
        public static extern int tp_scene_add_light(SceneHandle scene, ref Light light, out uint id);

        [DllImport(Library, CallingConvention = CallingConvention.Cdecl)]
        public static extern int tp_scene_set_sky_color(SceneHandle scene, ref Vector3 rgb);

        [DllImport(Library, CallingConvention = CallingConvention.Cdecl)]
        public static extern int tp_scene_set_sky_sh(SceneHandle scene, ref SphericalHarmonicsL2 sh);

        [DllImport(Library, CallingConvention = CallingConvention.Cdecl)]
        public static extern int tp_scene_probes(SceneHandle scene, out IntPtr positions, out UIntPtr count);

        [DllImport(Library, CallingConvention = CallingConvention.Cdecl)]
        public static extern int tp_scene_set_probes(SceneHandle scene, [In] Vector3[] positions, UIntPtr count);

        [DllImport(Library, CallingConvention = CallingConvention.Cdecl)]
        public static extern int tp_scene_set_playable_seeds(SceneHandle scene, [In] Vector3[] positions, UIntPtr count);

        [DllImport(Library, CallingConvention = CallingConvention.Cdecl)]
        public static extern int tp_bake_options_init(ref NativeBakeOptions options);

        [DllImport(Library, CallingConvention = CallingConvention.Cdecl)]
        public static extern int tp_bake_plan(SceneHandle scene, [In] Vector3[] positions, UIntPtr position_stride,
            UIntPtr count, ref NativeBakeOptions options, ref NativeEffectsPlan plan, [Out] byte[] text,
            UIntPtr text_capacity);

        [DllImport(Library, CallingConvention = CallingConvention.Cdecl)]
        public static extern int tp_bake(SceneHandle scene, [In] Vector3[] positions, UIntPtr position_stride,
            UIntPtr count, ref NativeBakeOptions options, [Out] SphericalHarmonicsL2[] sh, UIntPtr sh_stride);

        [DllImport(Library, CallingConvention = CallingConvention.Cdecl)]
        public static extern int tp_bake_occlusion(SceneHandle scene, [In] Vector3[] positions, UIntPtr position_stride,
            UIntPtr count, ref NativeBakeOptions options, [Out] ProbeOcclusion[] occlusion, UIntPtr occlusion_stride,
            out uint mixed_lights);

        [DllImport(Library, CallingConvention = CallingConvention.Cdecl)]
        public static extern int tp_placement_options_init(ref NativePlacementOptions options);

        [DllImport(Library, CallingConvention = CallingConvention.Cdecl)]
        public static extern int tp_place_probes_bound(SceneHandle scene, ref NativePlacementOptions options, out UIntPtr bound);

        [DllImport(Library, CallingConvention = CallingConvention.Cdecl)]
        public static extern int tp_place_probes(SceneHandle scene, ref NativePlacementOptions options,
            [Out] Vector3[] positions, UIntPtr capacity, out UIntPtr count, [Out] float[] error_curve, UIntPtr curve_capacity,
            out UIntPtr curve_points);

        [DllImport(Library, CallingConvention = CallingConvention.Cdecl)]
        public static extern int tp_find_inside_probes(SceneHandle scene, [In] Vector3[] positions, UIntPtr position_stride,
            UIntPtr count, [Out] uint[] indices, UIntPtr capacity, out UIntPtr found);

        [DllImport(Library, CallingConvention = CallingConvention.Cdecl)]
        public static extern int tp_fix_inside_probes(SceneHandle scene, [In] Vector3[] positions, UIntPtr position_stride,
            UIntPtr count, uint mode, float margin, [Out] Vector3[] fixed_positions, UIntPtr capacity, out UIntPtr fixed_count);
    }
}
