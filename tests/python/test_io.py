"""read_cloud / write_cloud round trips, and PointCloud2 buffers without a Python loop."""

import numpy as np
import pytest

import surfgrow


@pytest.mark.parametrize("name, encoding", [
    ("c.ply", None), ("c.ply", "ascii"), ("c.ply", "binary_big_endian"), ("c.pcd", None),
    ("c.pcd", "ascii"), ("c.pcd", "binary_compressed"), ("c.xyz", None),
])
def test_round_trip_with_normals_and_labels(tmp_path, corner_result, name, encoding):
    r = corner_result
    pts = r.homes.astype(np.float32)
    normals = r.normals.astype(np.float32)
    labels = np.arange(len(pts), dtype=np.int32)
    surfgrow.write_cloud(tmp_path / name, pts, normals=normals, labels=labels, encoding=encoding)
    back = surfgrow.read_cloud(tmp_path / name)
    assert np.array_equal(back.points, pts)
    assert back.normals is not None and np.array_equal(back.normals, normals)
    if not name.endswith(".xyz"):
        assert np.array_equal(back.labels, labels)


def test_cloud_round_trip_keeps_scans(tmp_path, corner):
    surfgrow.write_cloud(tmp_path / "scan.ply", corner.cloud)
    back = surfgrow.read_cloud(tmp_path / "scan.ply")
    assert np.array_equal(back.points, corner.points)
    assert np.array_equal(back.labels, corner.cloud.labels)


def test_normals_checked(tmp_path):
    with pytest.raises(surfgrow.InvalidParameterError, match="normals has 2 entries"):
        surfgrow.write_cloud(tmp_path / "x.ply", np.zeros((3, 3)), normals=np.zeros((2, 3)))
    assert not (tmp_path / "x.ply").exists()


def test_read_format_override(tmp_path):
    p = tmp_path / "points.dat"
    p.write_text("0 0 0\n1 0 0\n0 1 0\n")
    c = surfgrow.read_cloud(p, format="text")
    assert len(c) == 3 and np.array_equal(c.points[1], [1, 0, 0])


def pointcloud2(points, extra_before=4, extra_after=6, dtype="<f4", big=False, pad_row=0,
                width=None):
    """A PointCloud2-like buffer: padding fields around x y z, optional row padding."""
    n = len(points)
    size = np.dtype(dtype).itemsize
    step = extra_before + 3 * size + extra_after
    width = width or n
    height = n // width
    row_step = width * step + pad_row
    buf = np.zeros(height * row_step, np.uint8)
    order = ">" if big else "<"
    vals = points.astype(order + dtype[1:])
    for i in range(n):
        row, col = divmod(i, width)
        at = row * row_step + col * step + extra_before
        buf[at:at + 3 * size] = np.frombuffer(vals[i].tobytes(), np.uint8)
    datatype = {"f4": 7, "f8": 8, "i2": 3}[dtype[1:]]
    fields = [("x", extra_before, datatype), ("y", extra_before + size, datatype),
              ("z", extra_before + 2 * size, datatype), ("intensity", 0, 7)]
    return buf.tobytes(), fields, step, width, height, row_step


class Msg:
    """What rclpy gives: the attributes of sensor_msgs.msg.PointCloud2."""

    class Field:
        def __init__(self, name, offset, datatype):
            self.name, self.offset, self.datatype, self.count = name, offset, datatype, 1

    def __init__(self, data, fields, step, width, height, row_step, big=False):
        self.data = data
        self.fields = [Msg.Field(*f) for f in fields]
        self.point_step, self.width, self.height, self.row_step = step, width, height, row_step
        self.is_bigendian = big


@pytest.mark.parametrize("dtype, big, pad_row, width", [
    ("<f4", False, 0, None), ("<f8", False, 0, None), ("<f4", True, 0, None),
    ("<f4", False, 8, 50), ("<i2", False, 0, None),
])
def test_from_pointcloud2(dtype, big, pad_row, width):
    rng = np.random.default_rng(1)
    pts = rng.uniform(-100, 100, (200, 3)).round().astype(np.float32)
    data, fields, step, w, h, row_step = pointcloud2(pts, dtype=dtype, big=big, pad_row=pad_row,
                                                     width=width)
    xyz = surfgrow.from_pointcloud2(Msg(data, fields, step, w, h, row_step, big))
    assert xyz.shape == (200, 3)
    assert xyz.dtype == (np.float32 if dtype == "<f4" else np.float64)
    assert np.array_equal(xyz, pts)
    # The parts instead of a message; fields as dicts.
    xyz2 = surfgrow.from_pointcloud2(data=data, fields=[dict(name=f[0], offset=f[1], datatype=f[2])
                                                        for f in fields],
                                     point_step=step, width=w, height=h, row_step=row_step,
                                     is_bigendian=big)
    assert np.array_equal(xyz2, pts)


def test_from_pointcloud2_nans_and_errors():
    pts = np.array([[1, 2, 3], [np.nan, np.nan, np.nan], [4, 5, 6]], np.float32)
    data, fields, step, w, h, rs = pointcloud2(pts)
    assert surfgrow.from_pointcloud2(data=data, fields=fields, point_step=step).shape == (3, 3)
    assert surfgrow.from_pointcloud2(data=data, fields=fields, point_step=step,
                                     skip_nans=True).shape == (2, 3)
    with pytest.raises(surfgrow.InvalidParameterError, match="no field z"):
        surfgrow.from_pointcloud2(data=data, fields=fields[:2], point_step=step)
    with pytest.raises(surfgrow.InvalidParameterError, match="does not fit"):
        surfgrow.from_pointcloud2(data=data, fields=fields, point_step=8)
    with pytest.raises(surfgrow.InvalidParameterError, match="too short"):
        surfgrow.from_pointcloud2(data=data[:-5], fields=fields, point_step=step, width=3,
                                  height=1, row_step=rs)
    with pytest.raises(surfgrow.InvalidParameterError, match="unknown datatype"):
        surfgrow.from_pointcloud2(data=data, fields=[("x", 4, 9), ("y", 8, 7), ("z", 12, 7)],
                                  point_step=step)


def test_pointcloud2_into_grow(corner):
    """The full path of a ROS node: a PointCloud2 buffer to surfaces."""
    data, fields, step, w, h, rs = pointcloud2(corner.points[:20000], extra_before=0,
                                               extra_after=4)
    xyz = surfgrow.from_pointcloud2(data=data, fields=fields, point_step=step)
    r = surfgrow.grow(xyz, viewpoint=corner.cloud.scan_origins[0])
    assert np.mean(r.labels >= 0) > 0.9
