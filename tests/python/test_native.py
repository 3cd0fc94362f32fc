"""The ctypes layer: one prototype table that covers the whole header, the version check, structs."""
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


def test_prototype_table_declares_every_function_of_the_header():
    exported = set(re.findall(r"TP_API\s+[\w\s\*]+?\b(tp_\w+)\s*\(", header_text()))
    declared = [name for name, _, _ in _native.PROTOTYPES]
    assert len(declared) == len(set(declared))
    assert set(declared) == exported
    for name in declared:
        assert getattr(_native.lib, name).argtypes is not None


def test_argument_counts_match_the_header():
    text = header_text()
    for name, _, argtypes in _native.PROTOTYPES:
        match = re.search(r"TP_API\s+[\w\s\*]+?\b" + name + r"\s*\(([^)]*)\)", text)
        params = match.group(1).strip()
        count = 0 if params in ("", "void") else params.count(",") + 1
        assert count == len(argtypes), name


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
    assert _native.PACKAGE_VERSION[:2] == (0, 5)
    _native.check_version((0 << 16) | (5 << 8) | 7, (0, 5, 0))  # another patch is fine
    with pytest.raises(Error) as raised:
        _native.check_version((0 << 16) | (4 << 8), (0, 5, 0))  # the 0.4 library (format 2 stores)
    assert raised.value.status == Status.VERSION
    with pytest.raises(Error):
        _native.check_version((0 << 16) | (6 << 8), (0, 5, 0))
    with pytest.raises(Error):
        _native.check_version((1 << 16) | (5 << 8), (0, 5, 0))


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
