"""The audit of the public API's argument types: every parameter of every public function and method, given a value
of the wrong type, raises TypeError naming that parameter (never an AttributeError, a ctypes error or a crash).

Each public callable has a valid call below; the test swaps one argument at a time for a wrong one. A new public
function fails test_every_public_callable_is_audited until it is added here."""
import inspect
import os

import numpy as np
import pytest

import tetprobe
from tetprobe import Scene, Store, sh, tool

from test_docs import function_of, public_callables

SCENES = os.path.join(os.path.dirname(__file__), "..", "..", "samples", "scenes")
QUAD = np.array([[0, 0, 0], [1, 0, 0], [1, 0, 1], [0, 0, 1]], np.float32)
CUBE = np.array([[1, 0, 0, 1], [-1, 0, 0, 1], [0, 1, 0, 1], [0, -1, 0, 1], [0, 0, 1, 1], [0, 0, -1, 1]], np.float32)
POINTS = np.random.default_rng(1).random((6, 3)).astype(np.float32)


def room():
    """A closed one-sided box seen from inside (so placement can decide what is solid)."""
    corners = np.array([[4 * ((c >> a) & 1) for a in range(3)] for c in range(8)], np.float32)
    faces = np.array([[0, 4, 6], [0, 6, 2], [1, 3, 7], [1, 7, 5], [0, 1, 5], [0, 5, 4], [2, 6, 7], [2, 7, 3],
                      [0, 2, 3], [0, 3, 1], [4, 5, 7], [4, 7, 6]], np.uint32)[:, ::-1].copy()
    scene = Scene()
    scene.add_mesh(corners, faces, two_sided=False)
    scene.set_sky(color=(1, 1, 1))
    return scene


def store():
    return Store.build(POINTS, np.ones((6, 27), np.float32))


# name -> (the callable to call, a function giving valid keyword arguments). Methods get a fresh object each call.
CALLS = {
    "Store.build": (lambda: Store.build, lambda: dict(positions=POINTS, sh=None, compact=False, extrapolate=True,
                                                      index32=False, merge_tolerance=1e-6, flat_tolerance=1e-4,
                                                      progress=None, scene=None, occlusion=None, occlusion_lights=None,
                                                      sh_encoding="half", quantize_positions=False, layout="fast")),
    "Store.load": (lambda: Store.load, lambda: dict(source=store().to_bytes(), max_file_bytes=1 << 30)),
    "Store.save": (lambda: store().save, lambda: dict(path="replaced by the test: a file in tmp_path")),
    "Store.probe_sh": (lambda: store().probe_sh, lambda: dict(probe=0)),
    "Store.interpolate": (lambda: store().interpolate, lambda: dict(points=POINTS, hints=None, threads=1,
                                                                     chain_hints=False, occlusion=False)),
    "Store.weights": (lambda: store().weights, lambda: dict(points=POINTS, hints=None, threads=1, chain_hints=False)),
    "Store.locate": (lambda: store().locate, lambda: dict(point=POINTS[0], hint=-1)),
    "Store.sample_volume": (lambda: store().sample_volume, lambda: dict(origin=(0, 0, 0), cell_size=0.5, dims=(2, 3, 2),
                                                                         bands=2, unity=False, hint=None, out=None)),
    "Scene.load": (lambda: Scene.load, lambda: dict(path=os.path.join(SCENES, "cornell_box.json"), scale=1.0, up="+y")),
    "Scene.add_mesh": (lambda: Scene().add_mesh, lambda: dict(vertices=QUAD, indices=[[0, 1, 2]], albedo=(1, 1, 1),
                                                               emission=(0, 0, 0), two_sided=True)),
    "Scene.add_directional_light": (lambda: Scene().add_directional_light,
                                    lambda: dict(direction=(0, -1, 0), color=(1, 1, 1), intensity=1.0, mode="baked",
                                                 shadows=True)),
    "Scene.add_point_light": (lambda: Scene().add_point_light,
                              lambda: dict(position=(0, 1, 0), color=(1, 1, 1), intensity=1.0, range=5.0, mode="baked",
                                           shadows=True, near_distance=0.25)),
    "Scene.add_spot_light": (lambda: Scene().add_spot_light,
                             lambda: dict(position=(0, 1, 0), direction=(0, -1, 0), color=(1, 1, 1), intensity=1.0,
                                          range=5.0, inner_angle=20.0, outer_angle=40.0, mode="realtime",
                                          shadows=False, near_distance=0.25)),
    "Scene.set_sky": (lambda: Scene().set_sky, lambda: dict(color=(1, 1, 1), sh=None)),
    "Scene.set_playable_seeds": (lambda: Scene().set_playable_seeds, lambda: dict(positions=POINTS)),
    "bake": (lambda: tetprobe.bake, lambda: dict(scene=room(), positions=POINTS + 1, rays=4, bounces=0, seed=0,
                                                 threads=1, progress=None, culling=True)),
    "bake_plan": (lambda: tetprobe.bake_plan, lambda: dict(scene=room(), positions=POINTS + 1, rays=4, bounces=0,
                                                           seed=0, threads=1, progress=None, culling=True)),
    "bake_occlusion": (lambda: tetprobe.bake_occlusion, lambda: dict(scene=room(), positions=POINTS + 1,
                                                                     progress=None)),
    "place_probes": (lambda: tetprobe.place_probes,
                     lambda: dict(scene=room(), mode="whole", spacing=1.0, margin=0.1, walk_height=(0.0, 2.0), target=0,
                                  error_bound=0.0, rays=4, bounces=0, seed=0, threads=1, progress=None,
                                  light_clearance=1.0)),
    "find_inside_probes": (lambda: tetprobe.find_inside_probes, lambda: dict(scene=room(), positions=POINTS)),
    "fix_inside_probes": (lambda: tetprobe.fix_inside_probes, lambda: dict(scene=room(), positions=POINTS + 1,
                                                                           mode="drop", margin=0.1)),
    "shadow_caster_volume": (lambda: tetprobe.shadow_caster_volume, lambda: dict(planes=CUBE, light=("point", (0, 5, 0)))),
    "volume_test_aabb": (lambda: tetprobe.volume_test_aabb, lambda: dict(planes=CUBE, box_min=(0, 0, 0),
                                                                         box_max=(1, 1, 1))),
    "volume_test_sphere": (lambda: tetprobe.volume_test_sphere, lambda: dict(planes=CUBE, center=(0, 0, 0),
                                                                             radius=1.0)),
    "sh.eval_radiance": (lambda: sh.eval_radiance, lambda: dict(sh=np.ones(27), direction=(0, 0, 1))),
    "sh.eval_irradiance": (lambda: sh.eval_irradiance, lambda: dict(sh=np.ones(27), normal=(0, 0, 1))),
    "sh.ambient": (lambda: sh.ambient, lambda: dict(rgb=(1, 1, 1), sh=None)),
    "sh.directional": (lambda: sh.directional, lambda: dict(direction=(0, -1, 0), rgb=(1, 1, 1), sh=None)),
    "sh.eval_options": (lambda: sh.eval_options, lambda: dict(order="l2", window="sloan", strength=0.5)),
    "sh.eval_irradiance_ex": (lambda: sh.eval_irradiance_ex, lambda: dict(sh=np.ones(27), normals=(0, 0, 1),
                                                                          order="l1", window="none", strength=0.0)),
    "sh.apply_options": (lambda: sh.apply_options, lambda: dict(sh=np.ones(27), order="l2", window="sloan",
                                                                strength=0.5)),
    "sh.min_irradiance": (lambda: sh.min_irradiance, lambda: dict(sh=np.ones(27), order="l2", window="none",
                                                                  strength=0.0)),
    "sh.nonnegative_window_strength": (lambda: sh.nonnegative_window_strength, lambda: dict(sh=np.ones(27),
                                                                                           order="l2")),
    "status_name": (lambda: tetprobe.status_name, lambda: dict(status=4)),
    "tool.main": (lambda: tool.main, lambda: dict(argv=["version"])),
}

# Public names without parameters to get wrong, or that are not called with arguments.
NO_ARGUMENTS = {"Store", "Scene", "Error", "Status", "Placement", "Store.to_bytes", "Store.info", "Store.close",
                "Scene.close", "Scene.probes", "Scene.notes", "Scene.up", "library_version", "library_path", "tool.find_tool",
                "tool.tool_candidates"}
# Parameters where a string is a valid value (paths, names) or whose wrong strings are values, not types.
STRINGS_ALLOWED = {"path", "source", "scene", "mode", "order", "window", "up", "sh_encoding", "layout"}


class Opaque:
    """A value of no type the API takes."""


def test_every_public_callable_is_audited():
    names = {name for name, _ in public_callables()}
    assert names - set(CALLS) - NO_ARGUMENTS == set()
    assert set(CALLS) <= names
    for name, (target, arguments) in CALLS.items():
        parameters = [p for p in inspect.signature(target()).parameters]
        assert sorted(parameters) == sorted(arguments()), name


@pytest.mark.parametrize("name", sorted(CALLS))
def test_a_wrong_type_is_a_type_error_naming_the_parameter(name, monkeypatch, tmp_path):
    target, arguments = CALLS[name]
    if name == "tool.main":
        monkeypatch.setenv("TETPROBE_TOOL", "/bin/true")
    if name == "Store.save":
        arguments_of = lambda: dict(path=tmp_path / "x.tpb")  # noqa: E731
    else:
        arguments_of = arguments
    target()(**arguments_of())  # the valid call works
    for parameter in arguments_of():
        wrong_values = [Opaque()] + ([] if parameter in STRINGS_ALLOWED else ["1"])
        for wrong in wrong_values:
            given = arguments_of()
            given[parameter] = wrong
            with pytest.raises(TypeError) as raised:
                target()(**given)
            assert parameter in str(raised.value), (name, parameter, wrong, str(raised.value))


def test_scene_properties_and_paths_for_scenes(tmp_path):
    scene = Scene()
    with pytest.raises(TypeError, match="positions"):
        scene.probes = Opaque()
    with pytest.raises(TypeError, match="up"):
        scene.up = Opaque()
    # Every `scene` parameter takes a scene file's path: the file is loaded for the call.
    path = os.path.join(SCENES, "two_rooms.json")
    probes = Scene.load(path).probes
    positions = probes[:30]
    with Scene.load(path) as loaded:
        assert np.array_equal(tetprobe.bake(path, positions, rays=8, seed=1),
                              tetprobe.bake(loaded, positions, rays=8, seed=1))
        assert tetprobe.bake_plan(path, positions, rays=8)["text"] == tetprobe.bake_plan(loaded, positions, rays=8)["text"]
        assert np.array_equal(tetprobe.find_inside_probes(path, probes), tetprobe.find_inside_probes(loaded, probes))
        leak_from_path = Store.build(probes, scene=path)
        leak = Store.build(probes, scene=loaded)
    assert leak_from_path.to_bytes() == leak.to_bytes() and leak.info()["leak_edges"] > 0
    with pytest.raises(tetprobe.Error) as raised:
        Store.build(probes, scene=tmp_path / "missing.json")
    assert raised.value.status == tetprobe.Status.IO
