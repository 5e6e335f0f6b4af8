"""The robot service's followed object (a box moving along a path, detected by a
tracker on the robot's lidar): the requests of
``{ns}/sim/srv/follow_target/{start,hide,stop}``.
Its truth goes to ``{ns}/sim/target``, its detections to ``{ns}/dynamic_pose``."""

from __future__ import annotations

from pydantic import Field

from aiobt.msgs._base import Msg

OFFICE_LOOP_CENTRE = (7.5, 13.6)  # the office world's open plan, round both pillars
OFFICE_LOOP_RADII = (3.6, 1.8)


class StartTarget(Msg):
    """``sim/srv/follow_target/start``: a box of ``size`` m moving at ``speed`` along
    ``waypoints`` (a closed loop through them), or, without waypoints, along a loop
    drawn from ``seed``: an ellipse of ``radii`` round ``centre`` with seeded bumps,
    a seeded start and direction. It waits ``hold`` s of sim time before moving."""

    id: str = "target"
    waypoints: list[tuple[float, float]] = Field(default_factory=list)
    seed: int = 0
    centre: tuple[float, float] = OFFICE_LOOP_CENTRE
    radii: tuple[float, float] = OFFICE_LOOP_RADII
    speed: float = Field(default=0.3, ge=0.0, description="m/s")
    size: float = Field(default=0.4, gt=0.0, description="m, a square box")
    height: float = Field(default=1.0, gt=0.0)
    hold: float = Field(default=0.0, ge=0.0, description="s of sim time before it moves")


class TargetStarted(Msg):
    """The reply: ``ok`` or the reason; where the box starts and which way it heads."""

    ok: bool
    message: str = ""
    x: float = 0.0
    y: float = 0.0
    yaw: float = 0.0
    length: float = Field(default=0.0, description="m, the loop's length")


class HideTarget(Msg):
    """``sim/srv/follow_target/hide``: no detection of the box for ``seconds`` of sim
    time (it is hidden from the tracker: occluded, out of its view)."""

    seconds: float = Field(gt=0.0)
