"""The robot's control surface as plain methods: what each topic and service does.

The Zenoh main wires these to ``{ns}/cmd_vel``, ``{ns}/initialpose`` and the
``srv/...`` queryables; tests call them directly.
"""

from __future__ import annotations

import itertools
import logging
from pathlib import Path

from aiobt.geometry import Pose2D
from aiobt.msgs import Empty, PoseStamped, Twist
from aiobt.msgs.sim import (
    Ack,
    MoveObstacle,
    ObstacleList,
    RemoveObstacle,
    Snapshot,
    SnapshotRequest,
    SpawnObstacle,
)

from . import convert
from .obstacles import ObstacleError
from .sim import PoseError, Simulation
from .snapshot import render_png

log = logging.getLogger("aiobt_services.robot.service")

INITIALPOSE_MODES = ("teleport", "localize")


class RobotService:
    """Commands and requests applied to one :class:`Simulation`."""

    def __init__(self, sim: Simulation, *, initialpose: str = "teleport") -> None:
        if initialpose not in INITIALPOSE_MODES:
            raise ValueError(f"initialpose mode must be one of {INITIALPOSE_MODES}")
        self.sim = sim
        self.initialpose_mode = initialpose
        self._ids = itertools.count(1)

    # -- topics ----------------------------------------------------------
    def on_cmd_vel(self, msg: Twist) -> None:
        self.sim.command(msg.linear.x, msg.angular.z)

    def on_initialpose(self, msg: PoseStamped) -> None:
        """Teleport (default) or only re-seat the localization estimate (``localize``)."""
        ack = self._set_pose(msg, self.initialpose_mode)
        if not ack.ok:
            log.warning("initialpose refused: %s", ack.message)

    # -- services --------------------------------------------------------
    def reset_pose(self, msg: PoseStamped) -> Ack:
        """``sim/srv/reset_pose``: move the robot there (refused if outside or blocked)."""
        return self._set_pose(msg, "teleport")

    def reinitialize_localization(self, _: Empty) -> Ack:
        """``srv/reinitialize_global_localization``: the estimate snaps to the truth."""
        self.sim.reinitialize_localization()
        return Ack(ok=True, message="localization reinitialized")

    def spawn(self, req: SpawnObstacle) -> Ack:
        oid = req.id or self._fresh_id()
        try:
            self.sim.spawn(convert.obstacle_spec(req, oid))
        except ObstacleError as exc:
            return Ack(ok=False, message=str(exc), id=oid)
        log.info("spawned %s '%s' at (%.2f, %.2f)", req.shape, oid, req.x, req.y)
        return Ack(ok=True, message="spawned", id=oid)

    def move(self, req: MoveObstacle) -> Ack:
        try:
            self.sim.move(req.id, *convert.move_args(req))
        except ObstacleError as exc:
            return Ack(ok=False, message=str(exc), id=req.id)
        return Ack(ok=True, message="moved", id=req.id)

    def remove(self, req: RemoveObstacle) -> Ack:
        try:
            self.sim.remove(req.id)
        except ObstacleError as exc:
            return Ack(ok=False, message=str(exc), id=req.id)
        return Ack(ok=True, message="removed", id=req.id)

    def list_obstacles(self, _: Empty) -> ObstacleList:
        return ObstacleList(
            obstacles=[convert.obstacle_state(self.sim, oid) for oid in sorted(self.sim.obstacles)]
        )

    def snapshot(self, req: SnapshotRequest) -> Snapshot:
        png = render_png(self.sim, scale=req.scale, with_scan=req.with_scan)
        width, height = self.sim.world.width * req.scale, self.sim.world.height * req.scale
        if req.path:
            try:
                Path(req.path).write_bytes(png)
            except OSError as exc:
                return Snapshot(ok=False, message=f"cannot write {req.path}: {exc}")
        return Snapshot(width=width, height=height, png=png, path=req.path)

    # -- helpers ---------------------------------------------------------
    def _fresh_id(self) -> str:
        while (oid := f"obstacle_{next(self._ids)}") in self.sim.obstacles:
            pass
        return oid

    def _set_pose(self, msg: PoseStamped, mode: str) -> Ack:
        frame = msg.header.frame_id
        if frame not in ("map", ""):
            return Ack(ok=False, message=f"header.frame_id must be 'map', got {frame!r}")
        pose = Pose2D(msg.x, msg.y, msg.yaw)
        if mode == "localize":
            self.sim.set_localization(pose)
            return Ack(ok=True, message="localization estimate set")
        try:
            self.sim.teleport(pose)
        except PoseError as exc:
            return Ack(ok=False, message=str(exc))
        log.info("robot moved to (%.2f, %.2f, %.2f)", pose.x, pose.y, pose.yaw)
        return Ack(ok=True, message="robot moved")
