"""An initial pose for the filter, checked before anything changes: finite,
on the map, not in a wall, with a positive-definite covariance."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .likelihood_field import LikelihoodField
from .se2 import FloatArray

# Nav2's default when a pose comes without one (amcl_node: 0.5 m, 0.5 m, pi/12 rad)
DEFAULT_COVARIANCE = np.diag([0.5 * 0.5, 0.5 * 0.5, (np.pi / 12.0) ** 2])


class InitialPoseError(ValueError):
    """An initial pose the filter refuses (the message names what is wrong)."""


@dataclass(slots=True, frozen=True)
class InitialPose:
    mean: FloatArray  # x, y, yaw in map
    covariance: FloatArray  # 3x3: x, y, yaw


def covariance_from_6x6(flat: list[float] | FloatArray) -> FloatArray:
    """ROS's row-major 6x6 (x y z roll pitch yaw) -> AMCL's 3x3 (x, y and yaw)."""
    six = np.asarray(flat, dtype=np.float64)
    if six.size != 36:
        raise InitialPoseError(f"covariance must have 36 entries (6x6), got {six.size}")
    six = six.reshape(6, 6)
    cov = np.zeros((3, 3))
    cov[:2, :2] = six[:2, :2]
    cov[2, 2] = six[5, 5]
    cov[:2, 2] = six[:2, 5]
    cov[2, :2] = six[5, :2]
    return cov


def checked(
    x: float,
    y: float,
    yaw: float,
    covariance: FloatArray,
    field: LikelihoodField | None,
    where: str,
) -> InitialPose:
    """The pose if usable, else :class:`InitialPoseError` naming ``where`` it came from."""
    mean = np.array([x, y, yaw], dtype=np.float64)
    if not np.all(np.isfinite(mean)):
        raise InitialPoseError(f"{where}: pose ({x}, {y}, {yaw}) is not finite")
    cov = np.asarray(covariance, dtype=np.float64)
    if cov.shape != (3, 3) or not np.all(np.isfinite(cov)):
        raise InitialPoseError(f"{where}: covariance must be finite 3x3, got {cov.tolist()}")
    if not np.allclose(cov, cov.T, atol=1e-12):
        raise InitialPoseError(f"{where}: covariance is not symmetric: {cov.tolist()}")
    lowest = float(np.linalg.eigvalsh(cov)[0])
    if lowest <= 0.0:
        raise InitialPoseError(
            f"{where}: covariance (x, y, yaw) is not positive definite (smallest eigenvalue "
            f"{lowest:g}): {np.round(cov, 6).tolist()}"
        )
    if field is not None:
        why = field.where(x, y)
        if why:
            raise InitialPoseError(f"{where}: pose {why}")
    return InitialPose(mean, cov)


def sample(pose: InitialPose, count: int, rng: np.random.Generator) -> FloatArray:
    """``count`` particles from the Gaussian (AMCL's ``pf_init``)."""
    drawn = rng.multivariate_normal(pose.mean, pose.covariance, size=count, method="cholesky")
    drawn[:, 2] = (drawn[:, 2] + np.pi) % (2.0 * np.pi) - np.pi
    return np.asarray(drawn, dtype=np.float64)
