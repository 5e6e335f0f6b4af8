"""What the controller shows observers: the local plan and the local costmap, as messages.

Pure conversions and a rate gate; :mod:`.service` puts the results on
``{ns}/local_plan`` (each control cycle of a goal, an empty Path when it ends)
and ``{ns}/local_costmap/costmap`` (at most ``1 / period`` per robot second).
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Protocol, TypeVar

import numpy as np
from numpy.typing import NDArray

from aiobt.costmap import INSCRIBED, LETHAL, NO_INFORMATION, CostGrid
from aiobt.geometry import FloatArray
from aiobt.msgs import Header, OccupancyGrid, Path, Pose, PoseStamped
from aiobt.robot.rate import RateGate

from .base import NO_TRAJECTORY

M = TypeVar("M", contravariant=True)
COSTMAP_PERIOD = 0.5  # s of robot time between local costmaps (2 Hz)


def _translation_table() -> NDArray[np.int8]:
    """Nav2's costmap -> OccupancyGrid table (Costmap2DPublisher): 0 free, 1..97 for the
    inflated costs 1..252, 99 inscribed, 100 lethal, -1 unknown."""
    costs = np.arange(256)
    table = 1 + (97 * (costs - 1)) // 251
    table[0] = 0
    table[INSCRIBED] = 99
    table[LETHAL] = 100
    table[NO_INFORMATION] = -1
    return table.astype(np.int8)


OCCUPANCY_OF_COST = _translation_table()


def costmap_msg(grid: CostGrid, stamp: float, frame_id: str = "map") -> OccupancyGrid:
    """The costmap as Nav2 publishes it (``nav_msgs/OccupancyGrid``, translated values)."""
    g = grid.geometry
    return OccupancyGrid.from_array(
        OCCUPANCY_OF_COST[grid.costs],
        g.resolution,
        origin=Pose.from_xy_yaw(g.origin_x, g.origin_y),
        frame_id=frame_id,
        stamp=max(0.0, stamp),
    )


def path_msg(poses: FloatArray, stamp: float, frame_id: str) -> Path:
    """Poses ``(n, 3)`` (x, y, yaw) as a Path; ``n = 0`` gives the empty Path that clears."""
    header = Header(stamp=max(0.0, stamp), frame_id=frame_id)
    return Path(
        header=header,
        poses=[
            PoseStamped(header=header, pose=Pose.from_xy_yaw(float(x), float(y), float(yaw)))
            for x, y, yaw in poses
        ],
    )


class Sink(Protocol[M]):
    """Where a message goes (a transport Publisher): ``matched`` when someone listens."""

    @property
    def matched(self) -> bool: ...

    def put(self, message: M, /) -> None: ...


class LocalView:
    """Feeds ``plan`` and ``costmap`` during a goal, only while they have subscribers."""

    __slots__ = ("_costmap", "_costs", "_gate", "_plan")

    def __init__(
        self,
        plan: Sink[Path],
        costmap: Sink[OccupancyGrid],
        costs: Callable[[], CostGrid],
        costmap_period: float = COSTMAP_PERIOD,
    ) -> None:
        self._plan = plan
        self._costmap = costmap
        self._costs = costs
        self._gate = RateGate(costmap_period)

    def begin(self) -> None:
        """A goal starts: its first cycle shows the costmap."""
        self._gate.reset()

    def cycle(self, trajectory: FloatArray, frame_id: str, now: float) -> None:
        if self._plan.matched:
            self._plan.put(path_msg(trajectory, now, frame_id))
        if self._costmap.matched and self._gate.due(now):
            self._costmap.put(costmap_msg(self._costs(), now))

    def end(self, frame_id: str, now: float) -> None:
        """The goal ended: an empty local plan, so that viewers clear theirs."""
        if self._plan.matched:
            self._plan.put(path_msg(NO_TRAJECTORY, now, frame_id))
