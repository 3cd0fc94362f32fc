// Editor: bakes the open scene's LightProbeGroup positions with tetprobe and saves the store next to the scene as a
// .bytes TextAsset for TetProbeLighting. The tetprobe scene is made of the scene's static MeshFilters (Contribute GI;
// albedo from the material's colour, emission where _EMISSION is on), its Baked and Mixed Lights and
// RenderSettings.ambientProbe as the sky: what Unity's own probe bake sees.
#if UNITY_EDITOR
using System;
using System.Collections.Generic;
using System.IO;
using System.Threading;
using TetProbe;
using UnityEditor;
using UnityEngine;
using ProbeScene = TetProbe.Scene;
using ProbeLight = TetProbe.Light;
using ProbeMaterial = TetProbe.Material;

public static class LightProbeBaker
{
    [MenuItem("Tools/TetProbe/Bake Light Probes")]
    static void BakeOpenScene()
    {
        string scenePath = UnityEngine.SceneManagement.SceneManager.GetActiveScene().path;
        if (string.IsNullOrEmpty(scenePath))
        {
            EditorUtility.DisplayDialog("TetProbe", "Save the scene first: the store is written next to it.", "OK");
            return;
        }
        string assetPath = Path.ChangeExtension(scenePath, null) + "_probes.bytes";
        Debug.Log(Bake(assetPath, new BakeOptions()));
    }

    /// <summary>Bakes the open scene into assetPath (a .bytes store) and returns the effects plan's summary.</summary>
    public static string Bake(string assetPath, BakeOptions options)
    {
        Vector3[] positions = ProbePositions();
        if (positions.Length == 0) throw new InvalidOperationException("the scene has no LightProbeGroup probes");
        using (ProbeScene scene = FromOpenScene())
        using (var cancel = new CancellationTokenSource())
        {
            string plan = Baker.Plan(scene, positions, options).Summary;
            var progress = new ProgressBar(cancel);
            try
            {
                TetProbe.SphericalHarmonicsL2[] sh = Baker.Bake(scene, positions, options, progress, cancel.Token);
                using (ProbeStore store = ProbeStore.Build(positions, sh))
                    store.Save(assetPath);  // atomic: a cancelled or failed bake leaves the old asset as it was
            }
            finally
            {
                EditorUtility.ClearProgressBar();
            }
            AssetDatabase.ImportAsset(assetPath);
            return plan;
        }
    }

    /// <summary>Every LightProbeGroup's probes, in world space.</summary>
    public static Vector3[] ProbePositions()
    {
        var positions = new List<Vector3>();
        foreach (LightProbeGroup group in UnityEngine.Object.FindObjectsOfType<LightProbeGroup>())
            foreach (Vector3 local in group.probePositions) positions.Add(group.transform.TransformPoint(local));
        return positions.ToArray();
    }

    /// <summary>The open scene as a tetprobe scene: the meshes that contribute to GI (dynamic objects neither occlude
    /// nor bounce in Unity's bake), the lights ProbeLightOf keeps and the ambient probe as the sky.</summary>
    public static ProbeScene FromOpenScene()
    {
        var scene = new ProbeScene();
        foreach (MeshFilter filter in UnityEngine.Object.FindObjectsOfType<MeshFilter>())
        {
            var renderer = filter.GetComponent<MeshRenderer>();
            if (filter.sharedMesh == null || renderer == null) continue;
            if ((GameObjectUtility.GetStaticEditorFlags(filter.gameObject) & StaticEditorFlags.ContributeGI) == 0) continue;
            Vector3[] vertices = filter.sharedMesh.vertices;
            for (int i = 0; i < vertices.Length; ++i) vertices[i] = filter.transform.TransformPoint(vertices[i]);
            scene.AddMesh(vertices, filter.sharedMesh.triangles, MaterialOf(renderer.sharedMaterial));
        }
        foreach (UnityEngine.Light light in UnityEngine.Object.FindObjectsOfType<UnityEngine.Light>())
        {
            ProbeLight? converted = ProbeLightOf(light);
            if (converted.HasValue) scene.AddLight(converted.Value);
        }
        scene.SetSky(UnitySphericalHarmonics.FromUnity(RenderSettings.ambientProbe));
        return scene;
    }

    /// <summary>What Unity's probes hold of a light, as a tetprobe light (null: nothing). Baked lights: direct and
    /// bounced light. Mixed lights: bounced light only, in every Lighting Mode (Unity's MixedLightingMode table: light
    /// probes hold no direct light of Mixed lights in Baked Indirect, Shadowmask or Subtractive; dynamic objects get it in
    /// real time). Realtime lights: nothing, Unity's baked GI ignores them. Unity's intensity I is the exit radiance of a
    /// white Lambertian surface, so our irradiance-based intensity is pi I; the colour goes to linear space as Unity
    /// does it: colour times intensity together when GraphicsSettings.lightsUseLinearIntensity is off (the built-in
    /// pipeline's default), else the linear colour times the intensity.</summary>
    public static ProbeLight? ProbeLightOf(UnityEngine.Light light)
    {
        if (!light.enabled) return null;
        LightMode mode;
        if (light.lightmapBakeType == LightmapBakeType.Baked) mode = LightMode.Baked;
        else if (light.lightmapBakeType == LightmapBakeType.Mixed) mode = LightMode.Realtime;
        else return null;
        Color c;
        float intensity;
        if (UnityEngine.Rendering.GraphicsSettings.lightsUseLinearIntensity)
        {
            c = light.color.linear;
            intensity = (float)Math.PI * light.intensity;
        }
        else
        {
            c = (light.color * light.intensity).linear;
            intensity = (float)Math.PI;
        }
        var color = new Vector3(c.r, c.g, c.b);
        bool shadows = light.shadows != LightShadows.None;
        if (light.type == UnityEngine.LightType.Directional)
            return ProbeLight.Directional(light.transform.forward, color, intensity, mode, shadows);
        if (light.type == UnityEngine.LightType.Point)
            return ProbeLight.Point(light.transform.position, color, intensity, light.range, mode, shadows);
        if (light.type == UnityEngine.LightType.Spot)
            return ProbeLight.Spot(light.transform.position, light.transform.forward, color, intensity, light.range,
                                   light.innerSpotAngle, light.spotAngle, mode, shadows);
        return null;  // area lights: not in a tetprobe scene
    }

    static ProbeMaterial MaterialOf(UnityEngine.Material material)
    {
        if (material == null) return ProbeMaterial.Default;
        Color albedo = material.HasProperty("_Color") ? material.color.linear : Color.white;
        Color emission = material.IsKeywordEnabled("_EMISSION") && material.HasProperty("_EmissionColor")
            ? material.GetColor("_EmissionColor").linear : Color.black;
        return ProbeMaterial.Diffuse(new Vector3(Math.Min(albedo.r, 1), Math.Min(albedo.g, 1), Math.Min(albedo.b, 1)),
                                     new Vector3(emission.r, emission.g, emission.b), true);
    }

    /// <summary>The editor's cancellable progress bar; the bake reports on the main thread, so it may draw.</summary>
    sealed class ProgressBar : IProgress<float>
    {
        readonly CancellationTokenSource cancel;
        public ProgressBar(CancellationTokenSource cancel) { this.cancel = cancel; }
        public void Report(float fraction)
        {
            if (EditorUtility.DisplayCancelableProgressBar("TetProbe", "Baking light probes", fraction)) cancel.Cancel();
        }
    }
}
#endif
