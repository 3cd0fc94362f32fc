// Lights a large renderer from a tetprobe store the way Unity's Light Probe Proxy Volume does: every frame a grid of
// points over the renderer's bounds is sampled from the store (ProbeStore.SampleVolume, walking the grid from
// neighbour to neighbour) straight into the texels of a Light Probe Proxy Volume texture, a Texture3D of 4 x nx by
// ny by nz RGBAHalf (or RGBAFloat) texels whose x blocks hold unity_SHAr, unity_SHAg and unity_SHAb (the fourth,
// probe occlusion, is left at 1), and the renderer's MaterialPropertyBlock receives the texture and the
// unity_ProbeVolume* parameters the built-in shaders' SHEvalLinearL0L1_SampleProbeVolume reads. The volume holds
// the L0 and L1 bands, per pixel, as Unity's proxy volumes do.
#if UNITY_5_3_OR_NEWER
using System;
using TetProbe;
using UnityEngine;
using UnityEngine.Rendering;

[DisallowMultipleComponent]
public class TetProbeProxyVolume : MonoBehaviour
{
    [Tooltip("The store LightProbeBaker wrote (a .bytes asset).")]
    public TextAsset store;

    [Tooltip("The renderer lit by the volume; empty = the Renderer on this object.")]
    public Renderer target;

    [Tooltip("Points along each axis of the renderer's bounds (1 to 32 each).")]
    public int resolutionX = 8, resolutionY = 8, resolutionZ = 8;

    [Tooltip("Half floats, as Unity's proxy volumes use by default; off: 32-bit floats.")]
    public bool halfFloat = true;

    ProbeStore probes;
    int hint = -1;
    float[] texels;
    ushort[] halves;
    Texture3D volume;
    MaterialPropertyBlock block;
    LightProbeUsage previousUsage;

    /// <summary>The texture the renderer samples (for inspection).</summary>
    public Texture3D Volume { get { return volume; } }

    void OnEnable()
    {
        if (store == null) return;
        if (target == null) target = GetComponent<Renderer>();
        if (target == null) return;
        probes = ProbeStore.Load(store.bytes);
        hint = -1;
        int nx = resolutionX, ny = resolutionY, nz = resolutionZ;
        texels = new float[4 * nx * ny * nz * 4];
        for (int i = 0; i < texels.Length; ++i)
            if ((i / 4) % (4 * nx) >= 3 * nx) texels[i] = 1;  // the occlusion block: fully visible
        if (halfFloat) halves = new ushort[texels.Length];
        volume = new Texture3D(4 * nx, ny, nz, halfFloat ? TextureFormat.RGBAHalf : TextureFormat.RGBAFloat, false);
        volume.wrapMode = TextureWrapMode.Clamp;
        volume.filterMode = FilterMode.Bilinear;
        block = new MaterialPropertyBlock();
        previousUsage = target.lightProbeUsage;
        target.lightProbeUsage = LightProbeUsage.CustomProvided;
    }

    void Update()
    {
        if (probes == null) return;
        int nx = resolutionX, ny = resolutionY, nz = resolutionZ;
        Bounds bounds = target.bounds;
        // Points at the centres of nx x ny x nz cells of the bounds, as Unity's proxy volume places its probes.
        var cell = new Vector3(bounds.size.x / nx, bounds.size.y / ny, bounds.size.z / nz);
        cell = new Vector3(Math.Max(cell.x, 1e-4f), Math.Max(cell.y, 1e-4f), Math.Max(cell.z, 1e-4f));
        Vector3 min = bounds.center - new Vector3(cell.x * nx, cell.y * ny, cell.z * nz) * 0.5f;
        Vector3 origin = min + cell * 0.5f;
        // The atlas directly: texel (block nx + x, y, z), 16 bytes each; block k = unity_SHAr, SHAg, SHAb.
        probes.SampleVolume(origin, cell, nx, ny, nz, VolumeFormat.UnityL1, texels, ref hint, 16, 64L * nx,
                            64L * nx * ny, 16L * nx);
        if (halfFloat)
        {
            for (int i = 0; i < texels.Length; ++i) halves[i] = Mathf.FloatToHalf(texels[i]);
            volume.SetPixelData(halves, 0);
        }
        else
        {
            volume.SetPixelData(texels, 0);
        }
        volume.Apply(false);
        target.GetPropertyBlock(block);
        block.SetTexture("unity_ProbeVolumeSH", volume);
        // x: the volume is on; y: 0 = sampled at world positions; z: the atlas's texel width in texture coordinates.
        block.SetVector("unity_ProbeVolumeParams", new Vector4(1, 0, 1.0f / (4 * nx), 0));
        block.SetVector("unity_ProbeVolumeMin", new Vector4(min.x, min.y, min.z, 0));
        block.SetVector("unity_ProbeVolumeSizeInv",
                        new Vector4(1 / (cell.x * nx), 1 / (cell.y * ny), 1 / (cell.z * nz), 0));
        target.SetPropertyBlock(block);
    }

    /// <summary>Gives the renderer back to Unity's lighting (its previous probe usage, no property block of ours).</summary>
    void OnDisable()
    {
        if (probes != null) probes.Dispose();
        probes = null;
        if (target != null && block != null)
        {
            target.lightProbeUsage = previousUsage;
            target.SetPropertyBlock(null);
        }
        if (volume != null) Destroy(volume);
        volume = null;
    }
}
#endif
