"""The patrol: goals through the navigator, one of them blocked on the way (a recovery).

Runs against a system already up (see :func:`aiobt.system.run_system`), through
the same Python API a user embeds (:func:`aiobt.embed.connect`).
"""

from __future__ import annotations

import asyncio
import logging
import math
from collections.abc import Callable

from aiobt.demo.record import Leg, Record
from aiobt.embed import Feedback, RobotClient, pose
from aiobt.msgs import ComputePathToPose, OccupancyGrid, PoseStamped
from aiobt.transport import ActionError
from aiobt_services.robot.messages import Ack, SpawnObstacle

# the small world (5 m x 5 m, a wall at y = 1.2 from x = -2 to -1)
PATROL = (
    ("north-east corner", (1.5, 1.5, 1.57)),
    ("behind the wall", (-1.5, 1.9, 3.14)),
    ("south-west, a box dropped on the way", (-1.5, -1.6, -1.57)),
    ("home", (0.0, 0.0, 0.0)),
)
BLOCKED = 2  # the leg on which a box lands in front of the moving robot
DROP_AFTER = 0.6  # m driven on that leg before the box lands
BOX = (0.3, 0.6)  # m along and across the robot's heading
AHEAD = 0.65  # m from the robot to the box's centre: the robot service refuses a box it touches
PLAN_TIMEOUT = 30.0  # s of wall time for the planner's answer (a loaded machine is slow)
Progress = Callable[[int, Leg, Feedback], None]
log = logging.getLogger("aiobt.demo.mission")


class Patrol:
    def __init__(self, robot: RobotClient, record: Record, progress: Progress) -> None:
        self.robot = robot
        self.record = record
        self.progress = progress
        self.legs = [Leg(name, goal) for name, goal in PATROL]
        record.legs = self.legs
        self._heading = 0.0
        self._planner = robot.bus.action_client(ComputePathToPose.name, ComputePathToPose)

    def attach(self) -> None:
        self.robot.bus.subscribe("map", OccupancyGrid, self.record.on_map, latched=True)
        self.robot.bus.subscribe("pose", PoseStamped, self._on_pose)

    def _on_pose(self, msg: PoseStamped) -> None:
        self._heading = msg.yaw
        self.record.on_pose(msg)

    async def drive(self, number: int, leg: Leg) -> None:
        """Navigate leg ``number``; ``leg`` says how it went."""
        leg.plan = await self._plan(leg)
        began = self.robot.clock.now()
        dropper = asyncio.create_task(self._drop_box()) if number == BLOCKED else None

        def feedback(message: Feedback) -> None:
            if message.number_of_recoveries > leg.recoveries:
                self.record.recoveries.append(self.record.position)
                leg.recoveries = message.number_of_recoveries
            self.progress(number, leg, message)

        try:
            outcome = await self.robot.navigate_to(*leg.goal, on_feedback=feedback)
        finally:
            if dropper is not None:
                dropper.cancel()
                await asyncio.gather(dropper, return_exceptions=True)
                if not dropper.cancelled() and dropper.exception() is not None:
                    log.warning("the box was not dropped: %r", dropper.exception())
        leg.seconds = self.robot.clock.now() - began
        leg.reached = outcome.succeeded
        error = f" {outcome.error_code} {outcome.error_msg}" if outcome.error_code else ""
        leg.result = outcome.state.name + error

    async def _plan(self, leg: Leg) -> list[tuple[float, float]]:
        """The planner's path for ``leg`` from where the robot is (for the picture)."""
        goal = ComputePathToPose.Goal(goal=pose(*leg.goal), planner_id="GridBased")
        try:
            sent = await self._planner.send_goal(goal, server_timeout=PLAN_TIMEOUT)
            result = await sent.result(timeout=PLAN_TIMEOUT)
        except (ActionError, TimeoutError) as exc:
            log.warning("no path drawn for goal %s: %s", leg.name, exc)
            return []
        return [(p.x, p.y) for p in result.path.poses]

    async def _drop_box(self) -> None:
        start = self.record.position
        while math.dist(start, self.record.position) < DROP_AFTER:
            await self.robot.clock.sleep(0.05)
        (x, y), yaw = self.record.position, self._heading
        spot = (x + AHEAD * math.cos(yaw), y + AHEAD * math.sin(yaw))
        box = SpawnObstacle(x=spot[0], y=spot[1], yaw=yaw, size_x=BOX[0], size_y=BOX[1])
        ack = await self.robot.bus.call("obstacles/spawn", box, Ack, 5.0)
        if not ack.ok:
            raise RuntimeError(f"the robot refused the box: {ack.message}")
        self.record.obstacles.append((spot[0], spot[1], yaw, *BOX))
        log.info("a box landed %.2f m in front of the robot at (%.2f, %.2f)", AHEAD, *spot)
