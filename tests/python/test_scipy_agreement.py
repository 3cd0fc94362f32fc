"""Inside the convex hull, tetprobe's weights are the Delaunay barycentrics scipy (Qhull) gives.

On general-position sets, anisotropic and offset (a 50 x 2 x 8 box at (300, -20, 75)) and a random
cloud, at thousands of random points strictly inside the hull:
- where scipy's simplex is well shaped, the weights equal scipy's barycentrics (find_simplex +
  transform) on the same float32 positions within 1e-5, probe for probe (input indices); in slivers
  (where the store's re-rounding of positions to its local frame alone moves them by more) within
  1e-3 (the old builder's peeled hull slivers were off by 0.55); points are drawn in the bounding box
  and in every simplex on the hull;
- everywhere inside, a random field interpolated from tetprobe's weights equals
  LinearNDInterpolator's; in slivers (where Qhull's rounding may choose the other tetrahedralization
  of nearly cospherical points) the weights still reproduce the point and lie in [0, 1].
And a query exactly at any probe returns weight 1.0 there and 0.0 everywhere else, also on a rotated
lattice (many cospherical probes) at the same offset.

API used (the package's help, help(tetprobe.Store)): Store.build(positions[N, 3]) and
store.weights(points[M, 3], hints=None) -> (indices[M, 4] input indices, weights[M, 4], hints[M]).
"""
import numpy as np
import pytest
from scipy.interpolate import LinearNDInterpolator
from scipy.spatial import Delaunay

from tetprobe import Store

OFFSET = np.array([300.0, -20.0, 75.0])
BOX = np.array([50.0, 2.0, 8.0])
TOLERANCE = 1e-5
# The store keeps positions as float32 in a local frame (world minus the bounding box's centre), so
# its exact barycentrics are those of positions re-rounded by up to half an ulp: in thin simplices
# that alone moves them by more than 1e-5 (seen: 1.5e-5 in the random cloud). Simplices where that
# rounding could move a weight by more than TOLERANCE / 2 count as slivers, and are compared within
# SLIVER_TOLERANCE, which still tells a different cell or an extrapolation (the old builder's peeled
# hull slivers were off by 0.55).
SLIVER_TOLERANCE = 1e-3


def anisotropic_box(n=400, seed=7):
    rng = np.random.default_rng(seed)
    return (OFFSET + rng.random((n, 3)) * BOX).astype(np.float32)


def random_cloud(n=500, seed=8):
    rng = np.random.default_rng(seed)
    return rng.uniform(-10.0, 10.0, (n, 3)).astype(np.float32)


def rotated_lattice(n=8, seed=9, spacing=1.0):
    rng = np.random.default_rng(seed)
    q, r = np.linalg.qr(rng.normal(size=(3, 3)))
    rotation = q * np.sign(np.diag(r))
    if np.linalg.det(rotation) < 0:
        rotation[:, 0] = -rotation[:, 0]
    grid = np.stack(np.meshgrid(*[np.arange(n)] * 3, indexing="ij"), -1).reshape(-1, 3) * spacing
    return (OFFSET + (grid - grid.mean(0)) @ rotation.T).astype(np.float32)


SETS = {"anisotropic box 50x2x8 at (300,-20,75)": anisotropic_box, "random cloud": random_cloud}


def rounding_sensitivity(tri, positions):
    """Per simplex, a bound on how far its barycentrics move when the store re-rounds the positions
    and the query to float32 in its local frame (world minus the bounding box's centre): half an ulp
    of the largest local coordinate of each axis on each of the five points, times the gradients."""
    t = tri.transform[:, :3]                                   # rows: gradients of b0..b2
    gradients = np.concatenate([t, -t.sum(axis=1, keepdims=True)], axis=1)  # and of b3
    half_extent = 0.5 * (positions.max(0).astype(np.float64) - positions.min(0))
    half_ulp = 2.0 ** (np.floor(np.log2(half_extent)) - 24)   # per axis
    return 2.0 * (np.abs(gradients) * half_ulp).sum(axis=2).max(axis=1)


def scipy_barycentrics(tri, points):
    """(simplex[M], barycentrics[M, 4]) of float64 points; simplex -1 outside the hull."""
    simplex = tri.find_simplex(points)
    t = tri.transform[simplex]
    b = np.einsum("mij,mj->mi", t[:, :3], points - t[:, 3])
    return simplex, np.hstack([b, 1.0 - b.sum(axis=1, keepdims=True)])


def dense(indices, weights, n):
    """Rows of probe -> weight over all n input probes (repeated slots summed)."""
    out = np.zeros((indices.shape[0], n))
    np.add.at(out, (np.repeat(np.arange(indices.shape[0]), 4), indices.reshape(-1)), weights.reshape(-1))
    return out


def strictly_inside(tri, points):
    simplex, b = scipy_barycentrics(tri, points.astype(np.float64))
    return points[(simplex >= 0) & (b.min(axis=1) > 1e-7)]


def strictly_inside_points(tri, positions, m, seed):
    """m float32 points drawn in the bounding box, kept where scipy puts them strictly inside a simplex."""
    rng = np.random.default_rng(seed)
    lo, hi = positions.min(0).astype(np.float64), positions.max(0).astype(np.float64)
    points = strictly_inside(tri, (lo + rng.random((6 * m, 3)) * (hi - lo)).astype(np.float32))[:m]
    assert points.shape[0] == m, "not enough points inside the hull"
    return points


def hull_simplex_points(tri, per_simplex, seed):
    """Random float32 points in every simplex on the hull (where the old builder peeled slivers away),
    kept where rounding to float32 left them strictly inside."""
    rng = np.random.default_rng(seed)
    hull = np.flatnonzero((tri.neighbors == -1).any(axis=1))
    simplices = np.repeat(hull, per_simplex)
    b = rng.dirichlet(np.ones(4), simplices.size)
    points = np.einsum("mk,mkj->mj", b, tri.points[tri.simplices[simplices]]).astype(np.float32)
    return strictly_inside(tri, points)


@pytest.mark.parametrize("name", sorted(SETS))
def test_weights_equal_scipy_delaunay_barycentrics_inside_the_hull(name):
    positions = SETS[name]()
    n = positions.shape[0]
    store = Store.build(positions)
    tri = Delaunay(positions.astype(np.float64))
    points = np.vstack([strictly_inside_points(tri, positions, 5000, seed=11), hull_simplex_points(tri, 2, seed=13)])

    indices, weights, hints = store.weights(points)
    assert indices.shape == (points.shape[0], 4) and weights.shape == (points.shape[0], 4)
    assert hints.shape == (points.shape[0],)
    ours = dense(indices, weights, n)

    simplex, b = scipy_barycentrics(tri, points.astype(np.float64))
    theirs = np.zeros_like(ours)
    np.put_along_axis(theirs, tri.simplices[simplex], b, axis=1)
    well_shaped = rounding_sensitivity(tri, positions)[simplex] <= TOLERANCE / 2
    # The comparison must be about the bulk of the points, not a handful.
    assert well_shaped.mean() > 0.9, "too many slivers (%d of %d)" % ((~well_shaped).sum(), len(points))

    # Within 1e-5 where scipy's simplex is well shaped, within SLIVER_TOLERANCE in slivers.
    difference = np.abs(ours - theirs).max(axis=1)
    bad = np.flatnonzero(difference > np.where(well_shaped, TOLERANCE, SLIVER_TOLERANCE))
    assert bad.size == 0, "%d of %d points differ from scipy by up to %.3g; first %s: ours %s %s, scipy %s %s" % (
        bad.size, len(points), difference[bad].max(), points[bad[0]].tolist(), indices[bad[0]].tolist(),
        weights[bad[0]].tolist(), tri.simplices[simplex[bad[0]]].tolist(), b[bad[0]].tolist())

    # Everywhere inside: valid weights that reproduce the point (linear precision) ...
    assert np.all(weights >= 0) and np.all(weights <= 1)
    assert np.allclose(weights.sum(axis=1), 1.0, atol=1e-6)
    reproduced = np.einsum("mk,mkj->mj", weights.astype(np.float64), positions.astype(np.float64)[indices])
    scale = np.abs(positions - positions.mean(0)).max()
    assert np.abs(reproduced - points).max() <= 1e-5 * scale
    # ... and a random field interpolated as LinearNDInterpolator does it, off the slivers.
    field = np.random.default_rng(12).uniform(-1.0, 1.0, n)
    expected = LinearNDInterpolator(tri, field)(points.astype(np.float64))
    got = ours @ field
    assert np.abs(got - expected)[well_shaped].max() <= TOLERANCE

    # Hints from the first pass change nothing.
    indices2, weights2, _ = store.weights(points, hints)
    assert np.array_equal(dense(indices2, weights2, n), ours)


@pytest.mark.parametrize("name", sorted(SETS) + ["rotated lattice 8^3 at (300,-20,75)"])
def test_a_query_at_a_probe_weighs_it_exactly_one(name):
    positions = SETS[name]() if name in SETS else rotated_lattice()
    n = positions.shape[0]
    store = Store.build(positions)
    assert store.info()["merged_probes"] == 0
    for hints in (None, "chained"):
        if hints is None:
            indices, weights, _ = store.weights(positions)
        else:  # a hint from the previous probe's cell, as a moving object would have
            _, _, cells = store.weights(positions)
            indices, weights, _ = store.weights(positions, np.roll(cells, 1))
        ours = dense(indices, weights, n)
        at_probe = ours[np.arange(n), np.arange(n)]
        wrong = np.flatnonzero(at_probe != 1.0)
        assert wrong.size == 0, "%d of %d probes do not weigh 1.0 at themselves; first: probe %d at %s -> %s %s" % (
            wrong.size, n, wrong[0], positions[wrong[0]].tolist(), indices[wrong[0]].tolist(),
            weights[wrong[0]].tolist())
        ours[np.arange(n), np.arange(n)] = 0.0
        assert np.count_nonzero(ours) == 0
