"""Every function of capi/tetprobe.h is in both bindings: declared (the Python prototype table, a C# DllImport) and
used by the binding's own API (a call outside the declarations), so no part of the header is out of reach from
Python or C#. The C# declarations' types and struct layouts are checked against the header by tests/csharp
(HeaderCheck.cs); the Python prototypes are declared on the loaded library at import."""
import os
import re

from tetprobe import _native

ROOT = os.path.join(os.path.dirname(__file__), "..", "..")
HEADER = os.path.join(ROOT, "capi", "tetprobe.h")
PYTHON = os.path.join(ROOT, "bindings", "python", "tetprobe")
CSHARP = os.path.join(ROOT, "bindings", "csharp")


def header_functions(text):
    text = re.sub(r"/\*.*?\*/", " ", text, flags=re.S)
    return set(re.findall(r"TP_API\s+[\w\s\*]+?\b(tp_\w+)\s*\(", text))


def sources(folder, suffix):
    found = {}
    for name in sorted(os.listdir(folder)):
        if name.endswith(suffix):
            with open(os.path.join(folder, name), encoding="utf-8") as f:
                found[name] = f.read()
    return found


def python_gaps(functions):
    """(missing from the prototype table, declared but used nowhere in the package: called, or passed on as
    lib.tp_x to a helper that calls it)."""
    declared = {name for name, _, _ in _native.PROTOTYPES}
    code = "\n".join(text for name, text in sources(PYTHON, ".py").items())
    called = set(re.findall(r"\blib\.(tp_\w+)\b", code))
    return sorted(functions - declared), sorted(functions & declared - called)


def csharp_gaps(functions):
    """(without a DllImport in NativeMethods.cs, imported but called by no other file of the binding)."""
    files = sources(CSHARP, ".cs")
    imported = set(re.findall(r"static\s+extern\s+[\w\.]+\s+(tp_\w+)\s*\(", files["NativeMethods.cs"]))
    others = "\n".join(text for name, text in files.items() if name != "NativeMethods.cs")
    called = set(re.findall(r"\bNativeMethods\.(tp_\w+)\s*\(", others))
    return sorted(functions - imported), sorted(functions & imported - called)


def test_every_header_function_is_bound_in_python_and_csharp():
    with open(HEADER, encoding="utf-8") as f:
        functions = header_functions(f.read())
    assert len(functions) >= 53
    missing, unused = python_gaps(functions)
    assert missing == [], "functions of capi/tetprobe.h missing from the Python prototype table: %s" % missing
    assert unused == [], "Python prototypes the package never uses: %s" % unused
    missing, unused = csharp_gaps(functions)
    assert missing == [], "functions of capi/tetprobe.h without a C# DllImport: %s" % missing
    assert unused == [], "C# DllImports no layer-2/3 code calls: %s" % unused
    # Nothing bound that the header does not have.
    assert {name for name, _, _ in _native.PROTOTYPES} <= functions


def test_the_check_sees_a_function_the_bindings_lack():
    with open(HEADER, encoding="utf-8") as f:
        text = f.read()
    grown = text.replace("#ifdef __cplusplus\n}", "TP_API tp_status tp_new_thing(const tp_store* store, int* out);\n\n"
                         "#ifdef __cplusplus\n}", 1)
    functions = header_functions(grown)
    assert "tp_new_thing" in functions
    assert python_gaps(functions)[0] == ["tp_new_thing"]
    assert csharp_gaps(functions)[0] == ["tp_new_thing"]
    # A commented-out declaration is not a function.
    assert "tp_old_thing" not in header_functions(text + "\n/* TP_API tp_status tp_old_thing(void); */\n")
