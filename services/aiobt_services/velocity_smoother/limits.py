"""Nav2's acceleration limiting, vectorised over the axes ``[x, y, theta]``.

:func:`find_eta_constraint` and :func:`apply_constraints` are Nav2's
``findEtaConstraint`` and ``applyConstraints``: a change of velocity away from
zero (same sign, growing magnitude) is bounded by ``max_accel``, any other (slowing,
or passing through zero) by ``max_decel``, per smoothing period.
"""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike, NDArray

Vec = NDArray[np.float64]


def _bounds(v_curr: Vec, v_cmd: Vec, accel: Vec, decel: Vec, frequency: float) -> tuple[Vec, Vec]:
    """Per axis, the smallest and largest change allowed in one period."""
    speeding_up = (np.abs(v_cmd) >= np.abs(v_curr)) & (v_curr * v_cmd >= 0.0)
    upper = np.where(speeding_up, accel, -decel) / frequency
    lower = np.where(speeding_up, -accel, decel) / frequency
    return lower, upper


def find_eta_constraint(
    v_curr: ArrayLike, v_cmd: ArrayLike, accel: ArrayLike, decel: ArrayLike, frequency: float
) -> Vec:
    """Per axis, the scale of the change ``v_cmd - v_curr`` that keeps it within the
    axis's limit, or -1 where it is within already (Nav2's ``findEtaConstraint``)."""
    curr, cmd = np.asarray(v_curr, np.float64), np.asarray(v_cmd, np.float64)
    lower, upper = _bounds(curr, cmd, np.asarray(accel, np.float64), np.asarray(decel, np.float64),
                           frequency)  # fmt: skip
    dv = cmd - curr
    with np.errstate(divide="ignore", invalid="ignore"):
        return np.where(dv > upper, upper / dv, np.where(dv < lower, lower / dv, -1.0))


def common_eta(etas: Vec) -> float:
    """The scale for all axes: of the axes that need one, the farthest from 1 (Nav2)."""
    valid = etas[etas > 0.0]
    if valid.size == 0:
        return 1.0
    return float(valid[np.argmax(np.abs(1.0 - valid))])


def apply_constraints(
    v_curr: ArrayLike,
    v_cmd: ArrayLike,
    accel: ArrayLike,
    decel: ArrayLike,
    eta: float,
    frequency: float,
) -> Vec:
    """The next velocity: ``v_curr`` moved by ``eta * (v_cmd - v_curr)``, clamped to the
    change one period allows (Nav2's ``applyConstraints``)."""
    curr, cmd = np.asarray(v_curr, np.float64), np.asarray(v_cmd, np.float64)
    lower, upper = _bounds(curr, cmd, np.asarray(accel, np.float64), np.asarray(decel, np.float64),
                           frequency)  # fmt: skip
    return np.asarray(curr + np.clip(eta * (cmd - curr), lower, upper), np.float64)
