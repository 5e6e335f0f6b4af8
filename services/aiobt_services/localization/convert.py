"""Filter state -> wire messages: ``amcl_pose``, the particle cloud (thinned for viewers)
and ``pose`` (the ``map`` -> ``odom`` transform on ``tf``: the library's
:func:`aiobt.robot.correction.correction_message`, which its readers share)."""

from __future__ import annotations

import numpy as np

from aiobt.msgs import (
    ParticleCloud,
    PoseStamped,
    PoseWithCovarianceStamped,
    pose_fields,
)

from .estimate import Estimate
from .se2 import FloatArray

CLOUD_MAX = 250  # particles sent to viewers: enough to see the spread


def amcl_pose(est: Estimate, stamp: float, frame: str) -> PoseWithCovarianceStamped:
    """AMCL's ``amcl_pose``: the heaviest cluster's mean, the set's covariance."""
    cov6 = np.zeros((6, 6))
    cov6[:2, :2] = est.covariance[:2, :2]
    cov6[5, 5] = est.covariance[2, 2]
    x, y, yaw = (float(v) for v in est.mean)
    return PoseWithCovarianceStamped.model_validate(
        {
            "header": {"stamp": stamp, "frame_id": frame},
            "pose": {"pose": pose_fields(x, y, yaw), "covariance": cov6.ravel().tolist()},
        }
    )


def particle_cloud(
    particles: FloatArray, weights: FloatArray, stamp: float, frame: str, limit: int = CLOUD_MAX
) -> ParticleCloud:
    """At most ``limit`` particles, evenly strided (weights rescaled to sum to 1)."""
    step = max(1, -(-len(particles) // limit))
    picked, w = particles[::step], weights[::step]
    w = w / w.sum() if w.sum() > 0 else np.full(len(w), 1.0 / max(1, len(w)))
    return ParticleCloud.model_validate(
        {
            "header": {"stamp": stamp, "frame_id": frame},
            "particles": [
                {"pose": pose_fields(float(p[0]), float(p[1]), float(p[2])), "weight": float(wi)}
                for p, wi in zip(picked, w, strict=True)
            ],
        }
    )


def map_pose(pose: tuple[float, float, float], stamp: float, frame: str) -> PoseStamped:
    header = {"stamp": stamp, "frame_id": frame}
    x, y, yaw = pose
    return PoseStamped.model_validate({"header": header, "pose": pose_fields(x, y, yaw)})
