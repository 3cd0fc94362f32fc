// Layer 2 for scenes and the bake: statuses into exceptions, progress and cancellation, the plan's text.
using System;
using System.Runtime.InteropServices;
using System.Text;
using System.Threading;
#if UNITY_5_3_OR_NEWER
using Vector3 = UnityEngine.Vector3;
#endif

namespace TetProbe
{
    internal static partial class NativeProxy
    {
        public static SceneHandle CreateScene()
        {
            EnsureVersion();
            SceneHandle scene;
            Check(NativeMethods.tp_scene_create(out scene));
            return scene;
        }

        public static SceneHandle LoadScene(string path)
        {
            EnsureVersion();
            SceneHandle scene;
            Check(NativeMethods.tp_scene_load_file(Utf8Path(path), out scene));
            return scene;
        }

        public static SceneHandle LoadScene(string path, NativeSceneLoadOptions options)
        {
            EnsureVersion();
            SceneHandle scene;
            Check(NativeMethods.tp_scene_load_file_ex(Utf8Path(path), ref options, out scene));
            return scene;
        }

        public static NativeSceneLoadOptions DefaultSceneLoadOptions()
        {
            EnsureVersion();
            var options = new NativeSceneLoadOptions();
            Check(NativeMethods.tp_scene_load_options_init(ref options));
            return options;
        }

        /// <summary>tp_scene_notes: the size first, then the text, split into lines.</summary>
        public static string[] Notes(SceneHandle scene)
        {
            UIntPtr size;
            Check(NativeMethods.tp_scene_notes(scene, null, UIntPtr.Zero, out size));
            var buffer = new byte[(int)size];
            Check(NativeMethods.tp_scene_notes(scene, buffer, size, out size));
            string text = Encoding.UTF8.GetString(buffer, 0, Math.Max(0, (int)size - 1));
            return text.Split(new[] { '\n' }, StringSplitOptions.RemoveEmptyEntries);
        }

        public static UpAxis Up(SceneHandle scene)
        {
            uint up;
            Check(NativeMethods.tp_scene_up(scene, out up));
            return (UpAxis)up;
        }

        public static void SetUp(SceneHandle scene, UpAxis up)
        {
            Check(NativeMethods.tp_scene_set_up(scene, (uint)up));
        }

        public static int AddMesh(SceneHandle scene, Vector3[] vertices, uint[] indices, Material[] materials,
                                  uint[] triangleMaterials)
        {
            uint mesh;
            Check(NativeMethods.tp_scene_add_mesh(scene, vertices, (UIntPtr)vertices.Length, indices,
                (UIntPtr)(indices.Length / 3), materials, (UIntPtr)materials.Length, triangleMaterials, out mesh));
            return (int)mesh;
        }

        public static int AddLight(SceneHandle scene, Light light)
        {
            uint id;
            Check(NativeMethods.tp_scene_add_light(scene, ref light, out id));
            return (int)id;
        }

        public static void SetSky(SceneHandle scene, Vector3 rgb)
        {
            Check(NativeMethods.tp_scene_set_sky_color(scene, ref rgb));
        }

        public static void SetSky(SceneHandle scene, SphericalHarmonicsL2 sh)
        {
            Check(NativeMethods.tp_scene_set_sky_sh(scene, ref sh));
        }

        /// <summary>The scene's probes, copied. tp_scene_probes points into the scene: the handle stays referenced until
        /// the copy is done, so a Dispose on another thread meanwhile defers the release instead of freeing what is read.
        /// </summary>
        public static Vector3[] Probes(SceneHandle scene)
        {
            bool referenced = false;
            var floats = new float[0];
            try
            {
                scene.DangerousAddRef(ref referenced);
                IntPtr data;
                UIntPtr count;
                Check(NativeMethods.tp_scene_probes(scene, out data, out count));
                if (BeforeBorrowedCopy != null) BeforeBorrowedCopy(scene);
                floats = new float[3 * (long)count.ToUInt64()];
                if (floats.Length > 0) Marshal.Copy(data, floats, 0, floats.Length);
            }
            finally
            {
                if (referenced) scene.DangerousRelease();
            }
            var probes = new Vector3[floats.Length / 3];
            for (int i = 0; i < probes.Length; ++i) probes[i] = new Vector3(floats[3 * i], floats[3 * i + 1], floats[3 * i + 2]);
            return probes;
        }

        public static void SetProbes(SceneHandle scene, Vector3[] positions)
        {
            Check(NativeMethods.tp_scene_set_probes(scene, positions, (UIntPtr)positions.Length));
        }

        public static void SetPlayableSeeds(SceneHandle scene, Vector3[] positions)
        {
            Check(NativeMethods.tp_scene_set_playable_seeds(scene, positions, (UIntPtr)positions.Length));
        }

        public static NativeBakeOptions DefaultBakeOptions()
        {
            EnsureVersion();
            var options = new NativeBakeOptions();
            Check(NativeMethods.tp_bake_options_init(ref options));
            return options;
        }

        /// <summary>tp_bake_plan with a text buffer grown until the summary fits.</summary>
        public static NativeEffectsPlan Plan(SceneHandle scene, Vector3[] positions, NativeBakeOptions options, out string text)
        {
            var plan = new NativeEffectsPlan();
            plan.struct_size = (uint)Marshal.SizeOf(typeof(NativeEffectsPlan));
            for (int capacity = 256; ; capacity *= 2)
            {
                var buffer = new byte[capacity];
                int status = NativeMethods.tp_bake_plan(scene, positions, PositionStride, (UIntPtr)positions.Length, ref options,
                    ref plan, buffer, (UIntPtr)capacity);
                if (status == (int)TetProbeStatus.BufferTooSmall && capacity < (1 << 20)) continue;
                Check(status);
                int length = Array.IndexOf(buffer, (byte)0);
                text = Encoding.UTF8.GetString(buffer, 0, length < 0 ? buffer.Length : length);
                return plan;
            }
        }

        public static SphericalHarmonicsL2[] Bake(SceneHandle scene, Vector3[] positions, NativeBakeOptions options,
                                                  IProgress<float> progress, CancellationToken cancel)
        {
            var result = new SphericalHarmonicsL2[positions.Length];
            using (var bridge = ProgressBridge.Start(progress, cancel))
            {
                options.progress = bridge.Callback;
                options.progress_user = bridge.User;
                int status = NativeMethods.tp_bake(scene, positions, PositionStride, (UIntPtr)positions.Length, ref options,
                    result, ShStride);
                bridge.Finish(status);
            }
            return result;
        }

        /// <summary>tp_bake_occlusion: 4 bytes per position; mixedLights receives the scene's mixed light count.</summary>
        public static ProbeOcclusion[] BakeOcclusion(SceneHandle scene, Vector3[] positions, NativeBakeOptions options,
                                                     IProgress<float> progress, CancellationToken cancel, out int mixedLights)
        {
            var result = new ProbeOcclusion[positions.Length];
            using (var bridge = ProgressBridge.Start(progress, cancel))
            {
                options.progress = bridge.Callback;
                options.progress_user = bridge.User;
                uint lights;
                int status = NativeMethods.tp_bake_occlusion(scene, positions, PositionStride, (UIntPtr)positions.Length,
                    ref options, result, (UIntPtr)4, out lights);
                bridge.Finish(status);
                mixedLights = (int)lights;
            }
            return result;
        }
    }
}
