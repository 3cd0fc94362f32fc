"""Errors: every status the package can meet becomes tetprobe.Error with its status and the library's message;
closed handles, wrong shapes and dtypes, and a library of another version are clear errors."""
import os
import struct
import subprocess
import sys

import numpy as np
import pytest

import tetprobe
from tetprobe import Error, Scene, Status, Store, bake, sh, shadow_caster_volume, volume_test_aabb, volume_test_sphere

SCENES = os.path.join(os.path.dirname(__file__), "..", "..", "samples", "scenes")
CUBE = np.array([[1, 0, 0, 1], [-1, 0, 0, 1], [0, 1, 0, 1], [0, -1, 0, 1], [0, 0, 1, 1], [0, 0, -1, 1]], np.float32)


def probes(n=20, seed=4):
    rng = np.random.default_rng(seed)
    return rng.random((n, 3)).astype(np.float32), rng.uniform(-1, 1, (n, 27)).astype(np.float32)


def raised(call):
    with pytest.raises(Error) as info:
        call()
    return info.value


def test_every_status_has_the_library_name_and_a_message_when_raised(tmp_path):
    for status in Status:
        assert tetprobe.status_name(status) == ("TP_OK" if status == Status.OK else "TP_ERROR_" + status.name)
        error = Error(int(status), "what happened")
        assert error.status is status and error.message == "what happened"
        assert str(error) == "%s: what happened" % tetprobe.status_name(status)
    positions, coefficients = probes()
    store = Store.build(positions, coefficients)
    nan = positions.copy()
    nan[2, 1] = np.nan
    broken_scene = tmp_path / "broken.json"
    broken_scene.write_text('{"meshes": [')
    blob = bytearray(store.to_bytes())
    format_version = store.info()["format_version"]
    assert struct.unpack_from("<I", blob, 8)[0] == format_version  # the header's version field
    struct.pack_into("<I", blob, 8, format_version + 1)
    bounded = Store.build(positions, coefficients, extrapolate=False)
    reached = {
        Status.INVALID_ARGUMENT: lambda: Store.build(nan),
        Status.IO: lambda: Store.load(tmp_path / "missing.tpb"),
        Status.INVALID_BLOB: lambda: Store.load(b"not a store at all"),
        Status.VERSION: lambda: Store.load(bytes(blob)),
        Status.DEGENERATE: lambda: Store.build(np.zeros((0, 3), np.float32)),
        Status.CANCELLED: lambda: Store.build(positions, progress=lambda fraction, stage: True),
        Status.OUTSIDE: lambda: bounded.interpolate([5.0, 5.0, 5.0]),
        Status.SCENE: lambda: Scene.load(broken_scene),
    }
    for status, call in reached.items():
        error = raised(call)
        assert error.status is status, (status, error)
        assert error.message and str(error).startswith(tetprobe.status_name(status) + ": ")
    assert "rebuild" in raised(reached[Status.VERSION]).message
    assert "outside" in raised(reached[Status.OUTSIDE]).message


def test_the_run_time_library_refuses_bake_time_work_with_unsupported(tmp_path):
    runtime = os.path.join(os.path.dirname(tetprobe.library_path), "libtetprobe_runtime.so")
    assert os.path.exists(runtime), "build the tetprobe_runtime target"
    positions, coefficients = probes()
    Store.build(positions, coefficients).save(tmp_path / "built.tpb")
    script = ("import tetprobe\n"
              "for work in (tetprobe.Scene, lambda: tetprobe.Store.build([[0, 0, 0], [1, 0, 0]])):\n"
              "    try:\n        work()\n"
              "    except tetprobe.Error as e:\n        print(e.status.name, bool(e.message))\n"
              "print(tetprobe.Store.load(%r).info()['probes'])\n" % str(tmp_path / "built.tpb"))
    env = dict(os.environ, TETPROBE_LIBRARY=runtime)
    result = subprocess.run([sys.executable, "-c", script], capture_output=True, text=True, timeout=60, env=env)
    assert result.stdout.splitlines() == ["UNSUPPORTED True", "UNSUPPORTED True", "20"], result.stderr


def test_a_closed_store_or_scene_is_a_clear_error(tmp_path):
    positions, coefficients = probes()
    store = Store.build(positions, coefficients)
    store.close()
    store.close()  # twice is fine
    for use in (store.info, store.to_bytes, lambda: store.save(tmp_path / "x.tpb"), lambda: store.probe_sh(0),
                lambda: store.interpolate(positions), lambda: store.interpolate(positions[0]),
                lambda: store.weights(positions), lambda: store.weights(positions[0]),
                lambda: store.locate(positions[0])):
        error = raised(use)
        assert error.status is Status.INVALID_ARGUMENT and error.message == "the store is closed"
    with Scene() as scene:
        pass
    for use in (lambda: scene.set_sky(color=(1, 1, 1)), lambda: scene.probes, lambda: bake(scene, positions),
                lambda: scene.add_point_light((0, 0, 0), (1, 1, 1))):
        assert raised(use).message == "the scene is closed"
    assert not (tmp_path / "x.tpb").exists()


def expect(kind, parameter, call):
    with pytest.raises(kind) as info:
        call()
    assert parameter in str(info.value), (parameter, str(info.value))


def test_wrong_shapes_and_dtypes_name_the_parameter():
    positions, coefficients = probes()
    store = Store.build(positions, coefficients)
    expect(ValueError, "positions", lambda: Store.build(positions[:, :2]))
    expect(ValueError, "positions", lambda: Store.build(np.zeros((2, 3, 1), np.float32)))
    expect(TypeError, "positions", lambda: Store.build(positions.astype(np.complex64)))
    expect(TypeError, "positions", lambda: Store.build(positions > 0.5))
    expect(TypeError, "positions", lambda: Store.build([["a", "b", "c"]]))
    expect(ValueError, "positions", lambda: Store.build([[0, 0, 0], [1, 1]]))
    expect(ValueError, "sh", lambda: Store.build(positions, coefficients[:, :9]))
    expect(ValueError, "sh", lambda: Store.build(positions, coefficients[:5]))
    expect(ValueError, "points", lambda: store.interpolate(positions[:, :2]))
    expect(TypeError, "points", lambda: store.weights(np.array([["x", "y", "z"]])))
    expect(ValueError, "hints", lambda: store.interpolate(positions, hints=[-1, -1]))
    expect(TypeError, "hints", lambda: store.interpolate(positions, hints=np.zeros(len(positions))))
    expect(ValueError, "hints", lambda: store.interpolate(positions, hints=np.full(len(positions), 2 ** 40)))
    expect(ValueError, "hints", lambda: store.interpolate(positions[0], hints=[1, 2]))
    expect(ValueError, "point", lambda: store.locate(positions[:2, :2]))
    expect(ValueError, "hint", lambda: store.locate(positions[:2], hint=[-1, -1, -1]))
    expect(ValueError, "sh", lambda: sh.eval_radiance(np.zeros(9), (0, 0, 1)))
    expect(ValueError, "normal", lambda: sh.eval_irradiance(np.zeros(27), (0, 1)))
    expect(TypeError, "rgb", lambda: sh.ambient(["r", "g", "b"]))
    expect(TypeError, "sh", lambda: sh.apply_options([["x"] * 27]))
    expect(TypeError, "normals", lambda: sh.eval_irradiance_ex(np.zeros(27), [["a", "b", "c"]]))
    expect(ValueError, "normals", lambda: sh.eval_irradiance_ex(np.zeros(27), np.zeros((2, 2))))
    expect(ValueError, "planes", lambda: shadow_caster_volume(CUBE[:, :3], ("point", (0, 5, 0))))
    expect(ValueError, "box_min", lambda: volume_test_aabb(CUBE, (0, 0), (1, 1, 1)))
    expect(ValueError, "center", lambda: volume_test_sphere(CUBE, (0, 0, 0, 0), 1.0))
    scene = Scene()
    quad = np.array([[0, 0, 0], [1, 0, 0], [1, 0, 1], [0, 0, 1]], np.float32)
    expect(ValueError, "vertices", lambda: scene.add_mesh(quad[:, :2], [[0, 1, 2]]))
    expect(ValueError, "indices", lambda: scene.add_mesh(quad, [[0, 1, 2, 3]]))
    expect(TypeError, "indices", lambda: scene.add_mesh(quad, [[0.0, 1.0, 2.0]]))
    expect(ValueError, "indices", lambda: scene.add_mesh(quad, [[0, -1, 2]]))
    expect(ValueError, "albedo", lambda: scene.add_mesh(quad, [[0, 1, 2]], albedo=(1, 1)))
    expect(ValueError, "direction", lambda: scene.add_directional_light((0, -1), (1, 1, 1)))
    expect(ValueError, "mode", lambda: scene.add_directional_light((0, -1, 0), (1, 1, 1), mode="sometimes"))
    expect(ValueError, "positions", lambda: bake(scene, np.zeros((2, 2), np.float32)))
    expect(ValueError, "rays", lambda: bake(scene, np.zeros((2, 3), np.float32), rays=-1))
    # float64 and integer positions are converted, not refused.
    assert Store.build(positions.astype(np.float64), coefficients).to_bytes() == store.to_bytes()


# Loads the package with a library whose tp_version reports 9.1.0: ctypes.CDLL is wrapped before the import.
FAKE_VERSION = """
import ctypes
class FakeVersion(ctypes.CDLL):
    def __getattr__(self, name):
        function = super().__getattr__(name)
        if name != "tp_version":
            return function
        fake = lambda: (9 << 16) | (1 << 8)
        setattr(self, name, fake)  # later look-ups find the attribute, as CDLL caches its functions
        return fake
ctypes.CDLL = FakeVersion
try:
    import tetprobe
except Exception as error:
    print(type(error).__name__, getattr(getattr(error, "status", None), "name", None))
    print(error)
else:
    print("imported", tetprobe.library_version())
"""


def test_a_library_of_another_version_is_refused_at_import():
    result = subprocess.run([sys.executable, "-c", FAKE_VERSION], capture_output=True, text=True, timeout=60)
    assert result.returncode == 0, result.stderr
    kind, message = result.stdout.splitlines()
    assert kind == "Error VERSION"
    assert message.startswith("TP_ERROR_VERSION: libtetprobe 9.1.0 at %s does not match the tetprobe package %s"
                              % (tetprobe.library_path, tetprobe.__version__))
    assert "TETPROBE_LIBRARY" in message
