// Lights renderers from a tetprobe store the way Unity lights them from its own light probes: each renderer keeps
// its cell hint, every frame one batch query interpolates the SH at every renderer's probe position, and each
// renderer receives its SH through a MaterialPropertyBlock (LightProbeUsage.CustomProvided), converted to Unity's
// SphericalHarmonicsL2 so that the built-in and SRP shaders evaluate it as they evaluate Unity's probes.
#if UNITY_5_3_OR_NEWER
using TetProbe;
using UnityEngine;
using UnityEngine.Rendering;
using ProbeSH = TetProbe.SphericalHarmonicsL2;
using UnitySH = UnityEngine.Rendering.SphericalHarmonicsL2;

[DisallowMultipleComponent]
public class TetProbeLighting : MonoBehaviour
{
    [Tooltip("The store LightProbeBaker wrote (a .bytes asset).")]
    public TextAsset store;

    [Tooltip("Renderers lit by the store; empty = every Renderer on this object and its children.")]
    public Renderer[] renderers;

    ProbeStore probes;
    int[] hints;
    Vector3[] positions;
    ProbeSH[] interpolated;
    readonly UnitySH[] one = new UnitySH[1];
    MaterialPropertyBlock block;
    // The renderers lit since OnEnable and their lightProbeUsage before, restored by OnDisable.
    Renderer[] lit;
    LightProbeUsage[] previousUsage;

    void OnEnable()
    {
        if (store == null) return;
        if (renderers == null || renderers.Length == 0) renderers = GetComponentsInChildren<Renderer>();
        probes = ProbeStore.Load(store.bytes);
        hints = new int[renderers.Length];
        for (int i = 0; i < hints.Length; ++i) hints[i] = -1;  // no cell yet: the first query starts cold
        positions = new Vector3[renderers.Length];
        interpolated = new ProbeSH[renderers.Length];
        block = new MaterialPropertyBlock();
        lit = (Renderer[])renderers.Clone();
        previousUsage = new LightProbeUsage[lit.Length];
        for (int i = 0; i < lit.Length; ++i)
        {
            previousUsage[i] = lit[i].lightProbeUsage;
            lit[i].lightProbeUsage = LightProbeUsage.CustomProvided;
        }
    }

    void Update()
    {
        if (probes == null) return;
        for (int i = 0; i < renderers.Length; ++i)
        {
            Renderer r = renderers[i];
            // Where Unity samples its probes for a renderer: the anchor override, else the bounds' centre.
            positions[i] = r.probeAnchor != null ? r.probeAnchor.position : r.bounds.center;
        }
        probes.Interpolate(positions, hints, interpolated);
        for (int i = 0; i < renderers.Length; ++i)
        {
            one[0] = UnitySphericalHarmonics.ToUnity(interpolated[i]);
            renderers[i].GetPropertyBlock(block);
            block.CopySHCoefficientArraysFrom(one);
            renderers[i].SetPropertyBlock(block);
        }
    }

    /// <summary>Gives the renderers back to Unity's lighting: their previous probe usage and no SH of ours (a
    /// CustomProvided renderer would otherwise keep the last frame's SH for ever).</summary>
    void OnDisable()
    {
        if (probes != null) probes.Dispose();
        probes = null;
        if (lit == null) return;
        for (int i = 0; i < lit.Length; ++i)
        {
            if (lit[i] == null) continue;  // destroyed meanwhile
            lit[i].lightProbeUsage = previousUsage[i];
            lit[i].SetPropertyBlock(null);
        }
        lit = null;
        previousUsage = null;
    }
}
#endif
