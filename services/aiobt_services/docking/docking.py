"""The ``dock_robot`` procedure (Nav2's ``DockingServer::dockRobot``), free of the bus.

1. The dock from the database (``dock_id``) or the goal (``dock_pose``, ``dock_type``).
2. Already docked or charging: success at once.
3. Outside ``dock_prestaging_tolerance`` of the staging pose (and asked to): navigate
   there (``navigate_to_pose``, within ``max_staging_time``).
4. Initial perception of the dock (``initial_perception_timeout``).
5. Approach with the controller toward the refined dock pose, projected 0.25 m beyond
   it, until docked or charging (``dock_approach_timeout``); wait for charge
   (``wait_charge_timeout``).
6. A failure in 4-5 drives back to the staging pose and tries again, ``max_retries``
   times. Every failure is a result with Nav2's code and message; a cancelled goal
   stops the robot and ends.
"""

from __future__ import annotations

import logging
import math
from collections.abc import Awaitable, Callable
from dataclasses import dataclass

from aiobt.geometry import Pose2D
from aiobt.msgs.remote_actions import DockRobot

from .database import DockInstance
from .errors import DockingError, FailedToCharge, FailedToControl, FailedToDetectDock
from .motion import Motion, l2_norm
from .plugins import ChargingDock

log = logging.getLogger("aiobt_services.docking.docking")
BACKWARD_PROJECTION = 0.25  # m beyond the dock the controller aims at (Nav2's)
Navigate = Callable[[Pose2D, str, float], Awaitable[None]]  # raises FailedToStage


class State:
    """DockRobot's feedback states."""

    NONE, NAV_TO_STAGING_POSE, INITIAL_PERCEPTION, CONTROLLING, WAIT_FOR_CHARGE, RETRY = range(6)


@dataclass(slots=True)
class DockTarget:
    """The dock of a goal: its instance and its plugin."""

    dock: DockInstance
    plugin: ChargingDock


class DockingAttempt:
    """One DockRobot goal: ``feedback`` receives each state change and loop."""

    def __init__(self, motion: Motion, navigate: Navigate,
                 feedback: Callable[[DockRobot.Feedback], None]) -> None:  # fmt: skip
        self.motion = motion
        self.navigate = navigate
        self._feedback = feedback
        self.began = motion.clock.now()
        self.retries = 0

    def feedback(self, state: int) -> None:
        elapsed = max(0.0, self.motion.clock.now() - self.began)
        self._feedback(DockRobot.Feedback(state=state, docking_time=elapsed,
                                          num_retries=self.retries))  # fmt: skip

    async def run(self, target: DockTarget, goal: DockRobot.Goal) -> None:
        """Dock, or raise a DockingError; returns once charging (or docked)."""
        dock, plugin = target.dock, target.plugin
        if plugin.is_charger and (plugin.is_docked() or plugin.is_charging()):
            log.info("Robot is already docked and/or charging (if applicable), no need to dock")
            return
        await self._stage(target, goal)
        fixed = self.motion.params.fixed_frame
        dock_pose = self.motion.frames.transform(dock.pose, dock.frame, fixed)
        dock_pose = await self._initial_perception(target, dock_pose)
        log.info("Successful initial dock detection")
        staging = plugin.staging_pose(dock.pose, dock.frame)
        if plugin.rotate_to_dock:
            staging = Pose2D(staging.x, staging.y, staging.yaw + math.pi)
        while True:
            try:
                if plugin.rotate_to_dock:
                    await self.motion.rotate_to(dock_pose.yaw + math.pi, fixed)
                dock_pose = await self._approach(target, dock_pose)
                log.info("Made contact with dock, waiting for charge to start (if applicable).")
                self.motion.stop()
                await self._wait_for_charge(plugin)
                return
            except DockingError as exc:
                self.retries += 1
                if self.retries > self.motion.params.max_retries:
                    log.error("Failed to dock, all retries have been used")
                    raise
                log.warning("Docking failed, will retry: %s", exc)
            await self._reset_approach(staging, dock.frame, plugin.backward)
            log.info("Returned to staging pose, attempting docking again")

    async def _stage(self, target: DockTarget, goal: DockRobot.Goal) -> None:
        self.feedback(State.NAV_TO_STAGING_POSE)
        staging = target.plugin.staging_pose(target.dock.pose, target.dock.frame)
        robot = self.motion.frames.robot(target.dock.frame)
        tolerance = self.motion.params.dock_prestaging_tolerance
        if not goal.navigate_to_staging_pose or l2_norm(robot, staging) < tolerance:
            log.info("Robot already within pre-staging pose tolerance for dock")
            return
        frame = target.dock.frame
        if not self.motion.frames.knows(frame):  # a frame of tf_static: the navigator's map
            staging, frame = self.motion.frames.transform(staging, frame, "map"), "map"
        await self.navigate(staging, frame, goal.max_staging_time)
        log.info("Successful navigation to staging pose")

    async def _initial_perception(self, target: DockTarget, estimate: Pose2D) -> Pose2D:
        self.feedback(State.INITIAL_PERCEPTION)
        plugin, m = target.plugin, self.motion
        if not await plugin.start_detection():
            raise FailedToDetectDock("Failed to start the detection process.")
        began = m.clock.now()
        while (
            found := plugin.refined_pose(estimate, m.params.fixed_frame, target.dock.id)
        ) is None:
            if m.clock.now() - began > m.params.initial_perception_timeout:
                raise FailedToDetectDock("Failed initial dock detection: Timeout exceeded")
            await m.tick()
        return found

    async def _approach(self, target: DockTarget, dock_pose: Pose2D) -> Pose2D:
        """Drive onto the dock until docked (or charging); the newest dock pose."""
        plugin, m = target.plugin, self.motion
        began, fixed = m.clock.now(), m.params.fixed_frame
        while True:
            self.feedback(State.CONTROLLING)
            if plugin.is_docked() or (plugin.is_charger and plugin.is_charging()):
                return dock_pose
            refined = plugin.refined_pose(dock_pose, fixed, target.dock.id)
            if refined is None and not plugin.rotate_to_dock:
                raise FailedToDetectDock("Failed dock detection")
            dock_pose = refined or dock_pose
            m.refresh()
            aim = self._aim(dock_pose, plugin.backward)
            m.drive(m.controller.command(aim, plugin.backward, docking=True))
            if m.clock.now() - began > m.params.dock_approach_timeout:
                raise FailedToControl("Timed out approaching dock; dock nor charging (if "
                                      "applicable) detected")  # fmt: skip
            await m.tick()

    def _aim(self, dock_pose: Pose2D, backward: bool) -> Pose2D:
        """The controller's target in the robot's frame: the dock projected beyond it
        (so the spiral never ends before contact), turned round when docking backward."""
        c, s = math.cos(dock_pose.yaw), math.sin(dock_pose.yaw)
        beyond = Pose2D(dock_pose.x + c * BACKWARD_PROJECTION,
                        dock_pose.y + s * BACKWARD_PROJECTION, dock_pose.yaw)  # fmt: skip
        local = self.motion.frames.transform(beyond, self.motion.params.fixed_frame, "base_link")
        return Pose2D(local.x, local.y, local.yaw + math.pi) if backward else local

    async def _wait_for_charge(self, plugin: ChargingDock) -> None:
        if not plugin.is_charger:
            return
        m = self.motion
        began = m.clock.now()
        while True:
            self.feedback(State.WAIT_FOR_CHARGE)
            if plugin.is_charging():
                return
            if m.clock.now() - began > m.params.wait_charge_timeout:
                raise FailedToCharge("Timed out waiting for charge to start")
            await m.tick()

    async def _reset_approach(self, staging: Pose2D, frame: str, backward: bool) -> None:
        m = self.motion
        began, p = m.clock.now(), m.params
        while True:
            self.feedback(State.INITIAL_PERCEPTION)
            command = m.command_to_pose(staging, frame, p.undock_linear_tolerance,
                                        p.undock_angular_tolerance, not backward)  # fmt: skip
            if command is None:
                return
            m.drive(command)
            if m.clock.now() - began > p.dock_approach_timeout:
                raise FailedToControl("Timed out resetting dock approach")
            await m.tick()
