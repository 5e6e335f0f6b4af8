"""The docking server's database on the wire: the docks for viewers (latched on
``{ns}/docks``), the server's docked state (latched on ``{ns}/docking_state``) and
``nav2_msgs/ReloadDockDatabase``. The actions (``DockRobot``, ``UndockRobot``) are in
:mod:`aiobt.msgs.remote_actions`."""

from __future__ import annotations

from typing import ClassVar, TypeAlias

from pydantic import Field

from aiobt.msgs._base import Msg
from aiobt.msgs.geometry import PoseStamped


class DockEntry(Msg):
    """One dock of the database: its name (a DockRobot ``dock_id``), plugin type, the
    pose where the robot stands docked, and its staging pose (both in the dock's frame)."""

    name: str
    type: str = ""
    id: str = ""
    pose: PoseStamped = Field(default_factory=PoseStamped)
    staging: PoseStamped | None = None


class DockList(Msg):
    """Every dock the docking server knows (empty when its database did not load)."""

    docks: list[DockEntry] = Field(default_factory=list)


class DockingState(Msg):
    """Whether the docking server has the robot docked (an ``IsDocked`` for watchers):
    set by a successful DockRobot, cleared by a successful UndockRobot."""

    docked: bool = False
    dock: str = ""  # the dock's name, when docked at one of the database
    dock_type: str = ""


class _ReloadRequest(Msg):
    filepath: str


class _ReloadResponse(Msg):
    success: bool = False
    message: str = ""  # aiobt's addition: why it failed


class ReloadDockDatabase:
    """``nav2_msgs/ReloadDockDatabase`` (``docking_server/reload_database``): load another
    dock database; after a failure the one in use stays."""

    service_name: ClassVar[str] = "docking_server/reload_database"
    Request: TypeAlias = _ReloadRequest
    Response: TypeAlias = _ReloadResponse
