"""The ctypes layer: one prototype table that covers the whole header with the header's types, structs
field by field, every function used by the package, the version check."""
import ast
import ctypes
import os
import re

import pytest

import tetprobe
from tetprobe import _native
from tetprobe.errors import Error, Status

HEADER = os.path.join(os.path.dirname(__file__), "..", "..", "capi", "tetprobe.h")


def header_text():
    with open(HEADER) as f:
        return f.read()


def header_without_comments():
    text = re.sub(r"/\*.*?\*/", " ", header_text(), flags=re.S)
    return re.sub(r"//[^\n]*", " ", text)


def header_prototypes():
    """{name: (return type, [parameter declarations])} for every TP_API function of the header."""
    found = {}
    for ret, name, params in re.findall(r"TP_API\s+([\w\s\*]+?)\s*\b(tp_\w+)\s*\(([^)]*)\)",
                                        header_without_comments()):
        params = " ".join(params.split())
        found[name] = (ret.strip(), [] if params in ("", "void") else [p.strip() for p in params.split(",")])
    return found


def parse_declaration(declaration):
    """(base type, pointer depth, const, array length or None, name) of a C declaration like
    'const float position[3]' or 'tp_store** out_store'."""
    match = re.fullmatch(r"(const\s+)?(?:struct\s+)?(\w+)\s*(\**)\s*(\w*)\s*(?:\[(\w+)\])?", declaration.strip())
    assert match, "cannot parse %r" % declaration
    const, base, stars, name, length = match.groups()
    depth = len(stars) + (1 if length else 0)
    return base, depth, bool(const), length, name


SCALARS = {"uint8_t": ctypes.c_uint8, "int8_t": ctypes.c_int8, "uint16_t": ctypes.c_uint16, "int16_t": ctypes.c_int16,
           "uint32_t": ctypes.c_uint32, "int32_t": ctypes.c_int32, "uint64_t": ctypes.c_uint64,
           "int64_t": ctypes.c_int64, "size_t": ctypes.c_size_t, "float": ctypes.c_float, "double": ctypes.c_double,
           "int": ctypes.c_int, "tp_status": ctypes.c_int, "tp_progress_fn": _native.ProgressFn}
HANDLES = ("tp_store", "tp_scene")


def struct_class(c_name):
    """The ctypes Structure of a header struct: tp_build_options -> _native.BuildOptions (any capitals)."""
    wanted = c_name[len("tp_"):].replace("_", "").lower()
    matches = [value for name, value in vars(_native).items()
               if name.lower() == wanted and isinstance(value, type) and issubclass(value, ctypes.Structure)]
    assert len(matches) == 1, "no ctypes Structure in _native for %s" % c_name
    return matches[0]


def accepted_ctypes(declaration):
    """The ctypes argument types that pass a parameter of this C declaration correctly."""
    base, depth, const, _, _ = parse_declaration(declaration)
    if depth == 0:
        return {SCALARS[base]}
    if depth == 2:
        return {ctypes.POINTER(ctypes.c_void_p)}  # tp_store** out handles, const void** / const float** views
    if base in HANDLES:
        return {ctypes.c_void_p}
    if base == "char":
        return {ctypes.c_char_p} if const else {ctypes.POINTER(ctypes.c_char)}
    if base.startswith("tp_"):
        return {ctypes.POINTER(struct_class(base))}
    if base == "void":
        return {_native.Buffer}
    return {_native.Buffer, ctypes.POINTER(SCALARS[base])}  # an array or a single out-value


def test_prototype_table_declares_every_function_of_the_header():
    exported = set(header_prototypes())
    declared = [name for name, _, _ in _native.PROTOTYPES]
    assert len(declared) == len(set(declared))
    assert set(declared) == exported
    for name in declared:
        assert getattr(_native.lib, name).argtypes is not None


def test_argument_and_return_types_match_the_header():
    header = header_prototypes()
    for name, restype, argtypes in _native.PROTOTYPES:
        ret, params = header[name]
        assert len(argtypes) == len(params), name
        for position, (declaration, argtype) in enumerate(zip(params, argtypes)):
            assert argtype in accepted_ctypes(declaration), "%s argument %d (%s): %r" % (
                name, position, declaration, argtype)
        base, depth, const, _, _ = parse_declaration(ret + " result")
        expected = ctypes.c_char_p if (base, depth, const) == ("char", 1, True) else SCALARS[base]
        assert depth <= 1 and restype is expected, "%s returns %s, declared %r" % (name, ret, restype)


def header_structs():
    """{struct name: [field declarations]} for every struct the header defines."""
    structs = {}
    for name, body in re.findall(r"typedef\s+struct\s+(tp_\w+)\s*\{(.*?)\}\s*\1\s*;", header_without_comments(),
                                 flags=re.S):
        structs[name] = [" ".join(field.split()) for field in body.split(";") if field.strip()]
    return structs


def test_every_struct_matches_the_header_field_by_field():
    structs = header_structs()
    assert {"tp_build_options", "tp_store_info", "tp_location", "tp_bake_options"} <= set(structs)
    for c_name, fields in structs.items():
        ours = struct_class(c_name)._fields_
        assert [name for name, _ in ours] == [parse_declaration(f)[4] for f in fields], c_name
        for (name, ctype), field in zip(ours, fields):
            base, depth, _, length, _ = parse_declaration(field)
            if length:
                assert issubclass(ctype, ctypes.Array), (c_name, name)
                assert (ctype._type_, ctype._length_) == (SCALARS[base], int(length)), (c_name, name)
            elif depth == 1:
                pointee = {"void": None, "char": ctypes.c_char}.get(base, SCALARS.get(base))
                accepted = {ctypes.c_void_p} | ({ctypes.POINTER(pointee)} if pointee else set())
                assert ctype in accepted, (c_name, name)
            else:
                assert ctype is SCALARS[base], (c_name, name)


def attribute_uses_by_module():
    """{module file name: names tp_* used as attributes (lib.tp_x) in it} over the whole package."""
    package_dir = os.path.dirname(tetprobe.__file__)
    uses = {}
    for file_name in sorted(os.listdir(package_dir)):
        if file_name.endswith(".py"):
            with open(os.path.join(package_dir, file_name)) as f:
                tree = ast.parse(f.read())
            uses[file_name] = {node.attr for node in ast.walk(tree)
                               if isinstance(node, ast.Attribute) and node.attr.startswith("tp_")}
    return uses


def test_every_function_is_used_by_the_public_api():
    uses = attribute_uses_by_module()
    outside_the_table = set().union(*(names for module, names in uses.items() if module != "_native.py"))
    # tp_last_error is the message of every Error, raised by _native.check (which every wrapper calls).
    assert "tp_last_error" in uses["_native.py"]
    unreachable = [name for name, _, _ in _native.PROTOTYPES
                   if name not in outside_the_table and name != "tp_last_error"]
    assert not unreachable, "declared in _native.PROTOTYPES but called by no module of the package: %s" % unreachable


def test_flag_values_match_the_header():
    defines = dict(re.findall(r"#define\s+(TP_\w+)\s+(\d+)u", header_text()))
    assert int(defines["TP_BUILD_NO_EXTRAPOLATION"]) == _native.BUILD_NO_EXTRAPOLATION
    assert int(defines["TP_BUILD_INDEX32"]) == _native.BUILD_INDEX32
    assert int(defines["TP_BUILD_COMPACT"]) == _native.BUILD_COMPACT
    assert int(defines["TP_BATCH_CHAIN_HINTS"]) == _native.BATCH_CHAIN_HINTS


def test_status_enum_matches_the_header():
    values = dict(re.findall(r"(TP_\w+)\s*=\s*(\d+)", header_text()))
    for status in Status:
        name = "TP_OK" if status == Status.OK else "TP_ERROR_" + status.name
        assert int(values[name]) == int(status)
        assert _native.lib.tp_status_name(int(status)).decode() == name


def test_struct_sizes_are_what_the_library_fills():
    options = _native.BuildOptions()
    assert _native.lib.tp_build_options_init(ctypes.byref(options)) == 0
    assert options.struct_size == ctypes.sizeof(_native.BuildOptions)
    assert options.merge_tolerance == pytest.approx(1e-6)
    bake = _native.BakeOptions()
    assert _native.lib.tp_bake_options_init(ctypes.byref(bake)) == 0
    assert bake.struct_size == ctypes.sizeof(_native.BakeOptions)
    assert (bake.rays, bake.bounces) == (256, 2)
    material = _native.Material()
    assert _native.lib.tp_material_init(ctypes.byref(material)) == 0
    assert material.struct_size == ctypes.sizeof(_native.Material)
    batch = _native.BatchOptions()
    assert ctypes.sizeof(batch) == 12
    assert _native.lib.tp_batch_options_init(ctypes.byref(batch)) == 0
    assert batch.struct_size == ctypes.sizeof(_native.BatchOptions)
    assert (batch.flags, batch.threads) == (0, 1)
    light = _native.Light()
    assert _native.lib.tp_light_init(ctypes.byref(light)) == 0
    assert light.struct_size == ctypes.sizeof(_native.Light)


def test_version_matches_and_a_mismatch_is_refused():
    assert tetprobe.library_version()[:2] == _native.PACKAGE_VERSION[:2]
    assert tetprobe.__version__.startswith("%d.%d." % _native.PACKAGE_VERSION[:2])
    assert _native.PACKAGE_VERSION[:2] == (0, 8)
    _native.check_version((0 << 16) | (8 << 8) | 7, (0, 8, 0))  # another patch is fine
    with pytest.raises(Error) as raised:
        _native.check_version((0 << 16) | (7 << 8), (0, 8, 0))  # the 0.7 library (a shorter tp_light)
    assert raised.value.status == Status.VERSION
    with pytest.raises(Error):
        _native.check_version((0 << 16) | (9 << 8), (0, 8, 0))
    with pytest.raises(Error):
        _native.check_version((1 << 16) | (8 << 8), (0, 8, 0))


def test_library_search_order_starts_with_the_environment(monkeypatch):
    monkeypatch.setenv("TETPROBE_LIBRARY", "/some/where/libtetprobe.so")
    paths = _native.candidate_paths()
    assert paths[0] == "/some/where/libtetprobe.so"
    package_dir = os.path.dirname(os.path.abspath(_native.__file__))
    assert paths[1] == os.path.join(package_dir, "libtetprobe.so")
    assert paths[2].endswith(os.path.join("build", "libtetprobe.so"))
    assert os.path.exists(tetprobe.library_path)


def test_error_carries_status_and_message():
    error = Error(4, "bad magic")
    assert error.status == Status.INVALID_BLOB
    assert error.message == "bad magic"
    assert "TP_ERROR_INVALID_BLOB" in str(error) and "bad magic" in str(error)
