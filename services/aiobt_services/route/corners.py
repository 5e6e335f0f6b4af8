"""Nav2's ``CornerArc``: a circular arc of ``smoothing_radius`` fitted into the corner
two consecutive route edges make, for the dense path (``smooth_corners``).

No arc for a U-turn (angle ~0), a corner straighter than ``smoothing_angle_threshold``
(the angle between the edges, pi for a straight line), or one whose tangent points
would not fit on both edges.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
import numpy.typing as npt

from .vectors import XY


@dataclass(frozen=True, slots=True)
class CornerArc:
    start: XY  # where the arc leaves the first edge
    end: XY  # where it joins the second
    center: XY

    def points(self, max_angle_step: float) -> npt.NDArray[np.float64]:
        """Points along the arc from ``start`` (included) to ``end`` (excluded), at most
        ``max_angle_step`` rad apart."""
        rs = np.subtract(self.start, self.center)
        re = np.subtract(self.end, self.center)
        sweep = math.atan2(rs[0] * re[1] - rs[1] * re[0], float(rs @ re))
        count = max(1, math.ceil(abs(sweep) / max_angle_step))
        angles = np.arange(count) * (sweep / count)
        cos, sin = np.cos(angles), np.sin(angles)
        xs = self.center[0] + rs[0] * cos - rs[1] * sin
        ys = self.center[1] + rs[0] * sin + rs[1] * cos
        return np.column_stack((xs, ys))


def corner_arc(start: XY, corner: XY, end: XY, radius: float, threshold: float) -> CornerArc | None:
    """The arc into the corner start-corner-end, or None where Nav2 fits none."""
    a = np.subtract(start, corner)
    b = np.subtract(end, corner)
    la, lb = float(np.hypot(*a)), float(np.hypot(*b))
    if la == 0.0 or lb == 0.0:
        return None
    angle = math.acos(max(-1.0, min(1.0, float(a @ b) / (la * lb))))
    if angle < 1e-6 or angle > threshold:
        return None
    tangent = radius / math.tan(angle / 2)
    if not (tangent < la and tangent < lb):
        return None
    ua, ub = a / la, b / lb
    bisector = (ua + ub) / float(np.hypot(*(ua + ub)))
    center = np.asarray(corner) + bisector * (radius / math.sin(angle / 2))
    on_a, on_b = np.asarray(corner) + ua * tangent, np.asarray(corner) + ub * tangent
    return CornerArc(
        (float(on_a[0]), float(on_a[1])),
        (float(on_b[0]), float(on_b[1])),
        (float(center[0]), float(center[1])),
    )
