"""A closed loop without Zenoh: the real simulation, the followed box and its tracker,
and the following server's logic, stepped on the simulation's own time."""

from __future__ import annotations

import math
from collections.abc import Callable, Iterator
from contextlib import contextmanager
from dataclasses import dataclass, field

from aiobt.geometry import Velocity
from aiobt.geometry.pose_filter import StampedPose
from aiobt.msgs.remote_actions import FollowObject
from aiobt_services.following.follow import FollowingServer
from aiobt_services.following.frames import RobotFrames
from aiobt_services.following.params import FollowingParams
from aiobt_services.robot.convert import laser_scan
from aiobt_services.robot.sim import Simulation
from aiobt_services.robot.target import FollowTarget

ODOM_EVERY, SCAN_EVERY = 2, 10  # steps: 50 Hz and 10 Hz at dt 0.01


@dataclass
class Record:
    """Per scan: sim time, centre distance robot-box, gap between their outlines."""

    times: list[float] = field(default_factory=list)
    distances: list[float] = field(default_factory=list)
    feedback: list[int] = field(default_factory=list)


class SteppedWorld:
    """The clock of the server's logic: sleeping steps the simulation."""

    topic = "robot/dynamic_pose"

    def __init__(self, sim: Simulation, target: FollowTarget | None, params: FollowingParams):
        self.sim, self.target = sim, target
        self.frames = RobotFrames(params.base_frame, params.transform_tolerance)
        self.detection: StampedPose | None = None
        self.record = Record()
        self.events: list[tuple[float, Callable[[], None]]] = []  # (sim time, what), in order
        self.server = FollowingServer(params, self.frames, self, self.open, self.command)
        self._feed()

    def now(self) -> float:
        return self.sim.time

    async def sleep(self, seconds: float) -> None:
        for _ in range(max(1, round(seconds / self.sim.config.dt))):
            self.sim.step()
            self._feed()

    def at(self, time: float, event: Callable[[], None]) -> None:
        self.events.append((time, event))
        self.events.sort(key=lambda e: e[0])

    def _feed(self) -> None:
        sim = self.sim
        while self.events and self.events[0][0] <= sim.time:
            self.events.pop(0)[1]()
        if sim.steps % ODOM_EVERY == 0:
            self.frames.add("odom", sim.time, sim.odometry.pose)
            self.frames.add_turn_rate(sim.odometry.angular)
        if sim.steps % SCAN_EVERY == 0 and self.target is not None:
            seen = self.target.detect(laser_scan(sim.scan()))
            if seen is not None:
                self.detection = StampedPose(seen, sim.time, "base_link")
            robot, box = sim.true_pose, self.target.pose
            self.record.times.append(sim.time)
            self.record.distances.append(math.hypot(box.x - robot.x, box.y - robot.y))

    def latest(self) -> StampedPose | None:
        return self.detection

    @contextmanager
    def open(self, topic: str) -> Iterator[SteppedWorld]:
        yield self

    def command(self, cmd: Velocity) -> None:
        self.sim.command(cmd.v, cmd.w)

    def publish_feedback(self, feedback: FollowObject.Feedback) -> None:
        self.record.feedback.append(feedback.state)
