// Occlusion probes (Unity's Shadowmask): per probe, the visibility of each of up to four mixed lights as a byte.
using System;
using System.Runtime.InteropServices;

namespace TetProbe
{
    /// <summary>One probe's occlusion: byte i = round(255 x the visibility of the scene's i-th mixed light), 255 for
    /// channels without a light (the 4 bytes of tp_bake_occlusion per probe).</summary>
    [StructLayout(LayoutKind.Sequential)]
    public struct ProbeOcclusion
    {
        public byte Light0, Light1, Light2, Light3;

        /// <summary>The byte of mixed light `light` (0 to 3).</summary>
        public byte this[int light]
        {
            get
            {
                switch (light)
                {
                    case 0: return Light0;
                    case 1: return Light1;
                    case 2: return Light2;
                    case 3: return Light3;
                    default: throw new IndexOutOfRangeException("light " + light + " is not in 0..3");
                }
            }
            set
            {
                switch (light)
                {
                    case 0: Light0 = value; break;
                    case 1: Light1 = value; break;
                    case 2: Light2 = value; break;
                    case 3: Light3 = value; break;
                    default: throw new IndexOutOfRangeException("light " + light + " is not in 0..3");
                }
            }
        }

        /// <summary>The visibility of mixed light `light` in [0, 1].</summary>
        public float Visibility(int light)
        {
            return this[light] / 255f;
        }
    }

    /// <summary>The occlusion probes of a bake (Baker.BakeOcclusion): one ProbeOcclusion per position and the count of
    /// mixed lights they cover. Give them to BuildOptions.Occlusion; the store then answers InterpolateOcclusion.
    /// </summary>
    public sealed class OcclusionProbes
    {
        /// <summary>One per baked position, in order.</summary>
        public readonly ProbeOcclusion[] Probes;
        /// <summary>The scene's mixed lights, in the order added (0 to 4).</summary>
        public readonly int MixedLights;

        public OcclusionProbes(ProbeOcclusion[] probes, int mixedLights)
        {
            if (probes == null) throw new ArgumentNullException("probes");
            if (mixedLights < 0 || mixedLights > 4) throw new ArgumentOutOfRangeException("mixedLights", mixedLights, "0 to 4");
            Probes = probes;
            MixedLights = mixedLights;
        }
    }
}
