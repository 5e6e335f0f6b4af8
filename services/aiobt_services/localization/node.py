"""What ``amcl_node`` does with each message, without Zenoh: the map, odometry,
scans, initial poses and the two services in; the messages to publish out. The
service's ``main`` wires these methods to keys; tests call them directly.
"""

from __future__ import annotations

import logging
import math
import threading
import time
from collections.abc import Callable, Iterable
from dataclasses import dataclass, field

import numpy as np

from aiobt.msgs import (
    LaserScan,
    Msg,
    OccupancyGrid,
    Odometry,
    PoseWithCovarianceStamped,
)
from aiobt.robot.correction import compose, correction_message

from . import convert
from .amcl import Amcl
from .initial_pose import InitialPoseError, covariance_from_6x6
from .laser_model import (
    Beams,
    ScanError,
    check_scan_shape,
    effective_range_limits,
    select_beams,
)
from .likelihood_field import LikelihoodField, MapError
from .odom_buffer import OdomBuffer
from .params import AmclParams
from .se2 import FloatArray

log = logging.getLogger("aiobt_services.localization.node")


@dataclass(slots=True, frozen=True)
class Reply:
    """A service's or a topic's outcome: ``ok`` and why."""

    ok: bool
    message: str


@dataclass(slots=True, frozen=True)
class ScanJob:
    """One scan as the filter takes it: its stamp, the odometry then, its beams."""

    stamp: float
    odom_pose: FloatArray
    beams: Beams


@dataclass(slots=True)
class UpdateStats:
    """Scans seen, filter updates, their CPU seconds (the update's own thread time)."""

    scans: int = 0
    updates: int = 0
    skipped_no_odom: int = 0
    skipped_before_reset: int = 0  # taken before the last initial pose or global reset
    skipped_still: int = 0  # no motion since the last update: the filter takes no scan
    update_cpu: list[float] = field(default_factory=list)
    update_wall: list[float] = field(default_factory=list)  # scan read -> outputs sent

    def record(self, seconds: float) -> None:
        self.updates += 1
        if len(self.update_cpu) < 100_000:
            self.update_cpu.append(seconds)

    def record_latency(self, seconds: float) -> None:
        if len(self.update_wall) < 100_000:
            self.update_wall.append(seconds)


class LocalizationNode:
    """One robot's AMCL: call :meth:`on_map`, :meth:`on_odom`, :meth:`on_scan`, ...;
    each returns the messages to publish as ``(topic, message)`` pairs."""

    def __init__(
        self,
        params: AmclParams,
        rng: np.random.Generator | None = None,
        wanted: Callable[[str], bool] = lambda _topic: True,
        odometry: Callable[[], Iterable[Odometry]] = list,
    ) -> None:
        self.params = params
        # the odometry received since the last call, oldest first, for a reader that
        # does not hand each message to :meth:`on_odom` (the service's Zenoh ring)
        self._odometry = odometry
        # whether ``pose`` or ``particle_cloud`` has a reader now: neither is built for
        # none (an idle stack reads no pose; only viewers read the cloud)
        self._wanted = wanted
        self.amcl = Amcl(params, rng)
        self.odom = OdomBuffer()
        self.stats = UpdateStats()
        self._map_seen = False
        self._frame = params.global_frame_id
        # the filter's state: a scan's update may run on a worker thread; the map, an
        # initial pose and the services change it under this lock too (the pose stream,
        # on_odom, only reads map_to_odom, replaced whole)
        self.lock = threading.RLock()
        # the newest odometry's stamp when the filter was last set (initial pose, global
        # localization): a scan taken before it may show another place (a robot carried
        # off, then the pose given), and is not weighed against the new particles
        self._reset_at = -math.inf

    @property
    def has_map(self) -> bool:
        return self.amcl.field is not None

    # -- the map -----------------------------------------------------------
    def on_map(self, grid: OccupancyGrid) -> Reply:
        """Build the likelihood field (once per map; ``first_map_only`` keeps the first)."""
        if self._map_seen and self.params.first_map_only:
            return Reply(True, "map ignored: first_map_only")
        origin = grid.info.origin.position
        p = self.params
        try:
            field_ = LikelihoodField.build(
                grid.array, grid.info.resolution, (origin.x, origin.y),
                max_dist=p.laser_likelihood_max_dist, z_hit=p.z_hit, sigma_hit=p.sigma_hit,
            )  # fmt: skip
        except MapError as exc:
            return Reply(False, f"map refused: {exc}")
        with self.lock:
            self.amcl.set_map(field_)
        first, self._map_seen = not self._map_seen, True
        log.info("map %dx%d at %g m/cell: likelihood field ready", *grid.array.shape[::-1],
                 grid.info.resolution)  # fmt: skip
        if first and p.set_initial_pose:
            ip = p.initial_pose
            return self.initial_pose(ip.x, ip.y, ip.yaw, None, "parameter initial_pose")
        return Reply(True, "map ready")

    # -- odometry: {ns}/pose at odometry rate -------------------------------
    def on_odom(self, msg: Odometry) -> list[tuple[str, Msg]]:
        """Record the odometry; the estimate composed with it as ``pose`` once known."""
        self._record(msg)
        return self.pose_for(msg)

    def take_odometry(self) -> None:
        """Record the odometry the ``odometry`` source holds (in the order it came)."""
        for msg in self._odometry():
            self._record(msg)

    def _record(self, msg: Odometry) -> None:
        position = msg.pose.position
        self.odom.add(msg.header.stamp, position.x, position.y, msg.pose.yaw)

    def pose_for(self, msg: Odometry) -> list[tuple[str, Msg]]:
        """The estimate composed with ``msg``'s pose in ``odom``, stamped with its stamp,
        as ``pose`` (nothing before the filter has an estimate or while nobody reads it)."""
        correction = self.amcl.map_to_odom
        if correction is None or not self._wanted("pose"):
            return []
        here = (msg.pose.position.x, msg.pose.position.y, msg.pose.yaw)
        pose = compose((float(correction[0]), float(correction[1]), float(correction[2])), *here)
        return [("pose", convert.map_pose(pose, msg.header.stamp, self._frame))]

    # -- scans ---------------------------------------------------------------
    def on_scan(self, scan: LaserScan) -> list[tuple[str, Msg]]:
        """One scan through the filter (:class:`ScanError` for a malformed one), then
        the correction as it stands (:meth:`correction`)."""
        job = self.scan_job(scan)
        return ([] if job is None else self.update(job)) + self.correction(scan.header.stamp)

    def correction(self, stamp: float) -> list[tuple[str, Msg]]:
        """``map`` -> ``odom`` on ``tf``, stamped ``stamp`` (the scan's), once the filter
        has one and ``tf_broadcast``: sent with every scan taken, updated or not, as
        AMCL republishes the last transform "to keep everybody happy", so a reader
        composing its own pose from odometry (:mod:`aiobt.robot.correction`) has it
        within a scan of listening, and knows localization is alive."""
        transform = self.amcl.map_to_odom
        if transform is None or not self.params.tf_broadcast:
            return []
        xyyaw = (float(transform[0]), float(transform[1]), float(transform[2]))
        return [("tf", correction_message(xyyaw, stamp, self._frame, self.params.odom_frame_id))]

    def scan_job(self, scan: LaserScan) -> ScanJob | None:
        """What the filter needs of ``scan``: its beams and the odometry at its stamp
        (None if the filter cannot use it yet). Reads the odometry: call it where
        :meth:`on_odom` runs."""
        self.take_odometry()
        self.stats.scans += 1
        if not (self.has_map and self.amcl.initialized):
            return None
        check_scan_shape(len(scan.ranges), scan.angle_min, scan.angle_max, scan.angle_increment)
        odom_pose = self.odom.at(scan.header.stamp, tolerance=self.params.transform_tolerance)
        if odom_pose is None:
            self.stats.skipped_no_odom += 1
            return None
        with self.lock:
            if not self.amcl.takes_scan_at(odom_pose):  # standing still: nothing to weigh
                self.stats.skipped_still += 1
                return None
        low, high = effective_range_limits(
            scan.range_min, scan.range_max, self.params.laser_min_range, self.params.laser_max_range
        )
        beams = select_beams(
            scan.ranges_array(), scan.angles_array(),
            max_beams=self.params.max_beams, range_min=low, range_max=high,
            laser_model_type=self.params.laser_model_type,
        )  # fmt: skip
        return ScanJob(scan.header.stamp, odom_pose, beams)

    def update(self, job: ScanJob) -> list[tuple[str, Msg]]:
        """The filter's update from one scan; safe on another thread than :meth:`on_odom`
        (the service runs it on one, so the pose stream goes on meanwhile)."""
        with self.lock:
            if job.stamp < self._reset_at:
                self.stats.skipped_before_reset += 1
                return []
            start = time.thread_time()
            outcome = self.amcl.on_scan(job.odom_pose, job.beams)
            if outcome.updated:
                self.stats.record(time.thread_time() - start)
            return self._outputs(outcome.estimate is not None, job.stamp, outcome.updated)

    def _outputs(self, estimated: bool, stamp: float, updated: bool) -> list[tuple[str, Msg]]:
        out: list[tuple[str, Msg]] = []
        amcl, frame = self.amcl, self._frame
        if estimated and amcl.last_estimate is not None and amcl.map_to_odom is not None:
            out.append(("amcl_pose", convert.amcl_pose(amcl.last_estimate, stamp, frame)))
        if updated and self._wanted("particle_cloud"):
            cloud = convert.particle_cloud(amcl.particles, amcl.weights, stamp, frame)
            out.append(("particle_cloud", cloud))
        return out

    # -- initial pose and services ------------------------------------------
    def on_initialpose(self, msg: PoseWithCovarianceStamped) -> Reply:
        """``initialpose``: refused (and nothing changed) unless in ``map``, finite, on
        the map, off the walls, with a positive-definite covariance."""
        frame = msg.header.frame_id
        if frame not in (self._frame, ""):
            return Reply(
                False, f"initialpose: header.frame_id must be {self._frame!r}, got {frame!r}"
            )
        try:
            cov = covariance_from_6x6(msg.pose.covariance)
        except InitialPoseError as exc:
            return Reply(False, f"initialpose: {exc}")
        return self.initial_pose(msg.x, msg.y, msg.yaw, cov, "initialpose")

    def initial_pose(
        self, x: float, y: float, yaw: float, cov: np.ndarray | None, where: str
    ) -> Reply:
        if not self.has_map:
            return Reply(False, f"{where}: no map yet; the pose needs the map to be checked")
        try:
            pose = self.amcl.check_pose(x, y, yaw, cov, where)
        except InitialPoseError as exc:
            return Reply(False, str(exc))
        with self.lock:
            self.amcl.initialize(pose)
            self._mark_reset()
        log.info("%s: pose set to (%.3f, %.3f, %.3f)", where, x, y, yaw)
        return Reply(True, f"pose set to ({x:.3f}, {y:.3f}, {yaw:.3f})")

    def reinitialize_global_localization(self) -> Reply:
        if not self.has_map:
            return Reply(
                False, "no map yet: global localization spreads particles over its free space"
            )
        with self.lock:
            self.amcl.global_localization()
            self._mark_reset()
        log.info("global localization: %d particles over the free space", len(self.amcl.particles))
        return Reply(True, "particles spread over the free space")

    def _mark_reset(self) -> None:
        self.take_odometry()
        newest = self.odom.newest
        self._reset_at = -math.inf if newest is None else newest[0]

    def request_nomotion_update(self) -> Reply:
        if not self.amcl.initialized:
            return Reply(False, "no pose yet: set initialpose or reinitialize global localization")
        with self.lock:
            self.amcl.request_nomotion_update()
        return Reply(True, "the next scan updates the filter")


__all__ = ["LocalizationNode", "Reply", "ScanError"]
