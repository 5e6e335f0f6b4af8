"""The patrol: goals through the navigator, one of them walled in until a recovery.

Runs against a system already up (see :func:`aiobt.system.run_system`), through
the same Python API a user embeds (:func:`aiobt.embed.connect`).
"""

from __future__ import annotations

import asyncio
import logging
from collections.abc import Callable

from aiobt.demo.boxes import WallIn
from aiobt.demo.record import Leg, Record
from aiobt.embed import Feedback, RobotClient, pose
from aiobt.msgs import ComputePathToPose, OccupancyGrid, PoseStamped
from aiobt.transport import ActionError
from aiobt.transport.keys import SIM_POSE

# the small world (5 m x 5 m, a wall at y = 1.2 from x = -2 to -1)
PATROL = (
    ("north-east corner", (1.5, 1.5, 1.57)),
    ("behind the wall", (-1.5, 1.9, 3.14)),
    ("south-west, walled in until a recovery", (-1.5, -1.6, -1.57)),
    ("home", (0.0, 0.0, 0.0)),
)
WALLED_IN = 2  # the leg that starts walled in by boxes (see aiobt.demo.boxes)
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
        # the picture may read the truth (a viewer; no navigation service does)
        self.robot.bus.subscribe(SIM_POSE, PoseStamped, self.record.on_truth)

    def _on_pose(self, msg: PoseStamped) -> None:
        self._heading = msg.yaw
        self.record.on_pose(msg)

    async def drive(self, number: int, leg: Leg) -> None:
        """Navigate leg ``number``; ``leg`` says how it went."""
        leg.plan = await self._plan(leg)  # before the walls: the way out, once they are gone
        walls = WallIn(self.robot.bus, self.robot.clock) if number == WALLED_IN else None
        if walls is not None:
            await self._wall_in(walls)
        began = self.robot.clock.now()
        opening: list[asyncio.Task[None]] = []

        def feedback(message: Feedback) -> None:
            if message.number_of_recoveries > leg.recoveries:
                self.record.recoveries.append(self.record.position)
                leg.recoveries = message.number_of_recoveries
                if walls is not None and not opening:
                    opening.append(asyncio.create_task(walls.open()))
            self.progress(number, leg, message)

        try:
            outcome = await self.robot.navigate_to(*leg.goal, on_feedback=feedback)
        finally:
            if walls is not None:
                await self._open(walls, opening)
        leg.seconds = self.robot.clock.now() - began
        leg.reached = outcome.succeeded
        error = f" {outcome.error_code} {outcome.error_msg}" if outcome.error_code else ""
        leg.result = outcome.state.name + error

    async def _wall_in(self, walls: WallIn) -> None:
        try:
            self.record.obstacles.extend(await walls.close())
        except (RuntimeError, ActionError, TimeoutError) as exc:
            log.warning("the robot is not walled in (no recovery forced): %s", exc)

    async def _open(self, walls: WallIn, opening: list[asyncio.Task[None]]) -> None:
        """Wait for the removal the first recovery started, or remove the boxes now."""
        try:
            await (opening[0] if opening else walls.open())
        except (RuntimeError, ActionError, TimeoutError) as exc:
            log.warning("the boxes were not all removed: %s", exc)

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
