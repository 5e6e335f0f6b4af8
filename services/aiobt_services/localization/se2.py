"""Planar poses as numpy rows ``(x, y, yaw)``: composition, inversion, angle wrap.

The particle filter works on arrays of poses (one row per particle); these are
the few rigid-body operations it needs, vectorised over rows.
"""

from __future__ import annotations

import numpy as np
import numpy.typing as npt

FloatArray = npt.NDArray[np.float64]


def wrap(angle: FloatArray | float) -> FloatArray:
    """Angles in [-pi, pi)."""
    return np.asarray((np.asarray(angle) + np.pi) % (2.0 * np.pi) - np.pi, dtype=np.float64)


def angle_diff(a: FloatArray | float, b: FloatArray | float) -> FloatArray:
    """``a - b`` wrapped (AMCL's ``angleutils::angle_diff``)."""
    return wrap(np.asarray(a) - np.asarray(b))


def compose(a: FloatArray, b: FloatArray) -> FloatArray:
    """``a * b``: ``b`` expressed in the frame of ``a`` (rows broadcast)."""
    a, b = np.asarray(a, dtype=np.float64), np.asarray(b, dtype=np.float64)
    c, s = np.cos(a[..., 2]), np.sin(a[..., 2])
    return np.stack(
        [
            a[..., 0] + c * b[..., 0] - s * b[..., 1],
            a[..., 1] + s * b[..., 0] + c * b[..., 1],
            wrap(a[..., 2] + b[..., 2]),
        ],
        axis=-1,
    )


def inverse(a: FloatArray) -> FloatArray:
    """The pose ``b`` with ``a * b`` the identity."""
    a = np.asarray(a, dtype=np.float64)
    c, s = np.cos(a[..., 2]), np.sin(a[..., 2])
    return np.stack(
        [-c * a[..., 0] - s * a[..., 1], s * a[..., 0] - c * a[..., 1], wrap(-a[..., 2])], axis=-1
    )


def pose(x: float, y: float, yaw: float) -> FloatArray:
    return np.array([x, y, yaw], dtype=np.float64)
