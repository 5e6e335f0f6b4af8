"""AMCL's ``DifferentialMotionModel``: sample_motion_model_odometry (Probabilistic
Robotics p. 136) with forward and backward motion treated alike, over all
particles at once (``nav2_amcl/src/motion_model/differential_motion_model.cpp``).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .se2 import FloatArray, angle_diff, wrap

IN_PLACE = 0.01  # m: below this the bearing of the motion is meaningless (a turn in place)


@dataclass(slots=True, frozen=True)
class DifferentialMotionModel:
    """``alpha1``: rotation noise from rotation; ``alpha2``: rotation noise from
    translation; ``alpha3``: translation noise from translation; ``alpha4``:
    translation noise from rotation."""

    alpha1: float = 0.2
    alpha2: float = 0.2
    alpha3: float = 0.2
    alpha4: float = 0.2

    def odometry_update(
        self,
        particles: FloatArray,
        odom_pose: FloatArray,
        delta: FloatArray,
        rng: np.random.Generator,
    ) -> FloatArray:
        """Move every particle (rows ``x, y, yaw`` in ``map``) by the odometry step
        ``delta`` (``odom_pose - previous``, angle wrapped) with sampled noise; returns
        new rows."""
        old_yaw = float(odom_pose[2] - delta[2])
        trans = float(np.hypot(delta[0], delta[1]))
        rot1 = (
            0.0 if trans < IN_PLACE else float(angle_diff(np.arctan2(delta[1], delta[0]), old_yaw))
        )
        rot2 = float(angle_diff(delta[2], rot1))
        # backward motion as noisy as forward: the rotations' distance from 0 or pi
        rot1_noise = min(abs(float(angle_diff(rot1, 0.0))), abs(float(angle_diff(rot1, np.pi))))
        rot2_noise = min(abs(float(angle_diff(rot2, 0.0))), abs(float(angle_diff(rot2, np.pi))))
        n = len(particles)
        sd_rot1 = np.sqrt(self.alpha1 * rot1_noise**2 + self.alpha2 * trans**2)
        sd_trans = np.sqrt(
            self.alpha3 * trans**2 + self.alpha4 * rot1_noise**2 + self.alpha4 * rot2_noise**2
        )
        sd_rot2 = np.sqrt(self.alpha1 * rot2_noise**2 + self.alpha2 * trans**2)
        rot1_hat = wrap(rot1 - rng.normal(0.0, 1.0, n) * sd_rot1)
        trans_hat = trans - rng.normal(0.0, 1.0, n) * sd_trans
        rot2_hat = wrap(rot2 - rng.normal(0.0, 1.0, n) * sd_rot2)
        heading = particles[:, 2] + rot1_hat
        moved = np.empty_like(particles)
        moved[:, 0] = particles[:, 0] + trans_hat * np.cos(heading)
        moved[:, 1] = particles[:, 1] + trans_hat * np.sin(heading)
        moved[:, 2] = wrap(heading + rot2_hat)
        return moved
