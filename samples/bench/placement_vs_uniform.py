"""Placement quality on the two rooms: automatically placed probes against a uniform subsample of the same
candidates and the scene's hand-placed probes, each baked at 1,024 rays and judged at 600 random free
points against a 1,024-ray bake there (mean over the points of the relative irradiance error, RMS over
normals and channels), and the placement's own error curve (its estimate of the luminance irradiance's
interpolation error at validation points against the number of probes). Run from the repository root:

    TETPROBE_LIBRARY=build/libtetprobe.so PYTHONPATH=bindings/python /usr/bin/python3 samples/bench/placement_vs_uniform.py [DIR]

With DIR (as `make bench` runs it) it also writes DIR/placement.json for report.py, or a "not_run" reason
when the bindings, numpy or the placement fail:
    {"part": "placement", "scene": str, "spacing": 0.5, "candidates": int, "placement_rays": int,
     "reference_rays": int, "query_points": int,
     "error_curve": [[probes, error], ...],   # the placement to the largest target, counts increasing
     "comparison": [{"probes": int, "placed": float, "uniform": float, "placement_seconds": float}, ...],
     "hand_placed": {"probes": int, "error": float}}
"""
import json
import os
import sys
import time

SCENE = "samples/scenes/two_rooms.json"
TARGETS = (100, 200, 400)
REFERENCE_RAYS = 1024


def measure():
    import numpy as np
    import tetprobe

    cosine_lobe = np.array([np.pi] + [2 * np.pi / 3] * 3 + [np.pi / 4] * 5)

    def irradiance(sh):
        return (sh.reshape(-1, 3, 9) * cosine_lobe).reshape(-1, 27)

    scene = tetprobe.Scene.load(SCENE)
    candidates = tetprobe.place_probes(scene, spacing=0.5, error_bound=0).positions
    rng = np.random.default_rng(1)
    points = []
    while len(points) < 600:  # inside the rooms, off the shared wall and the table
        p = rng.uniform([0.3, 0.3, 0.3], [7.9, 2.7, 3.7])
        if 3.8 < p[0] < 4.4 or (5.4 < p[0] < 7.0 and 1.2 < p[2] < 2.8 and p[1] < 1.0):
            continue
        points.append(p)
    points = np.array(points, np.float32)
    reference = irradiance(tetprobe.bake(scene, points, rays=REFERENCE_RAYS, bounces=2, seed=7))

    def error(positions):
        sh = tetprobe.bake(scene, positions, rays=REFERENCE_RAYS, bounces=2, seed=7)
        interpolated, _ = tetprobe.Store.build(positions, sh).interpolate(points)
        d = np.linalg.norm(irradiance(interpolated) - reference, axis=1) / np.linalg.norm(reference, axis=1)
        return float(d.mean())

    comparison, curve = [], []
    for n in TARGETS:
        start = time.time()
        placement = tetprobe.place_probes(scene, spacing=0.5, target=n)
        seconds = time.time() - start
        # The largest target's curve: the greedy's rounds through the smaller counts, then its own result.
        curve = [[int(c), float(e)] for c, e in placement.error_curve]
        uniform = candidates[((2 * np.arange(n) + 1) * len(candidates)) // (2 * n)]
        comparison.append({"probes": n, "placed": error(placement.positions), "uniform": error(uniform),
                           "placement_seconds": seconds})
    return {"part": "placement", "scene": SCENE, "spacing": 0.5, "candidates": int(len(candidates)),
            "placement_rays": 128, "reference_rays": REFERENCE_RAYS, "query_points": int(len(points)),
            "error_curve": curve, "comparison": comparison,
            "hand_placed": {"probes": int(len(scene.probes)), "error": error(scene.probes)}}


def main(argv):
    out_dir = argv[1] if len(argv) > 1 else None
    try:
        result = measure()
    except Exception as e:  # noqa: BLE001  (the report says why instead of dropping the part)
        if out_dir is None:
            raise
        result = {"part": "placement", "not_run": "placement_vs_uniform.py failed: %s: %s" % (type(e).__name__, e)}
    if out_dir is not None:
        path = os.path.join(out_dir, "placement.json")
        with open(path + ".tmp", "w") as f:
            json.dump(result, f, indent=1)
        os.replace(path + ".tmp", path)
    if "not_run" in result:
        print(result["not_run"])
        return 1
    print("| probes | placed | uniform subsample | placement s |")
    print("| ---: | ---: | ---: | ---: |")
    for row in result["comparison"]:
        print("| %d of %d | %.3f | %.3f | %.2f |" % (row["probes"], result["candidates"], row["placed"],
                                                   row["uniform"], row["placement_seconds"]))
    print("hand-placed (%d): %.3f" % (result["hand_placed"]["probes"], result["hand_placed"]["error"]))
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
