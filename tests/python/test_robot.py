"""Bound planes, coverage, occupancy and collision spheres from Python, against known answers."""

import numpy as np
import pytest

import surfgrow
from conftest import angle_deg


@pytest.fixture(scope="module")
def planes(corner_result):
    return surfgrow.bound_planes(corner_result)


def test_bound_planes_find_the_corner(planes, corner_result):
    """The room corner's floor and two walls are the three largest faces, square to each other."""
    assert len(planes) >= 3
    big = planes.normals[:3]
    # Floor normal vertical; the walls horizontal and perpendicular to each other.
    floor = int(np.argmax(np.abs(big[:, 2])))
    assert angle_deg(big[floor], [0, 0, 1]) < 0.5
    walls = [k for k in range(3) if k != floor]
    assert all(abs(big[k, 2]) < 0.01 for k in walls)
    assert abs(90 - angle_deg(big[walls[0]], big[walls[1]])) < 0.5
    faces = planes.faces
    assert faces[0]["area"] > 1.0 and faces[0]["point_count"] > 10000
    assert planes.areas[0] == faces[0]["area"]
    # The floor's plane passes through z = 0 (the scene's floor).
    f = faces[floor]
    assert abs(f["plane"][3]) < 0.005
    # Polygons in world coordinates lie on their plane.
    ring = f["polygons"][0]["outer"]
    assert ring.shape[1] == 3 and len(ring) >= 4
    assert np.max(np.abs(ring @ np.array(f["plane"][:3]) + f["plane"][3])) < 1e-9
    # Every member surface of a face points at it; per-point labels follow the surfaces.
    assert np.all(planes.plane_of_surface[f["members"]] == floor)
    pl = planes.point_labels
    lab = corner_result.labels
    assert np.array_equal(pl[lab >= 0], planes.plane_of_surface[lab[lab >= 0]])
    assert np.all(pl[lab < 0] == -1)


def test_bound_planes_with_points_given(planes, corner, corner_result):
    again = surfgrow.bound_planes(corner_result, corner.points)
    assert np.array_equal(again.planes, planes.planes)
    with pytest.raises(surfgrow.InvalidParameterError, match="rows but the result was grown"):
        surfgrow.bound_planes(corner_result, corner.points[:100])


def test_coverage(planes):
    cov = surfgrow.coverage(planes, blast_radius=0.05, standoff=0.15)
    g = len(cov)
    assert g > 100
    assert cov.stats["coverage"] > 0.95
    for name, shape in [("positions", (g, 3)), ("normals", (g, 3)), ("tool_positions", (g, 3)),
                        ("tool_axes", (g, 3)), ("orientations", (g, 4)), ("tilt_deg", (g,)),
                        ("planes", (g,)), ("transitions", (g,))]:
        assert getattr(cov, name).shape == shape, name
    # Pose: the tool stands `standoff` back along its axis, tilted 5..40 degrees off the normal.
    back = cov.positions - cov.tool_positions
    assert np.allclose(np.linalg.norm(back, axis=1), 0.15)
    assert np.allclose(back / 0.15, cov.tool_axes, atol=1e-9)
    tilt = np.degrees(np.arccos(np.clip(-np.sum(cov.tool_axes * cov.normals, axis=1), -1, 1)))
    assert np.all((tilt > 5 - 1e-6) & (tilt < 40 + 1e-6))
    assert np.allclose(tilt, cov.tilt_deg, atol=1e-6)
    # Quaternions (x, y, z, w): unit, and their z axis is the tool axis.
    q = cov.orientations
    assert np.allclose(np.linalg.norm(q, axis=1), 1) and np.all(q[:, 3] >= 0)
    x, y, z, w = q.T
    zaxis = np.stack([2 * (x * z + w * y), 2 * (y * z - w * x), 1 - 2 * (x * x + y * y)], 1)
    assert np.allclose(zaxis, cov.tool_axes, atol=1e-9)
    # Goals lie on their plane.
    pl = planes.planes[cov.planes]
    assert np.max(np.abs(np.sum(pl[:, :3] * cov.positions, axis=1) + pl[:, 3])) < 1e-6
    with pytest.raises(surfgrow.InvalidParameterError):
        surfgrow.coverage(planes, blast_radius=-1)


def test_occupancy(corner, corner_result, tmp_path):
    grid = surfgrow.occupancy(corner_result)
    assert len(grid) > 1000
    assert grid.cube_size == pytest.approx(0.012, rel=1e-5)
    reg = corner.points[corner_result.labels >= 0]
    assert np.all(grid.occupied(reg))
    assert grid.point_counts.sum() == len(reg)
    assert np.allclose(grid.centres, grid.origin + (grid.cells + 0.5) * grid.cube_size)
    # A point half a metre above the floor in the room is free (not occupied).
    assert not grid.occupied([[0.3, 0.3, 0.5]])[0]
    s = grid.write_octomap(tmp_path / "env.bt")
    assert (tmp_path / "env.bt").stat().st_size > 1000
    assert s["occupied"] == len(grid) and s["free"] > 0 and s["carving"] == "scan_origins"
    # Without origins nothing is carved; one origin given carves from it.
    plain = surfgrow.occupancy(surfgrow.grow(corner.points))
    assert plain.write_octomap(tmp_path / "plain.bt")["free"] == 0
    given = surfgrow.occupancy(corner_result, origins=corner.cloud.scan_origins[0])
    assert given.write_octomap(tmp_path / "given.bt")["carving"] == "viewpoint"


def test_collision_spheres_against_brute_force(corner_result):
    env = surfgrow.CollisionSpheres(corner_result)
    assert len(env) == len(corner_result)
    rng = np.random.default_rng(5)
    q = rng.uniform([-0.5, -0.5, -0.2], [2.0, 2.0, 1.5], size=(500, 3))
    clearance, ids = env.nearest(q)
    d = np.linalg.norm(q[:, None, :] - corner_result.homes[None, :, :], axis=2) - corner_result.radii
    assert np.allclose(clearance, d.min(axis=1), atol=1e-12)
    assert np.array_equal(ids, d.argmin(axis=1))
    # Spheres and capsules.
    sph = np.hstack([q, np.full((500, 1), 0.05)])
    c2, _ = env.nearest(sph)
    assert np.allclose(c2, clearance - 0.05)
    caps = np.hstack([q, q + [0.1, 0, 0], np.full((500, 1), 0.02)])
    c3, _ = env.nearest(caps)
    assert np.all(c3 <= clearance - 0.02 + 1e-12)
    hits = env.collides(sph)
    assert np.array_equal(hits, c2 < 0)
    assert np.array_equal(env.collides(q, tolerance=0.1), clearance < 0.1)
    with pytest.raises(surfgrow.InvalidParameterError):
        env.nearest(np.zeros((3, 5)))
    with pytest.raises(surfgrow.InvalidParameterError):
        env.nearest([[0, 0, np.nan]])


def test_collision_spheres_from_arrays():
    env = surfgrow.CollisionSpheres([[0, 0, 0], [1, 0, 0]], 0.1)
    c, i = env.nearest([[0.9, 0, 0]])
    assert i[0] == 1 and c[0] == pytest.approx(0.0)
    empty = surfgrow.CollisionSpheres(np.zeros((0, 3)), np.zeros(0))
    c, i = empty.nearest([[0, 0, 0]])
    assert np.isinf(c[0]) and i[0] == -1
