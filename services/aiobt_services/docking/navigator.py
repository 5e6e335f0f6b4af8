"""The docking server's way to a staging pose (Nav2's ``opennav_docking::Navigator``):
a ``navigate_to_pose`` goal to the navigator, within the remaining ``max_staging_time``
(robot time), tried twice; FailedToStage otherwise. A cancelled docking goal cancels
the navigation goal."""

from __future__ import annotations

import asyncio
import logging

from aiobt.core.clock import Clock
from aiobt.geometry import Pose2D
from aiobt.msgs import GoalState, PoseStamped
from aiobt.msgs.actions import NavigateToPose
from aiobt.transport import Bus
from aiobt.transport.actions.protocol import GoalLost, GoalRejected, ServerUnavailable

from .errors import FailedToStage

log = logging.getLogger("aiobt_services.docking.navigator")
SERVER_WAIT = 2.0  # wall s for the navigator to accept (Nav2: 1 s wait + 2 s to accept)
CANCEL_WAIT = 1.0


class StagingNavigator:
    def __init__(self, bus: Bus, clock: Clock, behavior_tree: str = "") -> None:
        self.client = bus.action_client(NavigateToPose.name, NavigateToPose)
        self.clock = clock
        self.behavior_tree = behavior_tree

    async def __call__(self, pose: Pose2D, frame: str, max_time: float) -> None:
        began = self.clock.now()
        if await self._go(pose, frame, max_time):
            return
        log.warning("Navigation request to staging pose failed.")
        if await self._go(pose, frame, max_time - (self.clock.now() - began)):
            return
        raise FailedToStage("Navigation request to staging pose failed.")

    async def _go(self, pose: Pose2D, frame: str, max_time: float) -> bool:
        goal = NavigateToPose.Goal(
            pose=PoseStamped.from_xy_yaw(pose.x, pose.y, pose.yaw, frame or "map"),
            behavior_tree=self.behavior_tree,
        )
        try:
            sent = await self.client.send_goal(goal, server_timeout=SERVER_WAIT)
        except (ServerUnavailable, GoalRejected) as exc:
            log.warning("navigate_to_pose: %s", exc)
            return False
        timer = asyncio.ensure_future(self.clock.sleep(max(0.0, max_time)))
        ending = asyncio.ensure_future(sent.result())
        try:
            await asyncio.wait((timer, ending), return_when=asyncio.FIRST_COMPLETED)
            if not ending.done():
                raise FailedToStage("Navigation request to staging pose timed out.")
            result = ending.result()
        except GoalLost as exc:
            log.warning("navigate_to_pose: %s", exc)
            return False
        finally:
            timer.cancel()
            if not ending.done():
                ending.cancel()
                await sent.cancel(CANCEL_WAIT)
        return sent.status is GoalState.SUCCEEDED and result.error_code == 0
