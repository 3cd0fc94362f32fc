// Light: tp_light as a blittable struct, made by one static constructor per light type.
using System;
using System.Runtime.InteropServices;
#if UNITY_5_3_OR_NEWER
using Vector3 = UnityEngine.Vector3;
#endif

namespace TetProbe
{
    /// <summary>The kinds of tp_light (TP_LIGHT_*).</summary>
    public enum LightType
    {
        Directional = 0,
        Point = 1,
        Spot = 2,
    }

    /// <summary>What the bake keeps of a light (TP_LIGHT_MODE_*).</summary>
    public enum LightMode
    {
        /// <summary>Direct and bounced light go into the probes.</summary>
        Baked = 0,
        /// <summary>The engine draws the direct light; only its bounced light is baked.</summary>
        Realtime = 1,
        /// <summary>Unity's Shadowmask: baked as Realtime (bounced light only), plus each probe's visibility of the light
        /// (Baker.BakeOcclusion, occlusion probes). At most four per scene.</summary>
        Mixed = 2,
    }

    /// <summary>A light of a bake scene. Directional intensity is the irradiance on a surface facing the light; point
    /// and spot intensity is radiant intensity (irradiance intensity/d² at distance d).</summary>
    [StructLayout(LayoutKind.Sequential)]
    public struct Light
    {
        uint structSize;
        uint type;
        uint mode;
        int shadows;
        /// <summary>Colour per channel (multiplies Intensity).</summary>
        public Vector3 Color;
        public float Intensity;
        /// <summary>Point and spot lights: where the light is.</summary>
        public Vector3 Position;
        /// <summary>Directional and spot lights: the direction the light travels.</summary>
        public Vector3 Direction;
        /// <summary>Point and spot lights: no light beyond this distance (infinity = unlimited).</summary>
        public float Range;
        /// <summary>Spot lights: full cone angle in degrees lit at full intensity.</summary>
        public float InnerAngle;
        /// <summary>Spot lights: full cone angle in degrees beyond which there is no light.</summary>
        public float OuterAngle;
        /// <summary>Point and spot lights: closer than this the irradiance stays at its value at this distance
        /// instead of growing without bound (0 = pure inverse square; a light compiler's near-field clamp).</summary>
        public float NearDistance;

        public LightType Type { get { return (LightType)type; } set { type = (uint)value; } }
        public LightMode Mode { get { return (LightMode)mode; } set { mode = (uint)value; } }
        /// <summary>True: the light casts shadows.</summary>
        public bool Shadows { get { return shadows != 0; } set { shadows = value ? 1 : 0; } }

        static Light Make(LightType type, Vector3 color, float intensity, LightMode mode, bool shadows)
        {
            NativeProxy.EnsureVersion();
            Light light;
            NativeProxy.Check(NativeMethods.tp_light_init(out light));
            light.Type = type;
            light.Color = color;
            light.Intensity = intensity;
            light.Mode = mode;
            light.Shadows = shadows;
            return light;
        }

        /// <summary>A sun travelling along `direction`; intensity is the irradiance on a surface facing it.</summary>
        public static Light Directional(Vector3 direction, Vector3 color, float intensity = 1,
                                        LightMode mode = LightMode.Baked, bool shadows = true)
        {
            Light light = Make(LightType.Directional, color, intensity, mode, shadows);
            light.Direction = direction;
            return light;
        }

        /// <summary>A point light; intensity is radiant intensity (irradiance intensity/d² at distance d), held at its
        /// value at nearDistance closer than that (0 = none).</summary>
        public static Light Point(Vector3 position, Vector3 color, float intensity = 1, float range = float.PositiveInfinity,
                                  LightMode mode = LightMode.Baked, bool shadows = true, float nearDistance = 0)
        {
            Light light = Make(LightType.Point, color, intensity, mode, shadows);
            light.Position = position;
            light.Range = range;
            light.NearDistance = nearDistance;
            return light;
        }

        /// <summary>A spot light at position shining along direction; cone angles are full angles in degrees.</summary>
        public static Light Spot(Vector3 position, Vector3 direction, Vector3 color, float intensity, float range,
                                 float innerAngle, float outerAngle, LightMode mode = LightMode.Baked, bool shadows = true,
                                 float nearDistance = 0)
        {
            Light light = Make(LightType.Spot, color, intensity, mode, shadows);
            light.NearDistance = nearDistance;
            light.Position = position;
            light.Direction = direction;
            light.Range = range;
            light.InnerAngle = innerAngle;
            light.OuterAngle = outerAngle;
            return light;
        }

        internal Light Sized()
        {
            Light copy = this;
            copy.structSize = (uint)Marshal.SizeOf(typeof(Light));
            return copy;
        }
    }
}
