"""simple_smoother: Nav2's gradient path smoother that never moves a point into collision."""

from __future__ import annotations

import math
import time
from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np

from aiobt.costmap import INSCRIBED, NO_INFORMATION, CostGrid, points_cost
from aiobt.geometry import XYYaw


@dataclass(frozen=True, slots=True)
class SmootherParams:
    """Nav2 ``simple_smoother`` parameters."""

    tolerance: float = 1e-10
    max_its: int = 1000
    w_data: float = 0.2
    w_smooth: float = 0.3


@dataclass(frozen=True, slots=True)
class SmoothResult:
    poses: list[XYYaw]
    completed: bool  # converged (False: iteration limit or time budget reached)
    timed_out: bool


def _blocked(grid: CostGrid, xy: np.ndarray) -> np.ndarray:
    costs = points_cost(grid, xy[:, 0], xy[:, 1])
    blocked: np.ndarray = (costs >= INSCRIBED) & (costs != NO_INFORMATION)
    return blocked


def smooth(
    grid: CostGrid,
    poses: Sequence[XYYaw],
    max_duration: float = math.inf,
    params: SmootherParams | None = None,
) -> SmoothResult:
    """Smooth interior points towards their neighbours' midpoint, pulled back to the
    original; a point that would enter an obstacle keeps its last safe position
    and is frozen (Nav2 reverts the point and stops smoothing it). Ends fixed."""
    params = params or SmootherParams()
    original = np.array([(p[0], p[1]) for p in poses], dtype=np.float64)
    if len(original) < 3:
        return SmoothResult(list(poses), True, False)
    current = original.copy()
    movable = np.ones(len(original), dtype=bool)
    movable[[0, -1]] = False
    deadline = time.monotonic() + max_duration
    for _ in range(params.max_its):
        if time.monotonic() > deadline:
            return SmoothResult(_headed(current, poses), False, True)
        proposal = current.copy()
        inner = slice(1, -1)
        proposal[inner] += params.w_data * (original[inner] - current[inner])
        proposal[inner] += params.w_smooth * (current[:-2] + current[2:] - 2.0 * current[inner])
        movable &= ~_blocked(grid, proposal)
        change = float(np.abs(proposal[movable] - current[movable]).sum())
        current[movable] = proposal[movable]
        if change < params.tolerance:
            return SmoothResult(_headed(current, poses), True, False)
    return SmoothResult(_headed(current, poses), False, False)


def _headed(xy: np.ndarray, poses: Sequence[XYYaw]) -> list[XYYaw]:
    headings = np.arctan2(np.diff(xy[:, 1]), np.diff(xy[:, 0]))
    out = [(float(x), float(y), float(yaw)) for (x, y), yaw in zip(xy[:-1], headings, strict=True)]
    out.append((float(xy[-1, 0]), float(xy[-1, 1]), poses[-1][2]))
    return out


def in_collision(grid: CostGrid, poses: Sequence[XYYaw]) -> list[int]:
    """Indices of poses on lethal or inscribed (known) cells."""
    xy = np.array([(p[0], p[1]) for p in poses], dtype=np.float64).reshape(-1, 2)
    return np.flatnonzero(_blocked(grid, xy)).tolist() if len(xy) else []


class SimpleSmoother:
    """Nav2's ``nav2_smoother::SimpleSmoother`` as a :class:`~.base.Smoother` plugin."""

    __slots__ = ("params",)

    def __init__(self, params: SmootherParams | None = None) -> None:
        self.params = params or SmootherParams()

    def smooth(self, grid: CostGrid, poses: Sequence[XYYaw], max_duration: float) -> SmoothResult:
        return smooth(grid, poses, max_duration, self.params)
