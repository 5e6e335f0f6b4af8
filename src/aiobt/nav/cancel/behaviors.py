"""The cancel leaves of Nav2's controller, behavior, coverage, route and following servers."""

from __future__ import annotations

from aiobt.msgs import (
    AssistedTeleop,
    BackUp,
    ComputeCoveragePath,
    DriveOnHeading,
    FollowPath,
    Spin,
    Wait,
)
from aiobt.msgs.remote_actions import ComputeAndTrackRoute, FollowObject
from aiobt.nav.cancel.base import BtCancelAction, cancel_ports


class CancelControl(BtCancelAction):
    """``<CancelControl server_name="follow_path"/>``: cancel the controller's goals."""

    ACTION = FollowPath
    PORTS = cancel_ports("controller server", FollowPath.name)


class CancelBackUp(BtCancelAction):
    """``<CancelBackUp/>``: cancel the backup behavior's goals."""

    ACTION = BackUp
    PORTS = cancel_ports("backup behavior", BackUp.name)


class CancelSpin(BtCancelAction):
    """``<CancelSpin/>``: cancel the spin behavior's goals."""

    ACTION = Spin
    PORTS = cancel_ports("spin behavior", Spin.name)


class CancelWait(BtCancelAction):
    """``<CancelWait/>``: cancel the wait behavior's goals."""

    ACTION = Wait
    PORTS = cancel_ports("wait behavior", Wait.name)


class CancelDriveOnHeading(BtCancelAction):
    """``<CancelDriveOnHeading/>``: cancel the drive-on-heading behavior's goals."""

    ACTION = DriveOnHeading
    PORTS = cancel_ports("drive on heading behavior", DriveOnHeading.name)


class CancelAssistedTeleop(BtCancelAction):
    """``<CancelAssistedTeleop/>``: cancel the assisted teleop behavior's goals."""

    ACTION = AssistedTeleop
    PORTS = cancel_ports("assisted teleop behavior", AssistedTeleop.name)


class CancelCoverage(BtCancelAction):
    """``<CancelCoverage/>``: cancel the coverage server's goals (opennav_coverage)."""

    ACTION = ComputeCoveragePath
    PORTS = cancel_ports("coverage server", ComputeCoveragePath.name)


class CancelComputeAndTrackRoute(BtCancelAction):
    """``<CancelComputeAndTrackRoute/>``: cancel the route tracker's goals."""

    ACTION = ComputeAndTrackRoute
    PORTS = cancel_ports("route compute and tracker server", ComputeAndTrackRoute.name)


class CancelFollowObject(BtCancelAction):
    """``<CancelFollowObject/>``: cancel the follow object behavior's goals."""

    ACTION = FollowObject
    PORTS = cancel_ports("follow object behavior", FollowObject.name)
