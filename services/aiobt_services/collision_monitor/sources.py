"""Observation sources: the newest data of each, as obstacle points in the base frame
now, or why there are none (missing, older than ``source_timeout``).

The robot's lidar sits at its centre, so a scan's frame is the base frame at the
scan's stamp. ``base_shift_correction`` (Nav2's): the points are moved from where the
base was at the data's stamp to where it is now, by odometry (interpolated at the
stamp; the newest odometry for now).
"""

from __future__ import annotations

import bisect
import math
from dataclasses import dataclass

import numpy as np

from aiobt.msgs import LaserScan
from aiobt.msgs.safety import PointCloud

from .params import SourceParams
from .shapes import Points

ODOM_HISTORY = 2.0  # s of odometry kept for base_shift_correction


def scan_points(scan: LaserScan) -> Points:
    """The returns of ``scan`` (ranges within [range_min, range_max]) as x, y."""
    ranges, angles = scan.ranges_array(), scan.angles_array()
    hit = (ranges >= scan.range_min) & (ranges <= scan.range_max)
    r, a = ranges[hit], angles[hit]
    return np.column_stack((r * np.cos(a), r * np.sin(a)))


def cloud_points(cloud: PointCloud, params: SourceParams) -> Points:
    """The points of ``cloud`` within the source's height band, as x, y."""
    if not cloud.points:
        return np.zeros((0, 2))
    xyz = np.array([(p.x, p.y, p.z) for p in cloud.points], dtype=np.float64)
    keep = (xyz[:, 2] >= params.min_height) & (xyz[:, 2] <= params.max_height)
    return xyz[keep, :2]


class OdomHistory:
    """Odometry poses (x, y, yaw in ``odom``) of the last :data:`ODOM_HISTORY` seconds."""

    __slots__ = ("_poses", "_stamps")

    def __init__(self) -> None:
        self._stamps: list[float] = []
        self._poses: list[tuple[float, float, float]] = []

    def add(self, stamp: float, x: float, y: float, yaw: float) -> None:
        if self._stamps and stamp <= self._stamps[-1]:
            if stamp == self._stamps[-1]:
                return
            self._stamps.clear()  # time went back: a restarted robot
            self._poses.clear()
        self._stamps.append(stamp)
        self._poses.append((x, y, yaw))
        old = bisect.bisect_left(self._stamps, stamp - ODOM_HISTORY)
        if old:
            del self._stamps[:old], self._poses[:old]

    @property
    def empty(self) -> bool:
        return not self._stamps

    def pose_at(self, stamp: float) -> tuple[float, float, float]:
        """The pose at ``stamp``, interpolated (the nearest end outside the history)."""
        i = bisect.bisect_left(self._stamps, stamp)
        if i == 0:
            return self._poses[0]
        if i == len(self._stamps):
            return self._poses[-1]
        t0, t1 = self._stamps[i - 1], self._stamps[i]
        (x0, y0, a0), (x1, y1, a1) = self._poses[i - 1], self._poses[i]
        f = (stamp - t0) / (t1 - t0)
        turn = math.remainder(a1 - a0, math.tau)
        return x0 + f * (x1 - x0), y0 + f * (y1 - y0), a0 + f * turn

    def latest(self) -> tuple[float, float, float]:
        return self._poses[-1]


def shift(
    points: Points, then: tuple[float, float, float], now: tuple[float, float, float]
) -> Points:
    """``points`` in the base frame at pose ``then``, expressed in the base frame at ``now``."""
    c0, s0 = math.cos(then[2]), math.sin(then[2])
    world = points @ np.array([[c0, s0], [-s0, c0]]) + np.array(then[:2])
    c1, s1 = math.cos(now[2]), math.sin(now[2])
    return np.asarray((world - np.array(now[:2])) @ np.array([[c1, -s1], [s1, c1]]))


@dataclass(slots=True)
class Reading:
    points: Points
    stamp: float  # the data's own stamp (robot time)
    arrival: float  # when it arrived, on the monitor's clock


class Source:
    """One observation source's newest reading and its validity."""

    __slots__ = ("params", "reading")

    def __init__(self, params: SourceParams) -> None:
        self.params = params
        self.reading: Reading | None = None

    def take(self, points: Points, stamp: float, arrival: float) -> None:
        self.reading = Reading(points, stamp, arrival)

    def stale_at(self, robot_time: bool) -> float:
        """When the newest reading goes stale (inf: none yet, or no timeout)."""
        reading, timeout = self.reading, self.params.source_timeout
        if reading is None or timeout == 0.0:
            return math.inf
        return (reading.stamp if robot_time else reading.arrival) + timeout

    def points(self, now: float, robot_time: bool, odom: OdomHistory | None) -> Points | str:
        """The points in the base frame now, or why the source is invalid."""
        reading, name, timeout = self.reading, self.params.name, self.params.source_timeout
        if reading is None:
            return f"source '{name}' has sent nothing on '{self.params.topic}'"
        age = now - (reading.stamp if robot_time else reading.arrival)
        if timeout != 0.0 and age > timeout:
            return f"source '{name}' is {age:.2f} s old (source_timeout {timeout:g} s)"
        if timeout != 0.0 and -age > timeout:  # robot time (odometry's stamps) stands still
            return f"source '{name}' is {-age:.2f} s ahead of the robot's time: odometry stale?"
        if odom is None:
            return reading.points
        if odom.empty:
            return f"source '{name}': no odometry yet for base_shift_correction"
        return shift(reading.points, odom.pose_at(reading.stamp), odom.latest())
