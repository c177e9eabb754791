"""Every kind of array a user may pass: the same result where the points are the same, a clear
surfgrow.InvalidParameterError (also a ValueError) otherwise, never a crash."""

import gc
import sys

import numpy as np
import pytest

import surfgrow


@pytest.fixture(scope="module")
def pts(corner):
    return np.array(corner.points)  # float32, C-contiguous, writeable copy


@pytest.fixture(scope="module")
def reference(pts, corner):
    return surfgrow.grow(pts, viewpoint=corner.cloud.scan_origins[0])


def same(r, ref):
    return np.array_equal(r.labels, ref.labels) and np.array_equal(r.normals, ref.normals)


@pytest.mark.parametrize("make", [
    lambda p: p.astype(np.float64),                      # Open3D's np.asarray(pcd.points)
    lambda p: np.asfortranarray(p),                       # column-major
    lambda p: np.ascontiguousarray(np.repeat(p, 2, axis=0)[::2]),  # a copy of a strided view
    lambda p: np.repeat(p, 2, axis=0)[::2],               # strided rows
    lambda p: np.hstack([p, np.ones((len(p), 1), np.float32)])[:, :3],  # column slice
    lambda p: p.astype(">f4"),                            # big-endian
    lambda p: p.astype(np.float64).tolist(),              # a Python list (slow, but works)
], ids=["float64", "fortran", "copy", "strided", "column-slice", "big-endian", "list"])
def test_layouts_give_the_same_result(make, pts, reference, corner):
    r = surfgrow.grow(make(pts), viewpoint=corner.cloud.scan_origins[0])
    assert same(r, reference)


def test_float32_is_read_in_place(pts, reference, corner):
    """A C-ordered float32 array is not copied: the result holds the array itself (one more
    reference while it lives) and later calls read it again, so a change after grow shows in
    bound_planes. copy=True makes a private copy that a change does not reach."""
    vp = corner.cloud.scan_origins[0]
    mine = pts.copy()
    refs = sys.getrefcount(mine)
    shared = surfgrow.grow(mine, viewpoint=vp)
    private = surfgrow.grow(mine, viewpoint=vp, copy=True)
    assert sys.getrefcount(mine) == refs + 1  # held by `shared` only
    assert same(shared, reference) and same(private, reference)
    def centroids(r):
        return np.array([f["centroid"] for f in surfgrow.bound_planes(r).faces])

    before = centroids(shared)
    assert np.array_equal(centroids(private), before)
    mine[:, 0] += 5.0  # the caller reuses its buffer: `shared`'s points are now 5 m off
    assert np.mean(centroids(shared)[:, 0]) > np.mean(before[:, 0]) + 4.0
    assert np.array_equal(centroids(private), before)
    del shared
    assert sys.getrefcount(mine) == refs


@pytest.mark.parametrize("make", [
    lambda p: p.astype(np.float64),
    lambda p: p[::-1][::-1],  # a view, still C-ordered: read in place
    lambda p: np.asfortranarray(p),
], ids=["float64", "view", "fortran"])
def test_what_is_held_lives_as_long_as_the_result(make, pts, reference, corner):
    """Whatever was passed (converted or held) stays valid after the caller drops it."""
    r = surfgrow.grow(make(pts.copy()), viewpoint=corner.cloud.scan_origins[0])
    gc.collect()
    assert same(r, reference)
    planes = surfgrow.bound_planes(r)
    assert len(planes) >= 3
    assert len(r.cloud) == len(pts) and np.array_equal(r.cloud.points, pts)


def test_misaligned_float32_is_copied(pts, reference, corner):
    """float32 rows at an odd address (a byte buffer's slice) are copied, not read unaligned."""
    raw = np.zeros(pts.nbytes + 1, np.uint8)
    odd = raw[1:].view(np.float32).reshape(-1, 3)
    odd[:] = pts
    assert not odd.flags.aligned
    refs = sys.getrefcount(odd)
    r = surfgrow.grow(odd, viewpoint=corner.cloud.scan_origins[0])
    assert sys.getrefcount(odd) == refs
    assert same(r, reference)


def test_integer_points():
    """Integer coordinates (e.g. millimetres) are converted once, like float64."""
    g = np.stack(np.meshgrid(np.arange(0, 300, 3), np.arange(0, 300, 3), [0]), -1).reshape(-1, 3)
    r = surfgrow.grow(g.astype(np.int32), mu=12, viewpoint=[150, 150, 500])
    assert np.mean(r.labels >= 0) > 0.95
    assert np.allclose(np.abs(r.normals[:, 2]), 1.0)


@pytest.mark.parametrize("bad, message", [
    (np.zeros((10, 2)), r"shape \(N, 3\), not \(10, 2\)"),
    (np.zeros((10, 4)), r"pass points\[:, :3\]"),
    (np.zeros(30), r"shape \(N, 3\), not \(30,\)"),
    (np.zeros((2, 5, 3)), r"shape \(N, 3\)"),
    (np.zeros((10, 3), dtype=np.complex64), "real numbers"),
    (np.array([["a", "b", "c"]]), "real numbers"),
    (np.zeros((10, 3), dtype=object), "real numbers"),
    (np.zeros((10, 3), dtype=bool), "real numbers"),
    ("points.ply", "real numbers"),
    (None, "None"),
])
def test_bad_arrays_raise(bad, message):
    with pytest.raises(surfgrow.InvalidParameterError, match=message) as e:
        surfgrow.grow(bad)
    assert isinstance(e.value, ValueError) and e.value.code == 3


def test_empty_cloud():
    r = surfgrow.grow(np.zeros((0, 3), np.float32))
    assert len(r) == 0 and r.labels.shape == (0,) and r.normals.shape == (0, 3)
    assert r.summary["points_in"] == 0
    assert len(surfgrow.bound_planes(r)) == 0
    assert len(surfgrow.occupancy(r)) == 0


def test_nan_rows_are_kept_and_unregistered(pts, corner):
    p = pts.copy()
    bad = np.arange(0, len(p), 50)
    p[bad[::2]] = np.nan
    p[bad[1::2], 1] = np.inf
    r = surfgrow.grow(p, viewpoint=corner.cloud.scan_origins[0])
    assert r.labels.shape == (len(p),)
    assert np.all(r.labels[bad] == -1)
    assert r.summary["invalid_points"] == len(bad)
    assert np.mean(r.labels[np.isfinite(p).all(axis=1)] >= 0) > 0.99


def test_all_nan():
    r = surfgrow.grow(np.full((1000, 3), np.nan))
    assert len(r) == 0 and np.all(r.labels == -1)


def test_input_is_copied_not_referenced(pts, corner):
    """The result keeps its own cloud: changing the array afterwards changes nothing."""
    p = pts.copy()
    r = surfgrow.grow(p)
    before = r.cloud.points.copy()
    p[:] = 0
    assert np.array_equal(r.cloud.points, before)
    assert not r.cloud.points.flags.writeable


def test_per_point_arrays_checked(pts):
    n = len(pts)
    with pytest.raises(surfgrow.InvalidParameterError, match="scan_index has 3 entries"):
        surfgrow.Cloud(pts, scan_index=[0, 0, 0], scan_origins=[[0, 0, 0]])
    with pytest.raises(surfgrow.InvalidParameterError, match="outside 0..0"):
        surfgrow.Cloud(pts, scan_index=np.ones(n, np.int64), scan_origins=[[0, 0, 0]])
    with pytest.raises(surfgrow.InvalidParameterError, match="needs scan_origins"):
        surfgrow.Cloud(pts, scan_index=np.zeros(n, np.int64))
    with pytest.raises(surfgrow.InvalidParameterError, match="viewpoint must be finite"):
        surfgrow.grow(pts, viewpoint=[0, np.nan, 0])
    with pytest.raises(surfgrow.InvalidParameterError, match="viewpoint must be 3 numbers"):
        surfgrow.grow(pts, viewpoint=[0, 0])
    with pytest.raises(surfgrow.InvalidParameterError, match="crop_box must be 2 rows"):
        surfgrow.grow(pts, crop_box=[[0, 0, 0]])
    with pytest.raises(surfgrow.InvalidParameterError, match="labels has 2 entries"):
        surfgrow.Cloud(pts, labels=[1, 2])


@pytest.mark.parametrize("kwargs, message", [
    (dict(mu=0), "mu"), (dict(mu=-0.01), "mu"), (dict(mu=float("nan")), "mu"),
    (dict(mu=float("inf")), "mu"), (dict(mu=1e40), "mu"), (dict(min_pts=2), "min.pts"),
    (dict(alpha=1.0), "alpha"), (dict(plane_test="ransac"), "plane_test"),
    (dict(adaptive_factor=0.5), "adaptive.factor|mu.max"), (dict(crop_radius=-1.0), "radius"),
])
def test_bad_parameters_raise(kwargs, message, pts):
    with pytest.raises(surfgrow.InvalidParameterError, match=message):
        surfgrow.grow(pts, **kwargs)


def test_absurd_thread_counts_are_clamped(pts, reference, corner):
    r = surfgrow.grow(pts, threads=100000, viewpoint=corner.cloud.scan_origins[0])
    assert same(r, reference)
    with pytest.raises(TypeError):
        surfgrow.grow(pts, threads=2**40)
