"""The docking server's docks in the web view's payload."""

from __future__ import annotations

import math

from aiobt.msgs import PoseStamped
from aiobt.msgs.docking import DockEntry, DockList
from aiobt.web import convert


def test_each_dock_with_its_staging_pose() -> None:
    docks = DockList(docks=[
        DockEntry(name="home_dock", pose=PoseStamped.from_xy_yaw(0.5, 9.75, math.pi),
                  staging=PoseStamped.from_xy_yaw(1.5, 9.75, math.pi)),
        DockEntry(name="bare", pose=PoseStamped.from_xy_yaw(1.0, 1.0, 0.0)),
    ])  # fmt: skip
    home, bare = convert.docks_payload(docks)
    assert (home["name"], home["x"], home["y"]) == ("home_dock", 0.5, 9.75)
    assert home["staging"]["x"] == 1.5
    assert bare["staging"] is None
