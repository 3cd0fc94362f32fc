// Stand-ins of the few UnityEditor members samples/unity/Editor uses.
using System;
using System.Collections.Generic;

namespace UnityEditor
{
    [AttributeUsage(AttributeTargets.Method)]
    public sealed class MenuItem : Attribute
    {
        public MenuItem(string itemName) { }
    }

    public static class EditorUtility
    {
        /// <summary>Stub only: what the progress bar was shown, and a fraction at which "Cancel" is pressed.</summary>
        public static readonly List<float> Shown = new List<float>();
        public static float CancelAt = float.PositiveInfinity;
        public static bool DisplayCancelableProgressBar(string title, string info, float progress)
        {
            Shown.Add(progress);
            return progress >= CancelAt;
        }
        public static void ClearProgressBar() { }
        public static bool DisplayDialog(string title, string message, string ok) { return true; }
    }

    /// <summary>Which of Unity's precomputations include a GameObject (only the flags the samples read).</summary>
    [Flags]
    public enum StaticEditorFlags
    {
        ContributeGI = 1,
        BatchingStatic = 4,
    }

    public static class GameObjectUtility
    {
        static readonly Dictionary<UnityEngine.GameObject, StaticEditorFlags> Flags =
            new Dictionary<UnityEngine.GameObject, StaticEditorFlags>();
        public static StaticEditorFlags GetStaticEditorFlags(UnityEngine.GameObject go)
        {
            StaticEditorFlags flags;
            return Flags.TryGetValue(go, out flags) ? flags : 0;
        }
        public static void SetStaticEditorFlags(UnityEngine.GameObject go, StaticEditorFlags flags) { Flags[go] = flags; }
    }

    public static class AssetDatabase
    {
        public static readonly List<string> Imported = new List<string>();
        public static void ImportAsset(string path) { Imported.Add(path); }
    }
}
