"""The surfgrow.Error hierarchy mirrors the command line's exit codes."""

import numpy as np
import pytest

import surfgrow

EXIT_CODES = {
    "InternalError": (1, RuntimeError), "UsageError": (2, ValueError),
    "InvalidParameterError": (3, ValueError), "CannotOpenError": (4, OSError),
    "UnknownFormatError": (5, ValueError), "MalformedInputError": (6, ValueError),
    "CannotWriteError": (7, OSError), "CloudTooLargeError": (8, ValueError),
}


@pytest.mark.parametrize("name", sorted(EXIT_CODES))
def test_hierarchy(name):
    cls = getattr(surfgrow, name)
    code, builtin = EXIT_CODES[name]
    assert issubclass(cls, surfgrow.Error) and issubclass(cls, builtin)
    assert cls.code == code
    assert cls.__module__ == "surfgrow"


def test_missing_file(tmp_path):
    with pytest.raises(surfgrow.CannotOpenError, match="missing.ply") as e:
        surfgrow.read_cloud(tmp_path / "missing.ply")
    assert e.value.code == 4 and isinstance(e.value, OSError)


def test_malformed_file(tmp_path):
    f = tmp_path / "broken.ply"
    f.write_bytes(b"ply\nformat binary_little_endian 1.0\nelement vertex 100\nproperty float x\n"
                  b"property float y\nproperty float z\nend_header\n" + b"\0" * 12)
    with pytest.raises(surfgrow.MalformedInputError, match="broken.ply"):
        surfgrow.read_cloud(f)


def test_unknown_format(tmp_path):
    f = tmp_path / "cloud.bin"
    f.write_bytes(bytes(range(256)) * 4)
    with pytest.raises(surfgrow.UnknownFormatError, match="cloud.bin"):
        surfgrow.read_cloud(f)


def test_cannot_write(tmp_path):
    with pytest.raises(surfgrow.CannotWriteError):
        surfgrow.write_cloud(tmp_path / "no" / "such" / "folder" / "x.ply", np.zeros((3, 3)))


def test_usage_errors(tmp_path):
    with pytest.raises(surfgrow.UsageError, match="format 'las'"):
        surfgrow.read_cloud(tmp_path / "x.ply", format="las")
    with pytest.raises(surfgrow.UnknownFormatError):
        surfgrow.write_cloud(tmp_path / "x.las", np.zeros((3, 3)))


def test_any_extent_within_float_range_is_indexed():
    # 10^11 cubes on an axis: the index ranks the cubes instead of refusing; nothing registers.
    pts = np.array([[0, 0, 0], [1e7, 0, 0], [0, 1e7, 0]], np.float64)
    with pytest.warns(RuntimeWarning, match="registered"):
        result = surfgrow.grow(pts, mu=1e-4)
    assert (result.labels == -1).all()


def test_extent_beyond_float_range_is_cloud_too_large():
    pts = np.array([[-3e38, 0, 0], [3e38, 0, 0], [0, 0, 0]], np.float64)
    with pytest.raises(surfgrow.CloudTooLargeError, match="float range") as e:
        surfgrow.grow(pts, mu=1e-4)
    assert e.value.code == 8
