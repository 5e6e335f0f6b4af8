"""The docking server's docks as a Foxglove scene: an arrow per dock and staging pose."""

from __future__ import annotations

import math

import pytest

from aiobt.foxglove import convert
from aiobt.msgs import PoseStamped
from aiobt.msgs.docking import DockEntry, DockList

from .test_convert import decoded


def test_an_arrow_per_dock_and_staging_pose_in_map() -> None:
    dock = DockEntry(name="home_dock", pose=PoseStamped.from_xy_yaw(0.5, 9.75, math.pi),
                     staging=PoseStamped.from_xy_yaw(1.5, 9.75, math.pi))  # fmt: skip
    [entity] = decoded(convert.docks(DockList(docks=[dock]), 2.0)).entities
    assert entity.frame_id == "map"
    docked, staging = entity.arrows
    assert (docked.pose.position.x, staging.pose.position.x) == pytest.approx((0.5, 1.5))
    assert abs(docked.pose.orientation.z) == pytest.approx(1.0)  # pointing -x, into the dock
    assert not decoded(convert.docks(DockList(), 0.0)).entities[0].arrows
