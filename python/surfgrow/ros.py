"""ROS interop: a sensor_msgs/PointCloud2 buffer as an (N, 3) array, without a Python loop."""

import numpy as np

from ._surfgrow import InvalidParameterError

# sensor_msgs/PointField datatypes.
_TYPES = {1: "i1", 2: "u1", 3: "i2", 4: "u2", 5: "i4", 6: "u4", 7: "f4", 8: "f8"}


def _field(f):
    """(name, offset, datatype) of a PointField, a dict or a tuple."""
    if isinstance(f, dict):
        return f["name"], int(f["offset"]), int(f["datatype"])
    if isinstance(f, (tuple, list)):
        return str(f[0]), int(f[1]), int(f[2])
    return f.name, int(f.offset), int(f.datatype)


def from_pointcloud2(msg=None, *, data=None, fields=None, point_step=None, width=None,
                     height=1, row_step=None, is_bigendian=False, skip_nans=False):
    """The x, y, z of a PointCloud2 as an (N, 3) array (float32 when all three are FLOAT32).

    Pass the message itself (anything with ``data``, ``fields``, ``point_step``, ``width``,
    ``height``, ``row_step``, ``is_bigendian``: a ROS 2 ``sensor_msgs.msg.PointCloud2``), or its
    parts: ``data`` (bytes-like), ``fields`` (PointField objects, dicts or (name, offset,
    datatype) tuples) and ``point_step``. Row padding (row_step > width * point_step) is
    handled. Points keep the message's order, NaN ones included unless ``skip_nans`` (then
    labels no longer line up with the message's points). The three fields are gathered out of
    the records into the result; padded rows cost one more copy of the buffer.
    """
    if msg is not None:
        data, fields, point_step = msg.data, msg.fields, msg.point_step
        width, height, row_step = msg.width, msg.height, msg.row_step
        is_bigendian = msg.is_bigendian
    if data is None or fields is None or point_step is None:
        raise InvalidParameterError("from_pointcloud2 needs a message, or data, fields and point_step")
    by_name = {}
    for f in fields:
        name, offset, datatype = _field(f)
        by_name[name] = (offset, datatype)
    missing = [c for c in "xyz" if c not in by_name]
    if missing:
        raise InvalidParameterError(f"PointCloud2 has no field {', '.join(missing)}")
    point_step = int(point_step)
    order = ">" if is_bigendian else "<"
    formats = []
    for c in "xyz":
        offset, datatype = by_name[c]
        if datatype not in _TYPES:
            raise InvalidParameterError(f"PointCloud2 field {c} has unknown datatype {datatype}")
        size = int(_TYPES[datatype][1])
        if offset < 0 or offset + size > point_step:
            raise InvalidParameterError(
                f"PointCloud2 field {c} at offset {offset} does not fit in point_step {point_step}")
        formats.append(order + _TYPES[datatype])
    buf = np.frombuffer(memoryview(data).cast("B"), dtype=np.uint8)
    if width is None:
        if buf.size % point_step:
            raise InvalidParameterError(
                f"PointCloud2 data of {buf.size} bytes is not a whole number of {point_step}-byte points")
        width, height, row_step = buf.size // point_step, 1, buf.size
    width, height = int(width), int(height)
    row_step = int(row_step) if row_step is not None else width * point_step
    if row_step < width * point_step or buf.size < height * row_step:
        raise InvalidParameterError(
            f"PointCloud2 data of {buf.size} bytes is too short for {height} x {width} points "
            f"of {point_step} bytes (row_step {row_step})")
    rows = buf[: height * row_step].reshape(height, row_step)[:, : width * point_step]
    records = np.ascontiguousarray(rows).reshape(-1)
    dtype = np.dtype({"names": ["x", "y", "z"], "formats": formats,
                      "offsets": [by_name[c][0] for c in "xyz"], "itemsize": point_step})
    structured = records.view(dtype)
    out_type = np.float32 if all(by_name[c][1] == 7 for c in "xyz") else np.float64
    xyz = np.empty((structured.shape[0], 3), dtype=out_type)
    for k, c in enumerate("xyz"):
        xyz[:, k] = structured[c]
    if skip_nans:
        xyz = xyz[np.isfinite(xyz).all(axis=1)]
    return xyz
