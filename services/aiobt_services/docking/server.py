"""The docking server's two executes (``dock_robot``, ``undock_robot``) and the dock
database it serves from, free of the bus: the robot, time, the base command and the
navigation to a staging pose come in through :class:`~.motion.Motion` and a callable,
so tests drive them with a simulated base."""

from __future__ import annotations

import asyncio
import logging
from collections.abc import Mapping
from typing import Any

from aiobt.geometry import Pose2D
from aiobt.msgs.remote_actions import DockRobot, UndockRobot, UndockRobotError

from .database import DockInstance
from .docking import DockingAttempt, DockTarget, Navigate
from .errors import DockingError, DockNotInDB, DockNotValid
from .motion import Motion
from .plugins import ChargingDock
from .undocking import undock

log = logging.getLogger("aiobt_services.docking.server")
UNDOCK_CODES = {int(code) for code in UndockRobotError}


class DockingServer:
    def __init__(self, motion: Motion, navigate: Navigate, plugins: Mapping[str, ChargingDock],
                 docks: Mapping[str, DockInstance]) -> None:  # fmt: skip
        self.motion = motion
        self.navigate = navigate
        self.plugins = dict(plugins)
        self.docks = dict(docks)
        self.database_error = ""  # why the dock database did not load, if it did not
        self.current_type = ""  # the dock type of the last successful docking
        self.docked_at = ""  # the dock's name while docked by this server
        self.lock = asyncio.Lock()  # one procedure at a time (Nav2's mutex)

    def find_plugin(self, kind: str) -> ChargingDock | None:
        """Nav2's findDockPlugin: by type, or the only plugin when the type is empty."""
        if not kind and len(self.plugins) == 1:
            return next(iter(self.plugins.values()))
        return self.plugins.get(kind)

    def target_of(self, goal: DockRobot.Goal) -> DockTarget:
        if goal.use_dock_id:
            dock = self.docks.get(goal.dock_id)
            if dock is None:
                known = ", ".join(sorted(self.docks)) or "none"
                why = f"; {self.database_error}" if self.database_error else ""
                raise DockNotInDB(f"Dock ID requested is not in database! ('{goal.dock_id}'; "
                                  f"known: {known}{why})")  # fmt: skip
        else:
            pose = goal.dock_pose
            dock = DockInstance(
                "", goal.dock_type, Pose2D(pose.x, pose.y, pose.yaw), pose.header.frame_id or "map"
            )
        plugin = self.find_plugin(dock.type)
        if plugin is None:
            raise DockNotValid(f"Dock type '{dock.type}' has no valid plugin! (loaded: "
                               f"{', '.join(self.plugins)})")  # fmt: skip
        return DockTarget(dock, plugin)

    async def dock_robot(self, goal: DockRobot.Goal, handle: Any) -> DockRobot.Result:
        async with self.lock:
            attempt = DockingAttempt(self.motion, self.navigate, handle.publish_feedback)
            target: DockTarget | None = None
            try:
                target = self.target_of(goal)
                log.info("Attempting to dock robot at %s.", target.dock.name or "the goal's pose")
                await attempt.run(target, goal)
            except (DockingError, LookupError) as exc:
                return self._failed_dock(exc, attempt.retries)
            finally:
                self.motion.stop()
                if target is not None:
                    await target.plugin.stop_detection()
            self.current_type, self.docked_at = target.dock.type, target.dock.name
            log.info(
                "Robot is charging!" if target.plugin.is_charger else "Docking was successful!"
            )
            return DockRobot.Result(success=True, num_retries=attempt.retries)

    async def undock_robot(self, goal: UndockRobot.Goal, handle: Any) -> UndockRobot.Result:
        async with self.lock:
            try:
                plugin = self.find_plugin(goal.dock_type or self.current_type)
                if plugin is None:
                    raise DockNotValid("No dock information to undock from!")
                log.info("Attempting to undock robot of dock type %s.", plugin.name)
                await undock(self.motion, plugin, goal.max_undocking_time)
            except (DockingError, LookupError) as exc:
                code, message = _code_and_message(exc)
                code = code if code in UNDOCK_CODES else int(UndockRobotError.UNKNOWN)
                log.error("%s", message)
                return UndockRobot.Result(success=False, error_code=code, error_msg=message)
            finally:
                self.motion.stop()
            self.current_type, self.docked_at = "", ""
            return UndockRobot.Result(success=True)

    @staticmethod
    def _failed_dock(exc: Exception, retries: int) -> DockRobot.Result:
        code, message = _code_and_message(exc)
        log.error("%s", message)
        return DockRobot.Result(success=False, error_code=code, error_msg=message,
                                num_retries=retries)  # fmt: skip


def _code_and_message(exc: Exception) -> tuple[int, str]:
    if isinstance(exc, DockingError):
        return int(exc.code), str(exc)
    return int(DockingError.code), f"Transform error: {exc}"
