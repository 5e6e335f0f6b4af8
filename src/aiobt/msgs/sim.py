"""The simulation's messages: its time on ``{ns}/clock`` when services run on sim time,
obstacle control, the bumper, and the small request/reply services of the robot service
(the simulation's own, ``{ns}/sim/srv/...``: ``aiobt.transport.keys.sim_namespace``)."""

from __future__ import annotations

from typing import Literal

from pydantic import Field

from aiobt.msgs._base import Msg
from aiobt.msgs.geometry import Header, Point


class Clock(Msg):
    """The simulation's time in seconds (``rosgraph_msgs/Clock``)."""

    clock: float = Field(ge=0.0)


class ObstacleMotion(Msg):
    """Back and forth between the obstacle's position and ``(to_x, to_y)``."""

    to_x: float
    to_y: float
    speed: float = Field(gt=0.0, description="m/s")


class SpawnObstacle(Msg):
    """``sim/srv/obstacles/spawn``: a box (size_x x size_y) or a cylinder (radius)."""

    id: str = Field(default="", description="empty: the service picks one")
    shape: Literal["box", "cylinder"] = "box"
    x: float
    y: float
    yaw: float = 0.0
    size_x: float = Field(default=0.5, gt=0.0)
    size_y: float = Field(default=0.5, gt=0.0)
    radius: float = Field(default=0.25, gt=0.0)
    height: float = Field(default=1.0, gt=0.0)
    motion: ObstacleMotion | None = None


class MoveObstacle(Msg):
    """``sim/srv/obstacles/move``: a new pose, and a new motion (or none: it stands still)."""

    id: str
    x: float
    y: float
    yaw: float = 0.0
    motion: ObstacleMotion | None = None


class RemoveObstacle(Msg):
    """``sim/srv/obstacles/remove``."""

    id: str


class ObstacleState(Msg):
    id: str
    shape: str
    x: float
    y: float
    yaw: float
    size_x: float
    size_y: float
    radius: float
    height: float
    moving: bool


class ObstacleList(Msg):
    """Reply of ``sim/srv/obstacles/list``."""

    obstacles: list[ObstacleState] = Field(default_factory=list)


class Ack(Msg):
    """Reply of the robot's services: ``ok`` false with the reason in ``message``."""

    ok: bool
    message: str = ""
    id: str = ""


class BumperEvent(Msg):
    """``{ns}/bumper``: contact with a wall or obstacle began (pressed) or ended."""

    header: Header = Field(default_factory=lambda: Header(frame_id="map"))
    pressed: bool
    other: str = Field(description='"wall" or the obstacle id')
    point: Point = Field(default_factory=Point, description="contact point in map")
    angle: float = Field(description="direction of the contact from the robot, rad, 0 = ahead")


class SnapshotRequest(Msg):
    """``sim/srv/snapshot``: a top-down PNG; written to ``path`` on the robot's host if given."""

    scale: int = Field(default=2, ge=1, le=8, description="pixels per map cell")
    with_scan: bool = True
    path: str = ""


class Snapshot(Msg):
    ok: bool = True
    message: str = ""
    width: int = 0
    height: int = 0
    png: bytes = b""
    path: str = ""


class StepRequest(Msg):
    """``sim/srv/step`` (``--stepped`` only): advance the simulation by ``seconds``."""

    seconds: float = Field(gt=0.0, le=3600.0)


class StepReply(Msg):
    time: float = Field(description="sim time after the step")
    steps: int = Field(description="physics steps taken")
