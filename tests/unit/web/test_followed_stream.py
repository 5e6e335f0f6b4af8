"""The followed object as the page gets it: the following server's filtered pose put in
``map`` (Sources.flush, aiobt.web.followed)."""

from __future__ import annotations

import json
import math

import pytest

from aiobt.geometry import Pose2D
from aiobt.msgs import Odometry, Pose, PoseStamped
from aiobt.transport import Bus
from aiobt.web.coalesce import Hub
from aiobt.web.followed import followed_in_map
from aiobt.web.sources import Sources

ROBOT = PoseStamped.from_xy_yaw(10.0, 5.0, math.pi / 2, "map", 3.0)  # in map
ODOM = Odometry(pose=Pose.from_xy_yaw(1.0, 0.0, 0.0))  # map = odom turned by pi/2, moved


def test_each_frame_is_put_in_map() -> None:
    ahead = PoseStamped.from_xy_yaw(2.0, 0.0, 0.0, "base_link")
    assert followed_in_map(ahead, ROBOT, None) == pytest.approx(Pose2D(10.0, 7.0, math.pi / 2))
    in_odom = PoseStamped.from_xy_yaw(3.0, 0.0, 0.0, "odom")  # 2 m ahead of the robot in odom
    where = followed_in_map(in_odom, ROBOT, ODOM)
    assert where is not None
    assert (where.x, where.y) == pytest.approx((10.0, 7.0))
    in_map = PoseStamped.from_xy_yaw(4.0, 4.0, 0.0, "map")
    assert followed_in_map(in_map, None, None) == Pose2D(4.0, 4.0, 0.0)
    assert followed_in_map(in_odom, ROBOT, None) is None
    assert followed_in_map(ahead, None, None) is None


async def test_the_filtered_pose_is_drawn_in_map(local_bus: Bus) -> None:
    hub = Hub()
    sources = Sources(local_bus, hub)
    sources.raw.set("pose", ROBOT)
    sources.flush()
    sources.raw.set("filtered_dynamic_pose", PoseStamped.from_xy_yaw(1.5, 0.0, 0.0, "base_link",
                                                                     3.1))  # fmt: skip
    sources.flush()
    assert json.loads(hub.latest["followed"]) == {"x": 10.0, "y": 6.5, "stamp": 3.1}
    sources.close()
