"""The robot's poses read from the kept messages when the server looks (PoseFeed)."""

from __future__ import annotations

from collections.abc import Iterator

from aiobt.geometry import Pose2D
from aiobt.msgs import Header, Odometry, Pose, Twist
from aiobt.msgs.geometry import Vector3
from aiobt_services.following.frames import RobotFrames
from aiobt_services.following.service import PoseFeed, odom_reading


class Kept:
    def __init__(self) -> None:
        self.messages: list[Odometry] = []

    def put(self, stamp: float, x: float) -> None:
        twist = Twist(angular=Vector3(z=0.5 * x))
        pose = Pose.from_xy_yaw(x, 0.0, 0.0)
        self.messages.append(Odometry(header=Header(stamp=stamp, frame_id="odom"), pose=pose,
                                      twist=twist))  # fmt: skip

    def newest_first(self) -> Iterator[Odometry]:
        return reversed(self.messages)


def test_each_look_up_reads_the_poses_that_came_meanwhile() -> None:
    kept = Kept()
    frames = RobotFrames("base_link", 0.1)
    feed = PoseFeed(kept, frames, odom_reading)
    frames.refresh = feed.refresh
    kept.put(1.0, 1.0)
    kept.put(1.02, 2.0)
    assert frames.robot_in("odom", 1.0) == Pose2D(1.0, 0.0, 0.0)
    kept.put(1.04, 3.0)
    assert frames.robot_in("odom") == Pose2D(3.0, 0.0, 0.0)
    assert frames.turn_rate == 1.5
    assert frames.robot_in("odom", 1.02) == Pose2D(2.0, 0.0, 0.0)
    kept.put(0.02, 9.0)  # the simulation restarted: its time anew
    assert frames.robot_in("odom") == Pose2D(9.0, 0.0, 0.0)
    assert frames.robot_in("odom", 0.0) == Pose2D(9.0, 0.0, 0.0)
