"""surfgrow.grow: shapes, the CLI's answer on the same file, determinism, accuracy on known planes."""

import json
import subprocess

import numpy as np
import pytest

import surfgrow
from conftest import angle_deg


def test_result_arrays(corner, corner_result):
    r = corner_result
    n, s = len(corner), len(r)
    assert s > 100
    assert r.labels.shape == (n,) and r.labels.dtype == np.int32
    assert not r.labels.flags.writeable
    # A view of the result's own labels, not a copy: the same memory on every access.
    assert np.shares_memory(r.labels, r.labels)
    assert r.labels.ctypes.data == r.labels.ctypes.data
    for name, shape, dtype in [("normals", (s, 3), np.float64), ("homes", (s, 3), np.float64),
                               ("centroids", (s, 3), np.float64), ("planes", (s, 4), np.float64),
                               ("eigenvalues", (s, 3), np.float64), ("radii", (s,), np.float64),
                               ("counts", (s,), np.uint32), ("mean_residuals", (s,), np.float64),
                               ("tolerances", (s,), np.float64)]:
        a = getattr(r, name)
        assert a.shape == shape and a.dtype == dtype, name
    assert np.allclose(np.linalg.norm(r.normals, axis=1), 1.0, atol=1e-9)
    # The plane passes through the centroid: n . c + d = 0.
    assert np.allclose(np.sum(r.planes[:, :3] * r.centroids, axis=1) + r.planes[:, 3], 0, atol=1e-9)
    # Labels name surfaces, and each surface's count is its labelled points.
    assert r.labels.min() >= -1 and r.labels.max() < s
    assert np.array_equal(np.bincount(r.labels[r.labels >= 0], minlength=s), r.counts)
    assert np.all(r.radii >= 0.012 - 1e-12)
    assert np.all(np.diff(r.eigenvalues, axis=1) >= 0)


def test_summary(corner, corner_result):
    s = corner_result.summary
    assert s["points_in"] == len(corner)
    assert s["surfaces"] == len(corner_result)
    assert s["registered"] == int(np.count_nonzero(corner_result.labels >= 0))
    assert s["registered_fraction"] == pytest.approx(s["registered"] / s["valid_points"])
    assert s["orientation"] == "scan_origins"
    sec = s["seconds"]
    assert sec["call"] >= sec["total"] > 0
    assert corner_result.parameters["mu"] == 0.012


def test_known_planes(corner, corner_result):
    """Every point registered to a surface whose normal is its true face's, with tails bounded."""
    r = corner_result
    truth = corner.truth.labels
    assert np.mean(r.labels >= 0) > 0.99
    e = surfgrow.evaluate(r, corner.truth)
    m = e["metrics"]
    assert m["registered_planar"] > 0.99
    assert m["normal_median"] < 1.0 and m["normal_p95"] < 3.0
    assert m["normal_over_45"] < 0.002
    assert m["facing_sensor"] > 0.99
    # Independently of the evaluation: the floor (the true face of the points at z = 0) has
    # vertical normals.
    pts = corner.points
    near_floor = truth[(np.abs(pts[:, 2]) < 0.003) & (truth >= 0)]
    floor_face = np.bincount(near_floor).argmax()
    floor = (truth == floor_face) & (r.labels >= 0)
    err = angle_deg(r.normals[r.labels[floor]], [0, 0, 1])
    assert floor.sum() > 10000
    assert np.percentile(err, 95) < 3.0 and np.mean(err > 45) < 0.002


def test_same_as_cli(tmp_path, cli):
    """Same file, same seed: the CLI's labels and normals, exactly."""
    subprocess.run([cli, "scan", "--scene", "room-corner", "--poses", "1", "-q", "-o",
                    str(tmp_path / "scan")], check=True)
    cloud_file = tmp_path / "scan" / "cloud.ply"
    subprocess.run([cli, "grow", str(cloud_file), "-o", str(tmp_path / "out"), "-q", "--seed", "3",
                    "--no-picture", "--no-octomap", "--no-coverage", "--no-planes",
                    "--no-occupancy"], check=True)
    r = surfgrow.grow(surfgrow.read_cloud(cloud_file), seed=3)
    labels = np.fromfile(tmp_path / "out" / "labels.bin", dtype="<i4")
    assert np.array_equal(r.labels, labels)
    # surfaces.ply: a numpy record array straight from its header.
    data = (tmp_path / "out" / "surfaces.ply").read_bytes()
    end = data.index(b"end_header\n") + len(b"end_header\n")
    props = [line.split()[1:] for line in data[:end].decode().splitlines()
             if line.startswith("property ")]
    surfaces = np.frombuffer(data[end:], dtype=[(name, {"double": "<f8", "uint": "<u4"}[kind])
                                                for kind, name in props])
    assert json.loads((tmp_path / "out" / "surfaces.json").read_text())["surfaces_file"] == \
        "surfaces.ply"
    normals = np.stack([surfaces["nx"], surfaces["ny"], surfaces["nz"]], axis=1)
    assert np.array_equal(r.normals, normals)
    homes = np.stack([surfaces["x"], surfaces["y"], surfaces["z"]], axis=1)
    assert np.array_equal(r.homes, homes)


def test_simulate_same_as_cli(tmp_path, cli, corner):
    subprocess.run([cli, "scan", "--scene", "room-corner", "--poses", "1", "--seed", "1", "-q",
                    "-o", str(tmp_path / "scan")], check=True)
    c = surfgrow.read_cloud(tmp_path / "scan" / "cloud.ply")
    assert np.array_equal(c.points, corner.points)
    assert np.array_equal(c.labels, corner.truth.labels)
    assert np.array_equal(c.scan_origins, corner.cloud.scan_origins)


def test_deterministic_across_threads(channel):
    runs = [surfgrow.grow(channel.cloud, threads=t, seed=2) for t in (1, 2, 4)]
    for r in runs[1:]:
        assert np.array_equal(r.labels, runs[0].labels)
        assert r.normals.tobytes() == runs[0].normals.tobytes()
        assert r.homes.tobytes() == runs[0].homes.tobytes()


def test_seed_changes_homes(corner):
    a = surfgrow.grow(corner.cloud, seed=1)
    b = surfgrow.grow(corner.cloud, seed=2)
    assert not np.array_equal(a.homes, b.homes)


def test_array_and_cloud_agree(corner):
    """An array carries no scan origins: with the same viewpoint the result is the Cloud's."""
    origin = corner.cloud.scan_origins[0]
    a = surfgrow.grow(corner.points, viewpoint=origin)
    c = surfgrow.grow(surfgrow.Cloud(corner.points, viewpoint=origin))
    assert np.array_equal(a.labels, c.labels) and np.array_equal(a.normals, c.normals)
    f64 = surfgrow.grow(corner.points.astype(np.float64), viewpoint=origin)
    assert np.array_equal(a.labels, f64.labels) and np.array_equal(a.normals, f64.normals)


def test_parameters_reach_the_library(corner):
    r = surfgrow.grow(corner.points, mu=0.02, min_pts=12, alpha=5, plane_test="paper",
                      adaptive_factor=2, pool_angle_deg=0, attach_leftovers=False)
    p = r.parameters
    assert p["mu"] == 0.02 and p["min_pts"] == 12 and p["alpha"] == 5
    assert p["plane_test"] == "paper" and p["mu_max"] == pytest.approx(0.04)
    assert p["attach_leftovers"] is False
    assert np.all(r.radii <= 0.04 + 1e-12)


def test_crop(corner):
    centre = corner.cloud.scan_origins[0]
    r = surfgrow.grow(corner.cloud, crop_radius=1.0, crop_center=centre)
    d = np.linalg.norm(corner.points - centre, axis=1)
    assert np.all(r.labels[d > 1.0 + 1e-6] == -1)
    assert r.summary["cropped_points"] == int(np.count_nonzero(d > 1.0 + 1e-6)) or \
        abs(r.summary["cropped_points"] - np.count_nonzero(d > 1.0)) < 10
    box = [[-0.5, -0.5, -0.1], [0.5, 0.5, 0.5]]
    r = surfgrow.grow(corner.cloud, crop_box=box)
    inside = np.all((corner.points >= np.array(box[0])) & (corner.points <= np.array(box[1])), axis=1)
    assert np.all(r.labels[~inside] == -1)


def test_georeferenced_float64(corner):
    """Coordinates of a survey frame (1e6 m) keep their precision (the readers' offset rule):
    a float32 cloud there would be quantised to 0.5 m."""
    shift = np.array([512345.0, 5412345.0, 250.0])
    origin = corner.cloud.scan_origins[0]
    near = surfgrow.grow(corner.points.astype(np.float64), viewpoint=origin)
    far = surfgrow.grow(corner.points.astype(np.float64) + shift, viewpoint=origin + shift)
    assert np.all(np.abs(far.cloud.offset - shift) < 5)  # stored relative to a rounded offset
    assert far.summary["registered_fraction"] == pytest.approx(near.summary["registered_fraction"], abs=0.002)
    assert len(far) == pytest.approx(len(near), rel=0.02)
    # Results come back in the input's coordinates: homes are input points, planes pass there.
    pts = corner.points.astype(np.float64) + shift
    ids = far.labels
    member = np.flatnonzero(ids >= 0)[::97]
    dist = np.abs(np.sum(far.planes[ids[member], :3] * pts[member], axis=1) + far.planes[ids[member], 3])
    assert np.percentile(dist, 95) < 0.012
    floor = (np.abs(corner.points[:, 2]) < 0.003) & (ids >= 0)
    err = angle_deg(far.normals[ids[floor]], [0, 0, 1])
    assert np.percentile(err, 95) < 3.0


def test_warns_when_mu_does_not_fit_the_units(corner):
    """A millimetre cloud grown with the metre default: a warning, as the CLI's note."""
    mm = corner.points.astype(np.float64) * 1000
    with pytest.warns(RuntimeWarning, match="not in the cloud's units"):
        r = surfgrow.grow(mm)
    assert r.summary["registered_fraction"] < 0.5
    import warnings
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        surfgrow.grow(mm, mu=12)  # fits: no warning


def test_simulate_drops_mixed_pixels_when_asked():
    # The pipes in front of their wall: blends in the depth gaps behind them. veil_angle drops
    # them (scanner/veil_filter.hpp); no face point goes (truth label -1: a blend or no face).
    every = surfgrow.simulate("pipes", poses=1, seed=1)
    kept = surfgrow.simulate("pipes", poses=1, seed=1, veil_angle=10.0)
    assert len(kept) < len(every) - 1000
    assert np.count_nonzero(kept.truth.labels >= 0) >= np.count_nonzero(every.truth.labels >= 0) - 10
    with pytest.raises(surfgrow.InvalidParameterError, match="mixed-pixel angle"):
        surfgrow.simulate("pipes", poses=1, seed=1, veil_angle=50.0)
