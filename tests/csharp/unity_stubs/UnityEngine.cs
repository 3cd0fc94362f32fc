// Small stand-ins of the UnityEngine types the binding and samples/unity use, so that they compile and run under
// mono without Unity. Same names, members and layouts as Unity's (Vector3 is 3 floats, blittable); behaviour only as
// much as the tests need. Scene objects register themselves so that Object.FindObjectsOfType finds them.
using System;
using System.Collections.Generic;
using System.Linq;
using System.Runtime.InteropServices;

namespace UnityEngine
{
    [StructLayout(LayoutKind.Sequential)]
    public struct Vector3 : IEquatable<Vector3>
    {
        public float x, y, z;
        public Vector3(float x, float y, float z) { this.x = x; this.y = y; this.z = z; }
        public static Vector3 zero { get { return new Vector3(0, 0, 0); } }
        public static Vector3 up { get { return new Vector3(0, 1, 0); } }
        public float magnitude { get { return (float)Math.Sqrt(x * x + y * y + z * z); } }
        public Vector3 normalized { get { float m = magnitude; return new Vector3(x / m, y / m, z / m); } }
        public static Vector3 operator +(Vector3 a, Vector3 b) { return new Vector3(a.x + b.x, a.y + b.y, a.z + b.z); }
        public static Vector3 operator -(Vector3 a, Vector3 b) { return new Vector3(a.x - b.x, a.y - b.y, a.z - b.z); }
        public static Vector3 operator -(Vector3 a) { return new Vector3(-a.x, -a.y, -a.z); }
        public static Vector3 operator *(Vector3 a, float s) { return new Vector3(a.x * s, a.y * s, a.z * s); }
        public static float Dot(Vector3 a, Vector3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
        public bool Equals(Vector3 o) { return x == o.x && y == o.y && z == o.z; }
        public override bool Equals(object o) { return o is Vector3 && Equals((Vector3)o); }
        public override int GetHashCode() { return x.GetHashCode() ^ y.GetHashCode() << 2 ^ z.GetHashCode() >> 2; }
        public override string ToString() { return "(" + x + ", " + y + ", " + z + ")"; }
    }

    [StructLayout(LayoutKind.Sequential)]
    public struct Vector4
    {
        public float x, y, z, w;
        public Vector4(float x, float y, float z, float w) { this.x = x; this.y = y; this.z = z; this.w = w; }
        public override string ToString() { return "(" + x + ", " + y + ", " + z + ", " + w + ")"; }
    }

    public struct Color
    {
        public float r, g, b, a;
        public Color(float r, float g, float b, float a = 1) { this.r = r; this.g = g; this.b = b; this.a = a; }
        public static Color white { get { return new Color(1, 1, 1); } }
        public static Color black { get { return new Color(0, 0, 0); } }
        /// <summary>sRGB to linear, as Unity's Color.linear.</summary>
        public Color linear { get { return new Color(ToLinear(r), ToLinear(g), ToLinear(b), a); } }
        static float ToLinear(float c)
        {
            return c <= 0.04045f ? c / 12.92f : (float)Math.Pow((c + 0.055) / 1.055, 2.4);
        }
        public static Color operator *(Color c, float s) { return new Color(c.r * s, c.g * s, c.b * s, c.a * s); }
    }

    public struct Bounds
    {
        public Vector3 center;
        public Vector3 size;
    }

    public class Object
    {
        static readonly List<Object> Live = new List<Object>();
        public string name = "";
        protected Object() { Live.Add(this); }
        public static T[] FindObjectsOfType<T>() where T : Object { return Live.OfType<T>().ToArray(); }
        public static void DestroyImmediate(Object o) { Live.Remove(o); }
        public static void Destroy(Object o) { Live.Remove(o); }
        /// <summary>Stub only: forgets every object (between tests).</summary>
        public static void ResetStubScene() { Live.Clear(); }
    }

    public class GameObject : Object
    {
        readonly List<Component> components = new List<Component>();
        public Transform transform { get; private set; }
        public GameObject(string name) { this.name = name; transform = AddComponent<Transform>(); }
        public T AddComponent<T>() where T : Component, new()
        {
            var component = new T();
            component.Attach(this);
            components.Add(component);
            return component;
        }
        public T GetComponent<T>() where T : Component { return components.OfType<T>().FirstOrDefault(); }
        public T[] GetComponentsInChildren<T>() where T : Component { return components.OfType<T>().ToArray(); }
    }

    public class Component : Object
    {
        public GameObject gameObject { get; private set; }
        public Transform transform { get { return gameObject.transform; } }
        internal void Attach(GameObject owner) { gameObject = owner; }
        public T GetComponent<T>() where T : Component { return gameObject.GetComponent<T>(); }
        public T[] GetComponentsInChildren<T>() where T : Component { return gameObject.GetComponentsInChildren<T>(); }
    }

    /// <summary>Translation only: enough for the tests' scenes.</summary>
    public class Transform : Component
    {
        public Vector3 position;
        /// <summary>The direction the object faces (a light's travel direction).</summary>
        public Vector3 forward = new Vector3(0, 0, 1);
        public Vector3 TransformPoint(Vector3 local) { return local + position; }
    }

    public class Behaviour : Component
    {
        public bool enabled = true;
    }

    public class MonoBehaviour : Behaviour { }

    public class Renderer : Component
    {
        public Bounds bounds;
        public Transform probeAnchor;
        public Material sharedMaterial;
        public Rendering.LightProbeUsage lightProbeUsage = Rendering.LightProbeUsage.BlendProbes;
        MaterialPropertyBlock block = new MaterialPropertyBlock();
        public void GetPropertyBlock(MaterialPropertyBlock into) { into.CopyFrom(block); }
        /// <summary>As Unity's: null clears the renderer's block.</summary>
        public void SetPropertyBlock(MaterialPropertyBlock from)
        {
            block = new MaterialPropertyBlock();
            if (from != null) block.CopyFrom(from);
        }
    }

    public class MeshRenderer : Renderer { }

    public class MeshFilter : Component
    {
        public Mesh sharedMesh;
    }

    public class Mesh : Object
    {
        public Vector3[] vertices = new Vector3[0];
        public int[] triangles = new int[0];
    }

    public class Material : Object
    {
        public Color color = Color.white;
        readonly Dictionary<string, Color> colors = new Dictionary<string, Color>();
        readonly HashSet<string> keywords = new HashSet<string>();
        public bool HasProperty(string property) { return property == "_Color" || colors.ContainsKey(property); }
        public Color GetColor(string property) { return property == "_Color" ? color : colors[property]; }
        public void SetColor(string property, Color value) { if (property == "_Color") color = value; else colors[property] = value; }
        public bool IsKeywordEnabled(string keyword) { return keywords.Contains(keyword); }
        public void EnableKeyword(string keyword) { keywords.Add(keyword); }
    }

    public class MaterialPropertyBlock
    {
        readonly Dictionary<string, Vector4[]> arrays = new Dictionary<string, Vector4[]>();
        internal void CopyFrom(MaterialPropertyBlock other)
        {
            arrays.Clear();
            foreach (var pair in other.arrays) arrays[pair.Key] = (Vector4[])pair.Value.Clone();
            vectors.Clear();
            foreach (var pair in other.vectors) vectors[pair.Key] = pair.Value;
            textures.Clear();
            foreach (var pair in other.textures) textures[pair.Key] = pair.Value;
        }
        readonly Dictionary<string, Vector4> vectors = new Dictionary<string, Vector4>();
        readonly Dictionary<string, Texture> textures = new Dictionary<string, Texture>();
        public void Clear() { arrays.Clear(); vectors.Clear(); textures.Clear(); }
        public void SetVector(string name, Vector4 value) { vectors[name] = value; }
        public Vector4 GetVector(string name) { Vector4 value; return vectors.TryGetValue(name, out value) ? value : new Vector4(0, 0, 0, 0); }
        public void SetTexture(string name, Texture value) { textures[name] = value; }
        public Texture GetTexture(string name) { Texture value; return textures.TryGetValue(name, out value) ? value : null; }
        public void SetVectorArray(string name, Vector4[] values) { arrays[name] = (Vector4[])values.Clone(); }
        public Vector4[] GetVectorArray(string name) { Vector4[] values; return arrays.TryGetValue(name, out values) ? values : null; }

        static readonly string[] ShNames = { "unity_SHAr", "unity_SHAg", "unity_SHAb", "unity_SHBr", "unity_SHBg", "unity_SHBb", "unity_SHC" };

        /// <summary>As Unity's: the shader constants of each SH (one array element per instance), packed as Unity packs
        /// its SphericalHarmonicsL2 for the built-in shaders.</summary>
        public void CopySHCoefficientArraysFrom(Rendering.SphericalHarmonicsL2[] lightProbes)
        {
            var packed = new Vector4[7][];
            for (int k = 0; k < 7; ++k) packed[k] = new Vector4[lightProbes.Length];
            for (int p = 0; p < lightProbes.Length; ++p)
            {
                Rendering.SphericalHarmonicsL2 u = lightProbes[p];
                for (int c = 0; c < 3; ++c)
                {
                    packed[c][p] = new Vector4(u[c, 3], u[c, 1], u[c, 2], u[c, 0] - u[c, 6]);
                    packed[3 + c][p] = new Vector4(u[c, 4], u[c, 5], u[c, 6] * 3, u[c, 7]);
                }
                packed[6][p] = new Vector4(u[0, 8], u[1, 8], u[2, 8], 1);
            }
            for (int k = 0; k < 7; ++k) arrays[ShNames[k]] = packed[k];
        }
    }

    public enum TextureFormat { RGBAFloat = 20, RGBAHalf = 17 }
    public enum TextureWrapMode { Repeat = 0, Clamp = 1 }
    public enum FilterMode { Point = 0, Bilinear = 1, Trilinear = 2 }

    public class Texture : Object
    {
        public TextureWrapMode wrapMode;
        public FilterMode filterMode;
    }

    /// <summary>As Unity's, keeping the texel data it was given (floats for RGBAFloat, half bits for RGBAHalf).</summary>
    public class Texture3D : Texture
    {
        public readonly int width, height, depth;
        public readonly TextureFormat format;
        public Array PixelData;
        public int Applied;
        public Texture3D(int width, int height, int depth, TextureFormat format, bool mipChain)
        {
            this.width = width; this.height = height; this.depth = depth; this.format = format;
        }
        public void SetPixelData<T>(T[] data, int mipLevel, int sourceDataStartIndex = 0)
        {
            int texel = format == TextureFormat.RGBAFloat ? 16 : 8;
            if (mipLevel != 0 || System.Runtime.InteropServices.Marshal.SizeOf(typeof(T)) * (data.Length - sourceDataStartIndex) !=
                texel * width * height * depth)
                throw new ArgumentException("SetPixelData: the data does not fill the texture");
            PixelData = (T[])data.Clone();
        }
        public void Apply(bool updateMipmaps) { ++Applied; }
    }

    public static class Mathf
    {
        /// <summary>As Unity's: IEEE binary16 bits of value, rounded to nearest even.</summary>
        public static ushort FloatToHalf(float value)
        {
            uint bits = BitConverter.ToUInt32(BitConverter.GetBytes(value), 0);
            uint sign = (bits >> 16) & 0x8000u;
            int exponent = (int)((bits >> 23) & 0xFF) - 127 + 15;
            uint mantissa = bits & 0x7FFFFFu;
            if (((bits >> 23) & 0xFF) == 0xFF) return (ushort)(sign | 0x7C00u | (mantissa != 0 ? 0x200u : 0));
            if (exponent >= 31) return (ushort)(sign | 0x7C00u);
            if (exponent <= 0)
            {
                if (exponent < -10) return (ushort)sign;
                mantissa |= 0x800000u;
                int shift = 14 - exponent;
                uint half = mantissa >> shift, rest = mantissa & ((1u << shift) - 1), midpoint = 1u << (shift - 1);
                if (rest > midpoint || (rest == midpoint && (half & 1) != 0)) ++half;
                return (ushort)(sign | half);
            }
            uint h = sign | ((uint)exponent << 10) | (mantissa >> 13);
            uint r = mantissa & 0x1FFFu;
            if (r > 0x1000u || (r == 0x1000u && (h & 1) != 0)) ++h;
            return (ushort)h;
        }
    }

    public class TextAsset : Object
    {
        readonly byte[] data;
        public TextAsset(byte[] data) { this.data = data; }
        public byte[] bytes { get { return (byte[])data.Clone(); } }
    }

    public class LightProbeGroup : Behaviour
    {
        public Vector3[] probePositions = new Vector3[0];
    }

    public enum LightType { Spot = 0, Directional = 1, Point = 2 }

    public enum LightShadows { None = 0, Hard = 1, Soft = 2 }

    public enum LightmapBakeType { Realtime = 4, Baked = 2, Mixed = 1 }

    public class Light : Behaviour
    {
        public LightType type = LightType.Point;
        public Color color = Color.white;
        public float intensity = 1;
        public float range = 10;
        public float spotAngle = 30;
        public float innerSpotAngle = 21.8f;
        public LightShadows shadows = LightShadows.None;
        public LightmapBakeType lightmapBakeType = LightmapBakeType.Baked;
    }

    public static class RenderSettings
    {
        public static Rendering.SphericalHarmonicsL2 ambientProbe;
    }

    public static class Debug
    {
        public static readonly List<string> Logged = new List<string>();
        public static void Log(object message) { Logged.Add(message.ToString()); }
        public static void LogError(object message) { Logged.Add("error: " + message); }
    }

    [AttributeUsage(AttributeTargets.Field)]
    public sealed class TooltipAttribute : Attribute
    {
        public TooltipAttribute(string tooltip) { }
    }

    [AttributeUsage(AttributeTargets.Class)]
    public sealed class DisallowMultipleComponentAttribute : Attribute { }
}

namespace UnityEngine.SceneManagement
{
    public struct Scene
    {
        public string path;
        public string name;
    }

    public static class SceneManager
    {
        public static Scene active;
        public static Scene GetActiveScene() { return active; }
    }
}
