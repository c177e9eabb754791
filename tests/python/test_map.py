"""surfgrow.Map: scans added one at a time give the map of the fused cloud, as well grown as
growing it at once, and its results go on to the other stages like grow's."""

import numpy as np
import pytest

import surfgrow


@pytest.fixture(scope="module")
def two_poses():
    return surfgrow.simulate("room-corner", poses=2, seed=4)


def test_scan_by_scan_equals_the_fused_cloud_grown_at_once(two_poses):
    cloud = two_poses.cloud
    index = np.asarray(cloud.scan_index)
    origins = np.asarray(cloud.scan_origins)
    m = surfgrow.Map(mu=0.012, seed=1)
    first = m.add_scan(cloud.points[index == 0], origins[0])
    assert m.scans == 1 and len(first.labels) == int((index == 0).sum())
    r = m.add_scan(cloud.points[index == 1], origins[1])
    assert m.scans == 2
    update = m.last_update
    assert update["scan"] == 1 and update["points"] == int((index == 1).sum())
    assert update["joined"] > update["points"] // 3  # the corner seen again joins what is there
    # The map's cloud is the fused cloud; its result is scored like grow's.
    np.testing.assert_array_equal(r.cloud.points, cloud.points)
    mapped = surfgrow.evaluate(r, two_poses.truth)["metrics"]
    batch = surfgrow.evaluate(surfgrow.grow(cloud, mu=0.012, seed=1), two_poses.truth)["metrics"]
    assert mapped["registered_planar"] >= batch["registered_planar"] - 0.01
    assert mapped["normal_median"] <= batch["normal_median"] + 0.2
    assert mapped["normal_over_45"] <= batch["normal_over_45"] + 0.005
    # And goes on to the robot outputs.
    planes = surfgrow.bound_planes(r)
    assert len(planes) >= 3
    # The first result is a snapshot: the second scan did not change it.
    assert len(first.labels) == int((index == 0).sum())


def test_deterministic_and_refuses_bad_input(two_poses):
    cloud = two_poses.cloud
    index = np.asarray(cloud.scan_index)
    results = []
    for threads in (1, 2):
        m = surfgrow.Map(seed=3, threads=threads)
        m.add_scan(cloud.points[index == 0], cloud.scan_origins[0])
        results.append(m.add_scan(cloud.points[index == 1], cloud.scan_origins[1]))
    np.testing.assert_array_equal(results[0].labels, results[1].labels)
    with pytest.raises(surfgrow.InvalidParameterError):
        surfgrow.Map(join_tolerance=0.5)
    with pytest.raises(surfgrow.InvalidParameterError):
        surfgrow.Map().add_scan(cloud.points[:10], [np.nan, 0, 0])
