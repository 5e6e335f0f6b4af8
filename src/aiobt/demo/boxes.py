"""The demo's forced recovery: boxes wall the robot in until the navigator recovers.

Before the walled-in leg, two boxes close the nook "behind the wall" of the small
world (the wall at y 1.1..1.25 for x -2..-1, the world's north and west edges
and the 0.35 m gap west of the wall, too narrow for the robot, close the rest).
They stand in the robot's lidar view, so once the planner's global costmap has
them no path leaves the nook: the first ComputePathToPose fails with
NO_VALID_PATH and the tree's planner recovery clears the global costmap. The
navigator counts that recovery in its feedback; at the first one the boxes are
taken away, the next plan leaves the nook and the goal is reached. So the leg
needs a recovery on every run, whatever the machine's speed.
"""

from __future__ import annotations

import asyncio
import logging

from aiobt.core.clock import Clock
from aiobt.msgs import GetCosts, PoseStamped
from aiobt.msgs.sim import Ack, RemoveObstacle, SpawnObstacle
from aiobt.transport import Bus
from aiobt.transport.keys import sim_namespace

log = logging.getLogger("aiobt.demo.boxes")
# x, y, size_x, size_y: one east of the nook from y 0.95 to the north edge, one from
# the wall's east end to the first; each far enough from the robot stopped within the
# goal checker's 0.25 m of (-1.5, 1.9) (the robot service refuses a box that touches it)
WALLS = ((-0.2, 1.675, 0.2, 1.45), (-0.6, 1.1, 0.9, 0.2))
BOX = tuple[float, float, float, float, float]  # x, y, yaw, size_x, size_y (for the picture)
INSCRIBED = 253  # a costmap cost the robot's centre cannot be on
COSTMAP = "global_costmap"  # the planner's, that the first plan is made on
SEEN_TIMEOUT = 30.0  # s of wall time for the planner's costmap to show the boxes
_LOOK_AGAIN = 0.1  # s of robot time between two looks at the costmap
CALL_TIMEOUT = 5.0  # s of wall time for a service answer (a loaded machine)


class WallIn:
    """Spawns :data:`WALLS`, waits until the planner sees them, takes them away."""

    def __init__(self, bus: Bus, clock: Clock) -> None:
        self.bus = bus
        self.sim = sim_namespace(bus.namespace)  # where the simulation's services are
        self.clock = clock
        self.ids: list[str] = []

    async def close(self) -> list[BOX]:
        """Put the boxes up and wait until the planner's costmap has them (the boxes
        put up, for the picture); RuntimeError says what failed."""
        placed = []
        for x, y, size_x, size_y in WALLS:
            box = SpawnObstacle(x=x, y=y, size_x=size_x, size_y=size_y)
            ack = await self.bus.call("obstacles/spawn", box, Ack, CALL_TIMEOUT, namespace=self.sim)
            if not ack.ok:
                raise RuntimeError(f"the robot refused the box at ({x}, {y}): {ack.message}")
            self.ids.append(ack.id)
            placed.append((x, y, 0.0, size_x, size_y))
        try:
            async with asyncio.timeout(SEEN_TIMEOUT):
                while not await self._seen():
                    await self.clock.sleep(_LOOK_AGAIN)
        except TimeoutError:
            raise RuntimeError(
                f"the planner's {COSTMAP} did not show the boxes within {SEEN_TIMEOUT:g} s"
            ) from None
        log.info("the robot is walled in by %d boxes (in the planner's costmap)", len(WALLS))
        return placed

    async def _seen(self) -> bool:
        centres = [PoseStamped.from_xy_yaw(x, y, 0.0) for x, y, _, _ in WALLS]
        request = GetCosts.Request(poses=centres)
        name = GetCosts.service_name(COSTMAP)
        answer = await self.bus.call(name, request, GetCosts.Response, CALL_TIMEOUT)
        return answer.success and all(cost >= INSCRIBED for cost in answer.costs)

    async def open(self) -> None:
        """Take the boxes away (each once; RuntimeError if the robot refuses)."""
        while self.ids:
            box = self.ids.pop()
            remove = RemoveObstacle(id=box)
            ack = await self.bus.call("obstacles/remove", remove, Ack, CALL_TIMEOUT,
                                      namespace=self.sim)  # fmt: skip
            if not ack.ok:
                raise RuntimeError(f"the robot did not remove box {box}: {ack.message}")
        log.info("the boxes are gone")
