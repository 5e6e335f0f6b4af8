"""Small geometry helpers: planar poses and merging grid cells into boxes."""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
import numpy.typing as npt


def wrap_angle(angle: float) -> float:
    """Angle in (-pi, pi]."""
    wrapped = math.remainder(angle, math.tau)
    return math.pi if wrapped == -math.pi else wrapped


@dataclass(slots=True, frozen=True)
class Pose2D:
    """A planar pose: position in metres, heading in radians."""

    x: float = 0.0
    y: float = 0.0
    yaw: float = 0.0

    def compose(self, other: Pose2D) -> Pose2D:
        """``self * other``: ``other`` expressed in the frame of ``self``."""
        c, s = math.cos(self.yaw), math.sin(self.yaw)
        return Pose2D(
            self.x + c * other.x - s * other.y,
            self.y + s * other.x + c * other.y,
            wrap_angle(self.yaw + other.yaw),
        )

    def inverse(self) -> Pose2D:
        c, s = math.cos(self.yaw), math.sin(self.yaw)
        return Pose2D(-c * self.x - s * self.y, s * self.x - c * self.y, wrap_angle(-self.yaw))

    def distance_to(self, other: Pose2D) -> float:
        return math.hypot(other.x - self.x, other.y - self.y)


def row_runs(mask: npt.NDArray[np.bool_]) -> npt.NDArray[np.int64]:
    """Horizontal runs of True cells as rows of (row, start_col, end_col_exclusive)."""
    padded = np.zeros((mask.shape[0], mask.shape[1] + 2), dtype=np.int8)
    padded[:, 1:-1] = mask
    edges = np.diff(padded, axis=1)
    start_rows, starts = np.nonzero(edges == 1)
    _, ends = np.nonzero(edges == -1)
    # nonzero scans row-major, so the k-th start and k-th end belong to one run
    return np.stack([start_rows, starts, ends], axis=1).astype(np.int64)


def merge_boxes(mask: npt.NDArray[np.bool_]) -> npt.NDArray[np.int64]:
    """Cover the True cells of ``mask`` with disjoint rectangles.

    Greedy merge: cells are first joined into maximal horizontal runs, then
    runs with the same column span in consecutive rows are stacked. Returns
    rows of (row0, col0, n_rows, n_cols).
    """
    runs = row_runs(mask)
    if runs.size == 0:
        return np.zeros((0, 4), dtype=np.int64)
    order = np.lexsort((runs[:, 0], runs[:, 2], runs[:, 1]))
    runs = runs[order]
    same_span = (runs[1:, 1] == runs[:-1, 1]) & (runs[1:, 2] == runs[:-1, 2])
    continues = same_span & (runs[1:, 0] == runs[:-1, 0] + 1)
    group_start = np.concatenate([[True], ~continues])
    starts = np.flatnonzero(group_start)
    ends = np.concatenate([starts[1:], [len(runs)]])
    first = runs[starts]
    n_rows = runs[ends - 1, 0] - first[:, 0] + 1
    return np.stack([first[:, 0], first[:, 1], n_rows, first[:, 2] - first[:, 1]], axis=1)
