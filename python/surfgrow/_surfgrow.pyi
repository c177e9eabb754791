"""Type stubs for surfgrow._surfgrow (the C++ extension). Lengths are in the cloud's units."""

import os
from typing import Any, Callable, Optional, Tuple, Union, overload

import numpy as np
import numpy.typing as npt

__version__: str

ArrayLike = npt.ArrayLike
PathLike = Union[str, os.PathLike]
Progress = Union[None, bool, Callable[[str, float], Any]]

class Error(Exception):
    """Every error surfgrow reports; ``code`` is the command line's exit code for it."""
    code: int

class InternalError(Error, RuntimeError): ...
class UsageError(Error, ValueError): ...
class InvalidParameterError(Error, ValueError): ...
class CannotOpenError(Error, OSError): ...
class UnknownFormatError(Error, ValueError): ...
class MalformedInputError(Error, ValueError): ...
class CannotWriteError(Error, OSError): ...
class CloudTooLargeError(Error, ValueError): ...

class Cloud:
    """A point cloud with what is known about its scans (viewpoint, scan origins)."""
    def __init__(self, points: ArrayLike, *, viewpoint: Optional[ArrayLike] = None,
                 scan_index: Optional[ArrayLike] = None, scan_origins: Optional[ArrayLike] = None,
                 labels: Optional[ArrayLike] = None, normals: Optional[ArrayLike] = None) -> None: ...
    def __len__(self) -> int: ...
    @property
    def points(self) -> npt.NDArray[np.float32]:
        """(N, 3) float32, relative to ``offset``; read-only view."""
    @property
    def offset(self) -> npt.NDArray[np.float64]:
        """(3,): add to ``points`` for the file's coordinates (zero unless georeferenced)."""
    @property
    def viewpoint(self) -> Optional[npt.NDArray[np.float64]]: ...
    @property
    def scan_index(self) -> Optional[npt.NDArray[np.uint32]]: ...
    @property
    def scan_origins(self) -> Optional[npt.NDArray[np.float64]]: ...
    @property
    def labels(self) -> Optional[npt.NDArray[np.int32]]: ...
    @property
    def normals(self) -> Optional[npt.NDArray[np.float32]]: ...

def read_cloud(path: PathLike, *, format: Optional[str] = None, label_field: str = "label") -> Cloud:
    """Reads a PLY, PCD or text cloud (format 'ply', 'pcd', 'text'; default from the extension or content)."""

def write_cloud(path: PathLike, points: Union[ArrayLike, Cloud], *, normals: Optional[ArrayLike] = None,
                labels: Optional[ArrayLike] = None, format: Optional[str] = None,
                encoding: Optional[str] = None) -> None:
    """Writes points with optional (N, 3) normals and (N,) labels, atomically."""

class GrowResult:
    """Surfaces grown over a cloud (S surfaces, N input points)."""
    def __len__(self) -> int: ...
    @property
    def labels(self) -> npt.NDArray[np.int32]:
        """(N,) surface of every input point, -1 unregistered; read-only view, no copy."""
    @property
    def normals(self) -> npt.NDArray[np.float64]:
        """(S, 3) unit normals facing the sensor side."""
    @property
    def homes(self) -> npt.NDArray[np.float64]:
        """(S, 3) home points."""
    @property
    def centroids(self) -> npt.NDArray[np.float64]: ...
    @property
    def planes(self) -> npt.NDArray[np.float64]:
        """(S, 4) planes (a, b, c, d) with n . x + d = 0."""
    @property
    def eigenvalues(self) -> npt.NDArray[np.float64]:
        """(S, 3) covariance eigenvalues, ascending [units^2]."""
    @property
    def radii(self) -> npt.NDArray[np.float64]:
        """(S,) neighbourhood radius: mu, or larger where it adapted."""
    @property
    def counts(self) -> npt.NDArray[np.uint32]:
        """(S,) member points per surface."""
    @property
    def mean_residuals(self) -> npt.NDArray[np.float64]: ...
    @property
    def tolerances(self) -> npt.NDArray[np.float64]: ...
    @property
    def cloud(self) -> Cloud:
        """The Cloud grown from: shared when a Cloud was passed, else copied from the array on first use."""
    @property
    def parameters(self) -> dict:
        """Every parameter used, defaults resolved (as in surfaces.json)."""
    @property
    def summary(self) -> dict:
        """Points, surfaces, registered_share, data_reduction, range bands, noise, seconds per stage."""

def grow(points: Union[ArrayLike, Cloud], mu: float = 0.012, min_pts: int = 10, seed: int = 1,
         threads: int = 0, *, alpha: float = 4.0, plane_test: str = "disk", min_spread: float = 0.3,
         max_incidence_deg: float = 85.0, thickness_sigmas: float = 2.5, noise_sigmas: float = 4.0,
         min_new_points: int = 1, plane_tolerance: float = 0.0, adaptive_factor: float = 8.0,
         attach_leftovers: bool = True, pool_angle_deg: float = 15.0, pool_radius: float = 0.0,
         viewpoint: Optional[ArrayLike] = None, crop_box: Optional[ArrayLike] = None,
         crop_radius: Optional[float] = None, crop_center: Optional[ArrayLike] = None,
         range_band: float = 1.0, progress: Progress = None, copy: bool = False) -> GrowResult:
    """Grows surfaces over (N, 3) points (cloud units; mu 0.012 = 12 mm in metres).

    A C-ordered float32 array is read in place and the result keeps a reference to it (later
    calls on the result read it again): do not change it afterwards, or pass copy=True. Other
    dtypes and layouts are converted once."""

class BoundPlanes:
    """Structural faces: neighbouring coplanar surfaces merged (P faces)."""
    def __len__(self) -> int: ...
    @property
    def faces(self) -> list[dict]:
        """plane, normal, centroid, u_axis, v_axis, area, rms, point_count, degenerate, members, polygons."""
    @property
    def normals(self) -> npt.NDArray[np.float64]: ...
    @property
    def planes(self) -> npt.NDArray[np.float64]: ...
    @property
    def areas(self) -> npt.NDArray[np.float64]: ...
    @property
    def plane_of_surface(self) -> npt.NDArray[np.int32]: ...
    @property
    def point_labels(self) -> npt.NDArray[np.int32]: ...
    @property
    def stats(self) -> dict: ...

def bound_planes(result: GrowResult, points: Optional[Union[ArrayLike, Cloud]] = None, *,
                 max_angle_deg: float = 10.0, max_offset: float = 0.0, adjacency: float = 0.0,
                 max_gap: float = 0.0, resolution: float = 0.0, closing_radius: float = 0.0,
                 simplify_tolerance: float = 0.0) -> BoundPlanes: ...

class CoveragePlan:
    """Goals in path order with the tool's approach pose (G goals)."""
    def __len__(self) -> int: ...
    @property
    def positions(self) -> npt.NDArray[np.float64]: ...
    @property
    def normals(self) -> npt.NDArray[np.float64]: ...
    @property
    def tool_positions(self) -> npt.NDArray[np.float64]: ...
    @property
    def tool_axes(self) -> npt.NDArray[np.float64]: ...
    @property
    def orientations(self) -> npt.NDArray[np.float64]:
        """(G, 4) quaternions (x, y, z, w)."""
    @property
    def tilt_deg(self) -> npt.NDArray[np.float64]: ...
    @property
    def planes(self) -> npt.NDArray[np.uint32]: ...
    @property
    def transitions(self) -> npt.NDArray[np.bool_]: ...
    @property
    def stats(self) -> dict: ...

def coverage(planes: BoundPlanes, blast_radius: float = 0.0, standoff: float = 0.3, *,
             min_angle_deg: float = 5.0, max_angle_deg: float = 40.0,
             tilt_deg: Optional[float] = None, sample_spacing: float = 0.0,
             start: Optional[ArrayLike] = None) -> CoveragePlan: ...

class OccupancyGrid:
    """Occupied cubes of side mu (K cubes)."""
    def __len__(self) -> int: ...
    @property
    def cells(self) -> npt.NDArray[np.int32]: ...
    @property
    def centres(self) -> npt.NDArray[np.float64]: ...
    @property
    def point_counts(self) -> npt.NDArray[np.uint32]: ...
    @property
    def cube_size(self) -> float: ...
    @property
    def origin(self) -> npt.NDArray[np.float64]: ...
    def occupied(self, points: ArrayLike) -> npt.NDArray[np.bool_]: ...
    def write_octomap(self, path: PathLike) -> dict: ...

def occupancy(result: GrowResult, points: Optional[Union[ArrayLike, Cloud]] = None, *,
              origins: Optional[ArrayLike] = None) -> OccupancyGrid: ...

class CollisionSpheres:
    """Environment spheres with vectorised proximity queries."""
    @overload
    def __init__(self, result: GrowResult) -> None:
        """One sphere per surface of a GrowResult (sphere id = surface id)."""
    @overload
    def __init__(self, centres: ArrayLike, radii: Union[float, ArrayLike]) -> None:
        """Spheres from (M, 3) centres and one radius or (M,) radii."""
    def __len__(self) -> int: ...
    def nearest(self, queries: ArrayLike) -> Tuple[npt.NDArray[np.float64], npt.NDArray[np.int64]]:
        """(clearance, ids) for (M, 3) points, (M, 4) spheres or (M, 7) capsules."""
    def collides(self, queries: ArrayLike, tolerance: float = 0.0) -> npt.NDArray[np.bool_]: ...

class Map:
    """A map grown scan by scan: each scan's points join the mapped surfaces where they fit and
    grow new ones elsewhere. Deterministic for a given order of scans and seed."""
    def __init__(self, mu: float = 0.012, min_pts: int = 10, seed: int = 1, threads: int = 0, *,
                 join_tolerance: float = 1.5) -> None: ...
    def add_scan(self, points: Union[ArrayLike, Cloud], origin: ArrayLike) -> GrowResult:
        """Adds one scan taken from `origin`; returns the whole map so far."""
    @property
    def scans(self) -> int: ...
    @property
    def last_update(self) -> dict: ...

class Truth:
    @property
    def labels(self) -> npt.NDArray[np.int32]: ...
    @property
    def faces(self) -> int: ...

class Scan:
    def __len__(self) -> int: ...
    @property
    def cloud(self) -> Cloud: ...
    @property
    def points(self) -> npt.NDArray[np.float32]: ...
    @property
    def truth(self) -> Truth: ...
    @property
    def poses(self) -> npt.NDArray[np.float64]: ...

def simulate(scene: str = "ibeam-channel", poses: Union[int, str] = 3, seed: int = 1, *,
             readings: int = 5, trim: int = 1, laser: str = "urg04lx-paper",
             noise: str = "datasheet", optical_offset: float = 0.040,
             min_range: Optional[float] = None, max_range: Optional[float] = None,
             veil_angle: float = 0.0, progress: Progress = None) -> Scan: ...

def evaluate(result: GrowResult, truth: Truth, *, workspace: float = 1.0, band: float = 0.5) -> dict: ...
