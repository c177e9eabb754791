"""Open3D interop: its clouds go in through np.asarray, results come back as arrays it takes."""

import numpy as np
import pytest

import surfgrow

o3d = pytest.importorskip("open3d")


def test_open3d_round_trip(corner, tmp_path):
    pcd = o3d.geometry.PointCloud()
    pcd.points = o3d.utility.Vector3dVector(corner.points.astype(np.float64))
    r = surfgrow.grow(np.asarray(pcd.points), viewpoint=corner.cloud.scan_origins[0])
    ref = surfgrow.grow(corner.points, viewpoint=corner.cloud.scan_origins[0])
    assert np.array_equal(r.labels, ref.labels)

    surf = o3d.geometry.PointCloud()
    surf.points = o3d.utility.Vector3dVector(r.homes)
    surf.normals = o3d.utility.Vector3dVector(r.normals)
    assert surf.has_normals() and len(surf.points) == len(r)
    # Open3D reads what surfgrow writes, normals included.
    surfgrow.write_cloud(tmp_path / "surfaces.ply", r.homes, normals=r.normals)
    back = o3d.io.read_point_cloud(str(tmp_path / "surfaces.ply"))
    assert np.allclose(np.asarray(back.points), r.homes, atol=1e-6)
    assert np.allclose(np.asarray(back.normals), r.normals, atol=1e-6)
    # ... and surfgrow reads what Open3D writes.
    o3d.io.write_point_cloud(str(tmp_path / "o3d.pcd"), pcd)
    c = surfgrow.read_cloud(tmp_path / "o3d.pcd")
    assert np.allclose(c.points, corner.points, atol=1e-6)


def test_normals_agree_with_open3d_on_a_plane():
    """On a noiseless plane both estimate the same normal (as lines)."""
    g = np.stack(np.meshgrid(np.linspace(0, 1, 100), np.linspace(0, 1, 100)), -1).reshape(-1, 2)
    pts = np.column_stack([g, 0.2 * g[:, 0] + 0.1 * g[:, 1]])
    r = surfgrow.grow(pts, mu=0.03, viewpoint=[0.5, 0.5, 2])
    pcd = o3d.geometry.PointCloud(o3d.utility.Vector3dVector(pts))
    pcd.estimate_normals(o3d.geometry.KDTreeSearchParamRadius(0.03))
    truth = np.array([-0.2, -0.1, 1]) / np.linalg.norm([-0.2, -0.1, 1])
    assert np.all(np.abs(r.normals @ truth) > 0.9999)
    assert np.median(np.abs(np.asarray(pcd.normals) @ truth)) > 0.9999
