"""Placement quality on the two rooms: automatically placed probes against a uniform subsample of the same
candidates and the scene's hand-placed probes, each baked at 1,024 rays and judged at 600 random free
points against a 1,024-ray bake there (mean over the points of the relative irradiance error, RMS over
normals and channels). Run from the repository root:

    TETPROBE_LIBRARY=build/libtetprobe.so PYTHONPATH=bindings/python /usr/bin/python3 samples/bench/placement_vs_uniform.py
"""
import time

import numpy as np

import tetprobe

COSINE_LOBE = np.array([np.pi] + [2 * np.pi / 3] * 3 + [np.pi / 4] * 5)


def irradiance(sh):
    return (sh.reshape(-1, 3, 9) * COSINE_LOBE).reshape(-1, 27)


def main():
    scene = tetprobe.Scene.load("samples/scenes/two_rooms.json")
    candidates = tetprobe.place_probes(scene, spacing=0.5, error_bound=0).positions
    rng = np.random.default_rng(1)
    points = []
    while len(points) < 600:  # inside the rooms, off the shared wall and the table
        p = rng.uniform([0.3, 0.3, 0.3], [7.9, 2.7, 3.7])
        if 3.8 < p[0] < 4.4 or (5.4 < p[0] < 7.0 and 1.2 < p[2] < 2.8 and p[1] < 1.0):
            continue
        points.append(p)
    points = np.array(points, np.float32)
    reference = irradiance(tetprobe.bake(scene, points, rays=1024, bounces=2, seed=7))

    def error(positions):
        sh = tetprobe.bake(scene, positions, rays=1024, bounces=2, seed=7)
        interpolated, _ = tetprobe.Store.build(positions, sh).interpolate(points)
        d = np.linalg.norm(irradiance(interpolated) - reference, axis=1) / np.linalg.norm(reference, axis=1)
        return d.mean()

    print("| probes | placed | uniform subsample | placement s |")
    print("| ---: | ---: | ---: | ---: |")
    for n in (100, 200, 400):
        start = time.time()
        placed = tetprobe.place_probes(scene, spacing=0.5, target=n).positions
        seconds = time.time() - start
        uniform = candidates[((2 * np.arange(n) + 1) * len(candidates)) // (2 * n)]
        print("| %d of %d | %.3f | %.3f | %.2f |" % (n, len(candidates), error(placed), error(uniform), seconds))
    print("hand-placed (%d): %.3f" % (len(scene.probes), error(scene.probes)))


if __name__ == "__main__":
    main()
