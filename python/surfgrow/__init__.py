"""surfgrow: laser-scan point clouds to the surfaces a robot works on.

Oriented surface patches (Paul, Liu & Kirchner's surface growing), bound planes, coverage goals
with approach poses, an occupancy grid with OctoMap export and collision spheres, from numpy
arrays. Lengths are in the cloud's units (metres for ROS, PCL and Open3D clouds). See
docs/python.md.

    import numpy as np, surfgrow
    r = surfgrow.grow(points, mu=0.012)      # (N, 3) float32/float64, metres
    r.labels, r.normals, r.summary
"""

from ._surfgrow import (
    BoundPlanes,
    CannotOpenError,
    CannotWriteError,
    Cloud,
    CloudTooLargeError,
    CollisionSpheres,
    CoveragePlan,
    Error,
    GrowResult,
    InternalError,
    InvalidParameterError,
    MalformedInputError,
    Map,
    OccupancyGrid,
    Scan,
    Truth,
    UnknownFormatError,
    UsageError,
    __version__,
    bound_planes,
    coverage,
    evaluate,
    grow,
    occupancy,
    read_cloud,
    simulate,
    write_cloud,
)
from .ros import from_pointcloud2

__all__ = [
    "BoundPlanes",
    "CannotOpenError",
    "CannotWriteError",
    "Cloud",
    "CloudTooLargeError",
    "CollisionSpheres",
    "CoveragePlan",
    "Error",
    "GrowResult",
    "InternalError",
    "InvalidParameterError",
    "MalformedInputError",
    "Map",
    "OccupancyGrid",
    "Scan",
    "Truth",
    "UnknownFormatError",
    "UsageError",
    "__version__",
    "bound_planes",
    "coverage",
    "evaluate",
    "from_pointcloud2",
    "grow",
    "occupancy",
    "read_cloud",
    "simulate",
    "write_cloud",
]
