"""``{ns}/sim/srv/follow_target/{start,hide,stop}`` on the bus: the followed box
started on a loop (given or seeded), hidden from the tracker a while, removed; its
detections on ``{ns}/{topic}`` (``PoseStamped`` in ``base_link``, stamped with the
scan's time), its truth on ``{ns}/sim/target`` (tests and viewers only)."""

from __future__ import annotations

import argparse
import logging
from collections.abc import Callable

from aiobt.msgs import Empty, LaserScan, Msg, PoseStamped
from aiobt.msgs import sim as messages
from aiobt.msgs.follow_target import HideTarget, StartTarget, TargetStarted
from aiobt.transport import Bus
from aiobt.transport.keys import sim_namespace, sim_topic

from .obstacles import ObstacleError
from .runner import Outputs
from .sim import Simulation
from .target import FollowTarget, TrackerConfig
from .target_path import LoopPath, PathError, seeded_loop

log = logging.getLogger("aiobt_services.robot.target")
TRUTH_TOPIC = sim_topic("target")
TRACKER = TrackerConfig()
CLEARANCE = 0.05  # m between the box and any wall along its path


class ScanTap:
    """The runner's outputs (an :class:`~.runner.Outputs`), and each scan to ``on_scan``:
    the tracker reads the scan that is published, at its step."""

    def __init__(self, outputs: Outputs, on_scan: Callable[[LaserScan], None]) -> None:
        self._outputs = outputs
        self._on_scan = on_scan

    def publish(self, topic: str, msg: Msg) -> None:
        self._outputs.publish(topic, msg)
        if topic == "scan" and isinstance(msg, LaserScan):
            self._on_scan(msg)


class TargetService:
    """The one followed box of a robot service (a new start replaces it)."""

    def __init__(self, sim: Simulation, bus: Bus, topic: str, tracker: TrackerConfig) -> None:
        self.sim = sim
        self.tracker = tracker
        self.target: FollowTarget | None = None
        self._detections = bus.publisher(topic, PoseStamped)
        self._truth = bus.publisher(TRUTH_TOPIC, PoseStamped)
        sim_ns = sim_namespace(bus.namespace)  # the simulation's own services
        bus.serve("follow_target/start", StartTarget, TargetStarted, self.start, namespace=sim_ns)
        bus.serve("follow_target/hide", HideTarget, messages.Ack, self.hide, namespace=sim_ns)
        bus.serve("follow_target/stop", Empty, messages.Ack, self.stop, namespace=sim_ns)
        sim.movers.append(self.update)

    def update(self) -> None:
        if self.target is not None:
            self.target.update()

    def on_scan(self, scan: LaserScan) -> None:
        """The tracker's detection from this scan, and the truth at its time."""
        target, stamp = self.target, scan.header.stamp
        if target is None:
            return
        truth = target.pose
        self._truth.put(PoseStamped.from_xy_yaw(truth.x, truth.y, truth.yaw, "map", stamp))
        seen = target.detect(scan)
        if seen is not None:
            self._detections.put(
                PoseStamped.from_xy_yaw(seen.x, seen.y, seen.yaw, "base_link", stamp)
            )

    def tap(self, outputs: Outputs) -> ScanTap:
        """``outputs`` with each scan also handed to the tracker."""
        return ScanTap(outputs, self.on_scan)

    def start(self, req: StartTarget) -> TargetStarted:
        try:
            path = (
                LoopPath.through(req.waypoints)
                if req.waypoints
                else seeded_loop(req.centre, req.radii, req.seed)
            )
            path.check_clear(self.sim.world, 0.5 * req.size * 2**0.5 + CLEARANCE)
            self._remove()
            self.target = FollowTarget(self.sim, req.id, path, req.speed, req.size,
                                       req.height, req.hold, self.tracker)  # fmt: skip
        except (PathError, ObstacleError) as exc:
            return TargetStarted(ok=False, message=f"sim/srv/follow_target/start: {exc}")
        start = path.pose_at(0.0)
        log.info("followed box '%s' on a %.1f m loop from (%.2f, %.2f) at %.2f m/s",
                 req.id, path.length, start.x, start.y, req.speed)  # fmt: skip
        return TargetStarted(ok=True, x=start.x, y=start.y, yaw=start.yaw, length=path.length)

    def hide(self, req: HideTarget) -> messages.Ack:
        if self.target is None:
            return messages.Ack(ok=False, message="sim/srv/follow_target/hide: no box started")
        self.target.hide(req.seconds)
        return messages.Ack(ok=True, message=f"hidden for {req.seconds:g} s", id=self.target.id)

    def stop(self, _req: Empty) -> messages.Ack:
        if self.target is None:
            return messages.Ack(ok=False, message="sim/srv/follow_target/stop: no box started")
        oid = self.target.id
        self._remove()
        return messages.Ack(ok=True, message="removed", id=oid)

    def _remove(self) -> None:
        target, self.target = self.target, None
        if target is not None and target.id in self.sim.obstacles:
            self.sim.remove(target.id)


def add_target_arguments(parser: argparse.ArgumentParser) -> None:
    group = parser.add_argument_group("followed object (sim/srv/follow_target/*)")
    add = group.add_argument
    add("--follow-target", type=int, default=None, metavar="SEED",
        help="start the followed box at start-up on the loop of this seed")  # fmt: skip
    add("--target-topic", default="dynamic_pose", metavar="KEY",
        help="its detections on {ns}/KEY (default: %(default)s)")  # fmt: skip
    add("--target-min-points", type=int, default=TRACKER.min_points,
        help="fewest lidar returns on it for a detection (default: %(default)s)")  # fmt: skip
    add("--target-dropout", type=float, default=TRACKER.dropout,
        help="share of scans the tracker misses it in (default: %(default)s)")  # fmt: skip


def wire_target(bus: Bus, sim: Simulation, args: argparse.Namespace) -> TargetService:
    """The target's services on ``bus``; :meth:`TargetService.tap` feeds its tracker."""
    tracker = TrackerConfig(args.target_min_points, args.target_dropout)
    service = TargetService(sim, bus, args.target_topic, tracker)
    if args.follow_target is not None:
        started = service.start(StartTarget(seed=args.follow_target))
        if not started.ok:
            log.error("--follow-target %d: %s", args.follow_target, started.message)
    return service
