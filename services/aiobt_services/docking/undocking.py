"""The ``undock_robot`` procedure (Nav2's ``DockingServer::undockRobot``), free of the
bus: the staging pose from where the robot stands (the dock's type from the goal or
from the last docking), charging disabled, then the controller back to it within
``undock_linear_tolerance`` / ``undock_angular_tolerance``, within the goal's
``max_undocking_time``; undocked once there and charging has stopped."""

from __future__ import annotations

import logging
import math

from aiobt.geometry import Pose2D

from .errors import FailedToControl
from .motion import Motion
from .plugins import ChargingDock

log = logging.getLogger("aiobt_services.docking.undocking")


async def undock(motion: Motion, plugin: ChargingDock, max_undocking_time: float) -> bool:
    """Back off the dock to its staging pose; False: the robot was not docked (nothing
    done); FailedToControl on a time-out or when charging goes on."""
    if plugin.is_charger and not plugin.is_docked() and not plugin.is_charging():
        log.info("Robot is not in the dock, no need to undock")
        return False
    fixed, p = motion.params.fixed_frame, motion.params
    here = motion.frames.robot(fixed)
    if plugin.backward:
        here = Pose2D(here.x, here.y, here.yaw + math.pi)
    staging = plugin.staging_pose(here, fixed)
    if plugin.rotate_to_dock:
        staging = Pose2D(staging.x, staging.y, staging.yaw + math.pi)
    began = motion.clock.now()
    while True:
        if motion.clock.now() - began > max_undocking_time:
            raise FailedToControl("Undocking timed out")
        if plugin.is_charger and not plugin.disable_charging():
            await motion.tick()
            continue
        linear, angular = p.undock_linear_tolerance, p.undock_angular_tolerance
        command = motion.command_to_pose(staging, fixed, linear, angular, not plugin.backward)
        if command is None:
            break
        motion.drive(command)
        await motion.tick()
    if plugin.rotate_to_dock:
        await motion.rotate_to(staging.yaw + math.pi, fixed)
    log.info("Robot has reached staging pose")
    motion.stop()
    if plugin.is_charger and not plugin.has_stopped_charging():
        raise FailedToControl("Failed to control off dock")
    log.info("Robot has undocked!")
    return True
