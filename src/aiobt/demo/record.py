"""What the demo keeps for its picture and its summary: map, the two tracks (the pose
estimate's and, in the simulation, the truth's), plans, recoveries."""

from __future__ import annotations

import math
from dataclasses import dataclass, field

from aiobt.demo.tracking import TrackingError
from aiobt.msgs import OccupancyGrid, PoseStamped

XY = tuple[float, float]
_STEP = 0.02  # m between kept trajectory points


@dataclass(slots=True)
class Leg:
    """One goal of the patrol and how it went."""

    name: str
    goal: tuple[float, float, float]
    plan: list[XY] = field(default_factory=list)
    reached: bool = False
    result: str = ""
    recoveries: int = 0
    seconds: float = 0.0  # sim time


@dataclass(slots=True)
class Record:
    map: OccupancyGrid | None = None
    trajectory: list[XY] = field(default_factory=list)  # the estimate's: {ns}/pose
    truth: list[XY] = field(default_factory=list)  # the simulation's: {ns}/sim/pose
    tracking: TrackingError = field(default_factory=TrackingError)
    legs: list[Leg] = field(default_factory=list)
    recoveries: list[XY] = field(default_factory=list)
    # boxes put in the robot's way: x, y, yaw, size along, size across
    obstacles: list[tuple[float, float, float, float, float]] = field(default_factory=list)

    def on_map(self, grid: OccupancyGrid) -> None:
        self.map = grid

    def on_pose(self, pose: PoseStamped) -> None:
        _extend(self.trajectory, pose)
        self.tracking.on_estimate(pose.header.stamp, (pose.x, pose.y))

    def on_truth(self, pose: PoseStamped) -> None:
        _extend(self.truth, pose)
        self.tracking.on_truth(pose.header.stamp, (pose.x, pose.y))

    @property
    def position(self) -> XY:
        return self.trajectory[-1] if self.trajectory else (0.0, 0.0)


def _extend(track: list[XY], pose: PoseStamped) -> None:
    here = (pose.x, pose.y)
    if not track or math.dist(track[-1], here) >= _STEP:
        track.append(here)
