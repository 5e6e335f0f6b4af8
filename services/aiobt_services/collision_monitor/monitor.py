"""Nav2's collision monitor as pure logic: one command in, the command to send out.

:meth:`CollisionMonitor.process` is Nav2's ``process``: every enabled source must be
valid (else STOP, "invalid source", whether the monitor is enabled or not, as Nav2);
then, while enabled, each enabled polygon in order may make the command safer: a
``stop`` polygon with ``min_points`` inside stops, ``slowdown`` scales by
``slowdown_ratio``, ``limit`` caps at ``linear_limit``/``angular_limit`` keeping the
curvature, ``approach`` scales so that the time before a collision stays
``time_before_collision``; the safest command wins (Nav2 compares squared
magnitudes) and the first stop ends the search. :meth:`publish_due` is Nav2's
``stop_pub_timeout``: a stop is sent for that long, then nothing until motion again.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from .params import MonitorParams
from .shapes import Points
from .sources import OdomHistory, Source
from .zones import Vel, Zone

STOP: Vel = (0.0, 0.0, 0.0)
INVALID_SOURCE = "invalid source"


@dataclass(slots=True, frozen=True)
class Action:
    """What the monitor does with one command, and why."""

    action_type: str  # none, stop, slowdown, limit, approach
    polygon_name: str
    velocity: Vel
    reason: str = ""
    publish: bool = True  # False: stopped longer than stop_pub_timeout, send nothing


def _speed2(v: Vel) -> float:
    return v[0] * v[0] + v[1] * v[1] + v[2] * v[2]


def _scaled(v: Vel, ratio: float) -> Vel:
    return (v[0] * ratio, v[1] * ratio, v[2] * ratio)


class CollisionMonitor:
    """The monitor's state: sources, polygons, whether enabled, the last action."""

    __slots__ = ("_previous", "_stop_stamp", "enabled", "odom", "params", "robot_time",
                 "sources", "zones")  # fmt: skip

    def __init__(self, params: MonitorParams, robot_time: bool = False) -> None:
        self.params = params
        self.robot_time = robot_time
        self.enabled = params.enabled
        self.sources = {s.name: Source(s) for s in params.sources}
        self.zones = [Zone(z) for z in params.polygons]
        self.odom = OdomHistory() if params.base_shift_correction else None
        self._previous = Action("none", "", (-1.0, -1.0, -1.0))  # Nav2's initial action
        self._stop_stamp = -math.inf

    @property
    def last(self) -> Action:
        """The last action (no action before the first command)."""
        initial = self._previous.velocity == (-1.0, -1.0, -1.0)
        return Action("none", "", STOP) if initial else self._previous

    def stale_at(self) -> float:
        """When the first enabled source goes stale unless new data comes (inf: never)."""
        sources = (s for s in self.sources.values() if s.params.enabled)
        return min((s.stale_at(self.robot_time) for s in sources), default=math.inf)

    def toggle(self, enable: bool) -> str:
        """Nav2's ``~/toggle``: the reply's message."""
        self.enabled = enable
        for zone in self.zones:
            zone.reset()
        return f"Collision monitor toggled {'on' if enable else 'off'} successfully"

    def process(self, cmd: Vel, now: float) -> Action:
        """The action on ``cmd`` at ``now`` (the monitor's clock); its ``publish``
        says whether to send its velocity (Nav2's ``stop_pub_timeout``)."""
        points: dict[str, Points] = {}
        for name, source in self.sources.items():
            if not source.params.enabled:
                continue
            got = source.points(now, self.robot_time, self.odom)
            if isinstance(got, str):
                if source.params.source_timeout != 0.0:
                    return self._remember(Action("stop", INVALID_SOURCE, STOP, got), now)
                continue
            points[name] = got
        action = Action("none", "", cmd)
        if self.enabled:
            action = self._zones(cmd, points)
        return self._remember(action, now)

    def _remember(self, action: Action, now: float) -> Action:
        """``action`` with ``publish`` set by Nav2's ``stop_pub_timeout`` rule."""
        publish = True
        if action.velocity == STOP:
            if self._previous.velocity != STOP:
                self._stop_stamp = now  # just stopped
            elif now - self._stop_stamp > self.params.stop_pub_timeout:
                publish = False
        self._previous = Action(
            action.action_type, action.polygon_name, action.velocity, action.reason, publish
        )
        return self._previous

    def _zones(self, cmd: Vel, by_source: dict[str, Points]) -> Action:
        action = Action("none", "", cmd)
        for zone in self.zones:
            p = zone.params
            if not p.enabled or p.action_type == "none":
                continue
            zone.update(cmd)
            wanted = [by_source[n] for n in p.sources_names if n in by_source]
            points = np.concatenate(wanted) if wanted else np.zeros((0, 2))
            found = self._zone_action(zone, points, cmd, action)
            if found is not None:
                action = found
                if found.action_type == "stop":
                    break
        return action

    def _zone_action(self, zone: Zone, points: Points, cmd: Vel, best: Action) -> Action | None:
        p = zone.params
        if p.action_type == "approach":
            return self._approach(zone, points, cmd, best)
        if not zone.triggered(points):
            return None
        inside = f"{zone.count(points)} points in '{p.name}' (min_points {p.min_points})"
        if p.action_type == "stop":
            return Action("stop", p.name, STOP, f"stop: {inside}")
        if p.action_type == "slowdown":
            safe = _scaled(cmd, p.slowdown_ratio)
            why = f"slowdown to {p.slowdown_ratio:g} of the command: {inside}"
        else:
            safe = _scaled(cmd, self._limit_ratio(cmd, p.linear_limit, p.angular_limit))
            why = f"limit to {p.linear_limit:g} m/s, {p.angular_limit:g} rad/s: {inside}"
        return (
            Action(p.action_type, p.name, safe, why)
            if _speed2(safe) < _speed2(best.velocity)
            else None
        )

    @staticmethod
    def _limit_ratio(cmd: Vel, linear_limit: float, angular_limit: float) -> float:
        ratio, linear = 1.0, math.hypot(cmd[0], cmd[1])
        if linear != 0.0:
            ratio = min(ratio, linear_limit / linear)
        if cmd[2] != 0.0:
            ratio = min(ratio, angular_limit / abs(cmd[2]))
        return min(1.0, max(0.0, ratio))

    def _approach(self, zone: Zone, points: Points, cmd: Vel, best: Action) -> Action | None:
        p = zone.params
        time = zone.collision_time(points, cmd)
        if time < 0.0:
            return None
        ratio = time / p.time_before_collision
        safe = _scaled(cmd, ratio)
        if _speed2(safe) >= _speed2(best.velocity):
            return None
        why = (f"approach: collision in {time:.2f} s within '{p.name}' "
               f"(time_before_collision {p.time_before_collision:g} s): x{ratio:.2f}")  # fmt: skip
        return Action("approach", p.name, safe, why)
