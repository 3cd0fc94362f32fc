// Every DllImport of NativeMethods against capi/tetprobe.h: the function exists, the library and calling
// convention are the binding's, the return and every parameter type match (scalars exactly; pointers as arrays,
// references or handles of the same element type, `out` only where the header's pointer is not const, fixed-size
// arrays by their byte size), and every struct that crosses by reference has the header struct's layout (each
// scalar at its offset, the same size). Header functions the binding does not declare are not an error.
using System;
using System.Collections.Generic;
using System.IO;
using System.Linq;
using System.Reflection;
using System.Runtime.InteropServices;
using System.Text.RegularExpressions;
using TetProbe;

static class HeaderCheck
{
    sealed class CType
    {
        public string Base;   // e.g. "float", "tp_store", "char"
        public int Pointers;  // '*' count, a trailing [N] counts as one
        public bool Const;    // the pointee is const
        public int ArrayLength; // N of a trailing [N], else 0
        public override string ToString()
        {
            return (Const ? "const " : "") + Base + new string('*', Pointers) + (ArrayLength > 0 ? "[" + ArrayLength + "]" : "");
        }
    }

    static readonly Dictionary<string, Type> Scalars = new Dictionary<string, Type>
    {
        { "tp_status", typeof(int) }, { "int", typeof(int) }, { "int32_t", typeof(int) }, { "uint32_t", typeof(uint) },
        { "uint64_t", typeof(ulong) }, { "size_t", typeof(UIntPtr) }, { "float", typeof(float) }, { "double", typeof(double) },
        { "char", typeof(byte) }, { "uint8_t", typeof(byte) },
    };

    static readonly Dictionary<string, Type> Handles = new Dictionary<string, Type>
    {
        { "tp_store", typeof(StoreHandle) }, { "tp_scene", typeof(SceneHandle) },
    };

    static string StripComments(string text)
    {
        text = Regex.Replace(text, @"/\*.*?\*/", " ", RegexOptions.Singleline);
        return Regex.Replace(text, @"//[^\n]*", " ");
    }

    static CType ParseType(string declaration, out string name)
    {
        declaration = declaration.Trim();
        var type = new CType();
        Match array = Regex.Match(declaration, @"\[(\d*)\]\s*$");
        if (array.Success)
        {
            type.Pointers += 1;
            type.ArrayLength = array.Groups[1].Value.Length > 0 ? int.Parse(array.Groups[1].Value) : 0;
            declaration = declaration.Substring(0, array.Index).Trim();
        }
        type.Pointers += declaration.Count(c => c == '*');
        declaration = declaration.Replace("*", " ");
        var words = declaration.Split(new[] { ' ', '\t', '\n' }, StringSplitOptions.RemoveEmptyEntries).ToList();
        type.Const = words.Remove("const");
        words.Remove("struct");
        name = words.Count > 1 ? words[words.Count - 1] : "";
        type.Base = words[0];
        return type;
    }

    /// <summary>Functions of the header: name, return type, parameters.</summary>
    static Dictionary<string, KeyValuePair<CType, List<CType>>> Functions(string header)
    {
        var result = new Dictionary<string, KeyValuePair<CType, List<CType>>>();
        foreach (Match m in Regex.Matches(header, @"TP_API\s+([\w\s\*]+?)\b(tp_\w+)\s*\(([^)]*)\)\s*;"))
        {
            string ignored;
            CType returns = ParseType(m.Groups[1].Value, out ignored);
            var parameters = new List<CType>();
            string list = m.Groups[3].Value.Trim();
            if (list != "void" && list.Length > 0)
                foreach (string p in list.Split(','))
                    parameters.Add(ParseType(p, out ignored));
            result[m.Groups[2].Value] = new KeyValuePair<CType, List<CType>>(returns, parameters);
        }
        return result;
    }

    /// <summary>Each struct's scalars in order as (offset, C# type), with its size, per the C rules on LP64.</summary>
    static Dictionary<string, KeyValuePair<List<KeyValuePair<int, Type>>, int>> Structs(string header)
    {
        var result = new Dictionary<string, KeyValuePair<List<KeyValuePair<int, Type>>, int>>();
        foreach (Match m in Regex.Matches(header, @"typedef\s+struct\s+(tp_\w+)\s*\{(.*?)\}\s*\1\s*;", RegexOptions.Singleline))
        {
            var fields = new List<KeyValuePair<int, Type>>();
            int offset = 0, alignment = 1;
            foreach (string member in m.Groups[2].Value.Split(';'))
            {
                if (member.Trim().Length == 0) continue;
                string name;
                CType type = ParseType(member, out name);
                bool pointer = type.Pointers > 0 && type.ArrayLength == 0 || type.Base.EndsWith("_fn");
                int count = type.ArrayLength > 0 ? type.ArrayLength : 1;
                Type scalar = pointer ? typeof(IntPtr) : Scalars[type.Base];
                int size = pointer ? IntPtr.Size : Marshal.SizeOf(scalar);
                offset = (offset + size - 1) / size * size;
                alignment = Math.Max(alignment, size);
                for (int i = 0; i < count; ++i, offset += size) fields.Add(new KeyValuePair<int, Type>(offset, scalar));
            }
            int total = (offset + alignment - 1) / alignment * alignment;
            result[m.Groups[1].Value] = new KeyValuePair<List<KeyValuePair<int, Type>>, int>(fields, total);
        }
        return result;
    }

    /// <summary>A blittable C# type's scalars in order as (offset, type), nested structs flattened.</summary>
    static void Flatten(Type type, int baseOffset, List<KeyValuePair<int, Type>> into)
    {
        if (type.IsPrimitive || type == typeof(IntPtr) || type == typeof(UIntPtr))
        {
            into.Add(new KeyValuePair<int, Type>(baseOffset, type));
            return;
        }
        foreach (FieldInfo field in type.GetFields(BindingFlags.Instance | BindingFlags.Public | BindingFlags.NonPublic)
                                        .OrderBy(f => Marshal.OffsetOf(type, f.Name).ToInt32()))
            Flatten(field.FieldType, baseOffset + Marshal.OffsetOf(type, field.Name).ToInt32(), into);
    }

    static string Describe(List<KeyValuePair<int, Type>> fields)
    {
        return string.Join(" ", fields.Select(f => f.Key + ":" + f.Value.Name));
    }

    static readonly HashSet<string> CheckedStructs = new HashSet<string>();

    /// <summary>Why `csharp` cannot stand for the header's `c` (null when it can).</summary>
    static string Mismatch(CType c, ParameterInfo parameter, Type csharp,
                           Dictionary<string, KeyValuePair<List<KeyValuePair<int, Type>>, int>> structs)
    {
        bool byRef = csharp.IsByRef;
        Type type = byRef ? csharp.GetElementType() : csharp;
        bool isOut = parameter != null && parameter.IsOut && !parameter.IsIn;
        if (c.Pointers == 0)
        {
            Type scalar;
            if (!Scalars.TryGetValue(c.Base, out scalar)) return "unknown scalar " + c;
            return !byRef && type == scalar ? null : "expected " + scalar.Name;
        }
        if (!byRef && type == typeof(IntPtr)) return null;  // any pointer may be passed as a raw address (NULL)
        if (c.Pointers == 2)
        {
            Type handle;
            if (Handles.TryGetValue(c.Base, out handle)) return byRef && isOut && type == handle ? null : "expected out " + handle.Name;
            return byRef && isOut && type == typeof(IntPtr) ? null : "expected out IntPtr";
        }
        if (isOut && c.Const) return "`out` for a const pointer";
        if (Handles.ContainsKey(c.Base)) return !byRef && type == Handles[c.Base] ? null : "expected " + Handles[c.Base].Name;
        if (structs.ContainsKey(c.Base))
        {
            if (!byRef && !type.IsArray) return "expected a struct by reference or an array of structs";
            if (type.IsArray) type = type.GetElementType();
            var fields = new List<KeyValuePair<int, Type>>();
            Flatten(type, 0, fields);
            var expected = structs[c.Base];
            if (Describe(fields) != Describe(expected.Key) || Marshal.SizeOf(type) != expected.Value)
                return type.Name + " [" + Describe(fields) + "] size " + Marshal.SizeOf(type) + " is not " + c.Base + " [" +
                       Describe(expected.Key) + "] size " + expected.Value;
            CheckedStructs.Add(c.Base);
            return null;
        }
        Type element = byRef ? type : type.IsArray ? type.GetElementType() : null;
        if (element == null) return "expected an array, a reference or IntPtr";
        if (!byRef && parameter != null && !c.Const && parameter.IsIn && !parameter.IsOut) return "[In] only on a written buffer";
        if (c.Base == "void") return element.IsValueType ? null : "expected a blittable element";
        Type scalarOf;
        if (!Scalars.TryGetValue(c.Base, out scalarOf)) return "unknown pointee " + c;
        var leaves = new List<KeyValuePair<int, Type>>();
        Flatten(element, 0, leaves);
        if (leaves.Count == 0 || leaves.Any(l => l.Value != scalarOf)) return element.Name + " is not made of " + scalarOf.Name;
        if (byRef && c.ArrayLength > 0 && Marshal.SizeOf(element) != c.ArrayLength * Marshal.SizeOf(scalarOf))
            return element.Name + " is " + Marshal.SizeOf(element) + " bytes, not " + c;
        return null;
    }

    public static void Run(string headerPath)
    {
        string header = StripComments(File.ReadAllText(headerPath));
        var functions = Functions(header);
        var structs = Structs(header);
        Tests.Check(functions.Count >= 40 && structs.Count >= 8, "header parsed: " + functions.Count + " functions, " +
                    structs.Count + " structs");

        var imports = typeof(NativeMethods).GetMethods(BindingFlags.Static | BindingFlags.Public | BindingFlags.NonPublic)
                                           .Where(m => (m.Attributes & MethodAttributes.PinvokeImpl) != 0).ToList();
        Tests.Check(imports.Count >= 40, imports.Count + " DllImports found");
        var problems = new List<string>();
        foreach (MethodInfo method in imports)
        {
            var import = (DllImportAttribute)method.GetCustomAttributes(typeof(DllImportAttribute), false).FirstOrDefault();
            string entry = import != null && !string.IsNullOrEmpty(import.EntryPoint) ? import.EntryPoint : method.Name;
            if (import == null || import.Value != NativeMethods.Library || import.CallingConvention != CallingConvention.Cdecl)
                problems.Add(method.Name + ": not [DllImport(NativeMethods.Library, Cdecl)]");
            KeyValuePair<CType, List<CType>> c;
            if (!functions.TryGetValue(entry, out c))
            {
                problems.Add(entry + ": not in the header");
                continue;
            }
            string why = Mismatch(c.Key, null, method.ReturnType, structs);
            if (why != null) problems.Add(entry + " returns " + method.ReturnType.Name + " for " + c.Key + ": " + why);
            ParameterInfo[] parameters = method.GetParameters();
            if (parameters.Length != c.Value.Count)
            {
                problems.Add(entry + ": " + parameters.Length + " parameters, the header has " + c.Value.Count);
                continue;
            }
            for (int i = 0; i < parameters.Length; ++i)
            {
                why = Mismatch(c.Value[i], parameters[i], parameters[i].ParameterType, structs);
                if (why != null)
                    problems.Add(entry + " parameter " + i + " (" + parameters[i].Name + "): " + parameters[i].ParameterType.Name +
                                 " for " + c.Value[i] + ": " + why);
            }
        }
        foreach (string problem in problems) Console.WriteLine("  header: " + problem);
        Tests.Check(problems.Count == 0, "every DllImport matches capi/tetprobe.h (" + problems.Count + " mismatches)");
        // And the other way: every function of the header is declared (the binding is complete).
        var declared = new HashSet<string>(imports.Select(m =>
        {
            var import = (DllImportAttribute)m.GetCustomAttributes(typeof(DllImportAttribute), false).FirstOrDefault();
            return import != null && !string.IsNullOrEmpty(import.EntryPoint) ? import.EntryPoint : m.Name;
        }));
        var missing = functions.Keys.Where(f => !declared.Contains(f)).OrderBy(f => f).ToList();
        Tests.Check(missing.Count == 0, "every function of capi/tetprobe.h has a DllImport" +
                    (missing.Count > 0 ? " (missing: " + string.Join(", ", missing) + ")" : " (" + functions.Count + ")"));
        Tests.Check(CheckedStructs.Count >= 8, "struct layouts checked: " + string.Join(", ", CheckedStructs.OrderBy(s => s)));

        // Constants and enums, by name without underscores: NativeMethods.BuildCompact = TP_BUILD_COMPACT, etc.
        var defines = new Dictionary<string, long>();
        foreach (Match m in Regex.Matches(header, @"#define\s+(TP_\w+)\s+(\d+)u?\b")) defines[Key(m.Groups[1].Value)] = long.Parse(m.Groups[2].Value);
        foreach (Match m in Regex.Matches(header, @"\b(TP_\w+)\s*=\s*(\d+)")) defines[Key(m.Groups[1].Value)] = long.Parse(m.Groups[2].Value);
        var constantProblems = new List<string>();
        Action<string, long> expect = (name, value) =>
        {
            long actual;
            if (!defines.TryGetValue(Key(name), out actual)) constantProblems.Add(name + " is not in the header");
            else if (actual != value) constantProblems.Add(name + " = " + value + ", the header says " + actual);
        };
        foreach (FieldInfo field in typeof(NativeMethods).GetFields(BindingFlags.Static | BindingFlags.Public | BindingFlags.NonPublic))
            if (field.IsLiteral && field.FieldType == typeof(uint)) expect("TP_" + field.Name, (uint)field.GetValue(null));
        foreach (TetProbeStatus status in Enum.GetValues(typeof(TetProbeStatus)))
            expect(status == TetProbeStatus.Ok ? "TP_OK" : "TP_ERROR_" + status, (long)status);
        foreach (TetProbe.LightType type in Enum.GetValues(typeof(TetProbe.LightType))) expect("TP_LIGHT_" + type, (long)type);
        foreach (ShadowLight type in Enum.GetValues(typeof(ShadowLight))) expect("TP_LIGHT_" + type, (long)type);
        foreach (LightMode mode in Enum.GetValues(typeof(LightMode))) expect("TP_LIGHT_MODE_" + mode, (long)mode);
        foreach (ShOrder order in Enum.GetValues(typeof(ShOrder))) expect("TP_SH_ORDER_" + order, (long)order);
        foreach (ShWindow window in Enum.GetValues(typeof(ShWindow))) expect("TP_SH_WINDOW_" + window, (long)window);
        foreach (UpAxis up in Enum.GetValues(typeof(UpAxis))) expect("TP_UP_" + up, (long)up);
        foreach (string problem in constantProblems) Console.WriteLine("  header: " + problem);
        Tests.Check(constantProblems.Count == 0, "constants and enums match the header's values");

        // The check itself must see a wrong declaration: a parameter type and a struct layout it has to reject.
        MethodInfo load = typeof(Fakes).GetMethod("tp_store_load_file");
        Tests.Check(Mismatch(functions["tp_store_load_file"].Value[0], load.GetParameters()[0], load.GetParameters()[0].ParameterType,
                             structs) != null, "the check rejects int[] for const char*");
        MethodInfo locate = typeof(Fakes).GetMethod("tp_store_locate");
        Tests.Check(Mismatch(functions["tp_store_locate"].Value[3], locate.GetParameters()[3], locate.GetParameters()[3].ParameterType,
                             structs) != null, "the check rejects a tp_location without its last field");
        MethodInfo save = typeof(Fakes).GetMethod("tp_store_interpolate");
        Tests.Check(Mismatch(functions["tp_store_interpolate"].Value[3], save.GetParameters()[3], save.GetParameters()[3].ParameterType,
                             structs) != null, "the check rejects 26 floats for float[27]");
    }

    static string Key(string name)
    {
        return name.Replace("_", "").ToUpperInvariant();
    }

    [StructLayout(LayoutKind.Sequential)]
    struct ShortLocation
    {
        public uint struct_size;
        public int cell;
        public uint cell_kind, steps, fallback, probe0, probe1, probe2, probe3;
        public float weight0, weight1, weight2, weight3;
    }

    [StructLayout(LayoutKind.Sequential, Size = 104)]
    struct TwentySixFloats
    {
        public float first;
    }

    static class Fakes
    {
        public static int tp_store_load_file(int[] path, out IntPtr store) { store = IntPtr.Zero; return 0; }
        public static int tp_store_locate(IntPtr store, ref Vector3 position, ref int hint, ref ShortLocation location) { return 0; }
        public static int tp_store_interpolate(IntPtr store, ref Vector3 position, ref int hint, out TwentySixFloats sh)
        {
            sh = default(TwentySixFloats);
            return 0;
        }
    }
}
