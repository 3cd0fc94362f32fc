// Layer 3: Scene, what the bake sees (triangle meshes with materials, lights, a sky, probe positions).
using System;
#if UNITY_5_3_OR_NEWER
using Vector3 = UnityEngine.Vector3;
#endif

namespace TetProbe
{
    /// <summary>Which way is up (TP_UP_*). File: what the file says (load options only).</summary>
    public enum UpAxis
    {
        File = 0,
        PosX = 1,
        NegX = 2,
        PosY = 3,
        NegY = 4,
        PosZ = 5,
        NegZ = 6,
    }

    /// <summary>How Scene.Load reads a file (tp_scene_load_options); a new instance holds the library's defaults.</summary>
    public sealed class SceneLoadOptions
    {
        /// <summary>World units per unit of the file; 0 = the file's own unit in metres (glTF and OBJ 1, FBX its
        /// UnitScaleFactor / 100). Point and spot intensities scale by the square of world units per metre.</summary>
        public float Scale;
        /// <summary>Which way is up in the file; File = what the file says (glTF and OBJ +y, FBX its UpAxis, a JSON scene
        /// its "up"). Coordinates are kept; the scene records it (Scene.Up).</summary>
        public UpAxis Up;

        public SceneLoadOptions()
        {
            NativeSceneLoadOptions defaults = NativeProxy.DefaultSceneLoadOptions();
            Scale = defaults.scale;
            Up = (UpAxis)defaults.up;
        }

        internal NativeSceneLoadOptions ToNative()
        {
            if (!(Scale >= 0) || float.IsInfinity(Scale))
                throw new ArgumentOutOfRangeException("Scale", Scale, "Scale must be 0 (the file's unit) or a finite number > 0");
            NativeSceneLoadOptions options = NativeProxy.DefaultSceneLoadOptions();
            options.scale = Scale;
            options.up = (uint)Up;
            return options;
        }
    }

    /// <summary>A bake scene over a native tp_scene. Needs the full library (the run-time library refuses every scene
    /// call with TetProbeStatus.Unsupported).</summary>
    public sealed class Scene : IDisposable
    {
        readonly SceneHandle handle;

        /// <summary>An empty scene: no meshes, no lights, a black sky.</summary>
        public Scene() : this(NativeProxy.CreateScene()) { }

        Scene(SceneHandle handle)
        {
            this.handle = handle;
        }

        /// <summary>Reads a scene file: glTF 2.0 (.gltf, .glb), FBX, OBJ (with its .mtl) or a JSON scene
        /// (docs/scene-format.md), in the file's own unit (as metres) and up.</summary>
        public static Scene Load(string path)
        {
            return new Scene(NativeProxy.LoadScene(path));
        }

        /// <summary>Reads a scene file with the unit and up given in options (null: the file's own). What the file holds
        /// that a bake cannot use (cameras, textures, animations, area lights) is listed in Notes; an invalid file throws
        /// TetProbeException with TetProbeStatus.Scene naming the file and what is wrong.</summary>
        public static Scene Load(string path, SceneLoadOptions options)
        {
            return new Scene(NativeProxy.LoadScene(path, (options ?? new SceneLoadOptions()).ToNative()));
        }

        /// <summary>What loading the scene left out or converted, one note each (empty for a scene built in code).</summary>
        public string[] Notes
        {
            get { return NativeProxy.Notes(Live()); }
        }

        /// <summary>Which way is up in the scene (PosY unless loaded or set otherwise); placement's walkable mode stands
        /// probes on floors along it. UpAxis.File is refused.</summary>
        public UpAxis Up
        {
            get { return NativeProxy.Up(Live()); }
            set { NativeProxy.SetUp(Live(), value); }
        }

        /// <summary>Adds a mesh of triangles indices[3 t .. 3 t + 2] over vertices, all of one material; returns its id.</summary>
        public int AddMesh(Vector3[] vertices, int[] indices, Material material)
        {
            return AddMesh(vertices, indices, new[] { material }, null);
        }

        /// <summary>Adds a mesh whose triangle t uses materials[triangleMaterials[t]] (triangleMaterials null: all use
        /// materials[0]); returns its id.</summary>
        public int AddMesh(Vector3[] vertices, int[] indices, Material[] materials, int[] triangleMaterials)
        {
            if (vertices == null) throw new ArgumentNullException("vertices");
            if (indices == null) throw new ArgumentNullException("indices");
            if (materials == null) throw new ArgumentNullException("materials");
            if (indices.Length % 3 != 0)
                throw new ArgumentException("indices holds " + indices.Length + " values, not 3 per triangle", "indices");
            if (materials.Length == 0) throw new ArgumentException("materials is empty", "materials");
            if (triangleMaterials != null && triangleMaterials.Length != indices.Length / 3)
                throw new ArgumentException("triangleMaterials holds " + triangleMaterials.Length + " for " + indices.Length / 3 +
                                            " triangles", "triangleMaterials");
            var sized = new Material[materials.Length];
            for (int i = 0; i < materials.Length; ++i) sized[i] = materials[i].Sized();
            return NativeProxy.AddMesh(Live(), vertices, Unsigned(indices, "indices"), sized,
                                       triangleMaterials == null ? null : Unsigned(triangleMaterials, "triangleMaterials"));
        }

        static uint[] Unsigned(int[] values, string name)
        {
            var result = new uint[values.Length];
            for (int i = 0; i < values.Length; ++i)
            {
                if (values[i] < 0) throw new ArgumentOutOfRangeException(name, values[i], name + "[" + i + "] is negative");
                result[i] = (uint)values[i];
            }
            return result;
        }

        /// <summary>Adds a light (made by Light.Directional, Light.Point or Light.Spot); returns its id.</summary>
        public int AddLight(Light light)
        {
            return NativeProxy.AddLight(Live(), light.Sized());
        }

        /// <summary>A sky of constant radiance (r, g, b).</summary>
        public void SetSky(Vector3 rgb)
        {
            NativeProxy.SetSky(Live(), rgb);
        }

        /// <summary>A sky whose radiance is the SH `sh` (the contract of capi/tetprobe.h, not Unity's convention).</summary>
        public void SetSky(SphericalHarmonicsL2 sh)
        {
            NativeProxy.SetSky(Live(), sh);
        }

        /// <summary>The scene's probe positions (from its file, or set here); copies in and out.</summary>
        public Vector3[] Probes
        {
            get { return NativeProxy.Probes(Live()); }
            set
            {
                if (value == null) throw new ArgumentNullException("value");
                NativeProxy.SetProbes(Live(), value);
            }
        }

        /// <summary>Points known to be where objects go (spawn points; copied, an empty array clears them): placement
        /// then keeps only candidates connected to one. A Quake 3 level loaded from its file has its spawn points.</summary>
        public void SetPlayableSeeds(Vector3[] positions)
        {
            if (positions == null) throw new ArgumentNullException("positions");
            NativeProxy.SetPlayableSeeds(Live(), positions);
        }

        internal SceneHandle Live()
        {
            if (handle.IsClosed) throw new ObjectDisposedException("Scene");
            return handle;
        }

        public void Dispose()
        {
            handle.Dispose();
        }
    }
}
