"""Nav2's docking exceptions (``opennav_docking_core/docking_exceptions.hpp``), each
with the DockRobot / UndockRobot error code the server answers with."""

from __future__ import annotations

from aiobt.msgs.remote_actions import DockRobotError


class DockingError(Exception):
    """A docking failure; ``code``: the DockRobot result's error code."""

    code: DockRobotError = DockRobotError.UNKNOWN


class DockNotInDB(DockingError):
    code = DockRobotError.DOCK_NOT_IN_DB


class DockNotValid(DockingError):
    code = DockRobotError.DOCK_NOT_VALID


class FailedToStage(DockingError):
    code = DockRobotError.FAILED_TO_STAGE


class FailedToDetectDock(DockingError):
    code = DockRobotError.FAILED_TO_DETECT_DOCK


class FailedToControl(DockingError):
    code = DockRobotError.FAILED_TO_CONTROL


class FailedToCharge(DockingError):
    code = DockRobotError.FAILED_TO_CHARGE


class DockDatabaseError(ValueError):
    """A dock database that does not load: the message names the file, line and dock."""
