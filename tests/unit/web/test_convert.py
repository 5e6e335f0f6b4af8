"""What the page is sent, from the bus's messages."""

from __future__ import annotations

import base64
import math
from typing import Any

import numpy as np
import pytest

from aiobt.costmap.grid import INSCRIBED, LETHAL
from aiobt.costmap.inflation import InflationParams
from aiobt.msgs import LaserScan, OccupancyGrid, Path, Pose, PoseStamped, Twist
from aiobt.msgs.bt import BtNode, BtNodeStatus, BtSnapshot, BtTransition, BtTransitions, BtTree
from aiobt.web import convert
from aiobt.web.tree import TreeStatus


def _cells(payload: dict[str, Any]) -> np.ndarray:
    raw = np.frombuffer(base64.b64decode(payload["cells"]), np.uint8)
    return raw.reshape(payload["height"], payload["width"])


def _grid() -> OccupancyGrid:
    cells = np.zeros((20, 30), np.int8)
    cells[10, 15] = 100
    cells[0, 0] = -1
    return OccupancyGrid.from_array(cells, 0.1, origin=Pose.from_xy_yaw(-1.0, 2.0))


def test_map_cells_keep_their_occupancy_with_255_for_unknown():
    payload = convert.map_payload(_grid())
    assert (payload["width"], payload["height"], payload["resolution"]) == (30, 20, 0.1)
    assert payload["origin"] == [-1.0, 2.0]
    cells = _cells(payload)
    assert cells[10, 15] == 100
    assert cells[0, 0] == 255
    assert cells[5, 5] == 0


def test_costmap_is_the_map_inflated_as_nav2_does():
    payload = convert.costmap_payload(_grid(), InflationParams(0.2, 0.5, 3.0))
    cells = _cells(payload)
    assert cells[10, 15] == LETHAL
    assert cells[10, 17] == INSCRIBED  # 0.2 m away: inside the inscribed radius
    assert 0 < cells[10, 19] < INSCRIBED  # 0.4 m: decaying
    assert cells[10, 25] == 0  # beyond the inflation radius


def test_scan_points_are_in_the_map_frame_seen_from_the_pose():
    scan = LaserScan(
        angle_min=0.0, angle_max=math.pi, angle_increment=math.pi / 2,
        range_min=0.1, range_max=5.0, ranges=[1.0, 2.0, 5.5],
    )  # fmt: skip
    pose = PoseStamped.from_xy_yaw(1.0, 1.0, math.pi / 2)
    points = convert.scan_points(scan, pose)
    assert points == [[1.0, 2.0], [-1.0, 1.0]]  # the third beam (past range_max) had no return


def test_rollout_drives_the_command_from_the_pose():
    pose = PoseStamped.from_xy_yaw(0.0, 0.0, 0.0)
    straight = convert.rollout(pose, Twist.model_validate({"linear": {"x": 1.0}}))
    assert straight[0] == [0.0, 0.0]
    assert straight[-1] == pytest.approx([convert.ROLLOUT_SECONDS, 0.0])
    turning = convert.rollout(
        pose, Twist.model_validate({"linear": {"x": 1.0}, "angular": {"z": 1.0}})
    )
    end = turning[-1]
    radius = 1.0  # v / w: the points stay on the circle through (0, 0) centred at (0, 1)
    assert math.hypot(end[0], end[1] - radius) == pytest.approx(radius, abs=0.01)
    still = convert.rollout(pose, Twist())
    assert all(p == [0.0, 0.0] for p in still)


def test_path_and_pose_are_rounded_to_the_millimetre():
    path = Path(
        poses=[PoseStamped.from_xy_yaw(0.12345, 1.0), PoseStamped.from_xy_yaw(2.0, 3.00049)]
    )
    assert convert.path_points(path) == [[0.123, 1.0], [2.0, 3.0]]
    assert convert.pose_payload(PoseStamped.from_xy_yaw(1.23456, 0.0, 0.5))["x"] == 1.235


def _tree(run: int) -> BtTree:
    nodes = [
        BtNode(uid=1, parent=None, path="Main/Seq", id="Sequence", name="Seq", kind="Control"),
        BtNode(uid=2, parent=1, path="Main/Seq/A", id="Wait", name="A", kind="Action"),
    ]
    return BtTree(run=run, tree_id="Main", nodes=nodes)


def test_tree_status_keeps_each_nodes_last_status_other_than_idle():
    tree = TreeStatus()
    assert tree.payload() is None
    assert tree.on_tree(_tree(1))["nodes"][1] == {
        "uid": 2, "parent": 1, "id": "Wait", "name": "A", "kind": "Action"
    }  # fmt: skip
    changes = [
        BtTransition(uid=2, previous="IDLE", status="RUNNING"),
        BtTransition(uid=2, previous="RUNNING", status="SUCCESS"),
        BtTransition(uid=2, previous="SUCCESS", status="IDLE"),
    ]
    assert tree.on_transitions(BtTransitions(run=1, transitions=changes))
    assert tree.payload() == {
        "run": 1,
        "status": {"1": "IDLE", "2": "IDLE"},
        "last": {"2": "SUCCESS"},
    }
    other_run = BtTransitions(
        run=7, transitions=[BtTransition(uid=1, previous="IDLE", status="FAILURE")]
    )
    assert not tree.on_transitions(other_run)
    snapshot = BtSnapshot(run=1, nodes=[BtNodeStatus(uid=1, status="RUNNING")])
    assert tree.on_snapshot(snapshot)
    assert tree.payload()["status"]["1"] == "RUNNING"  # type: ignore[index]
    assert not tree.on_snapshot(BtSnapshot(run=2, nodes=[]))
    tree.on_tree(_tree(2))
    assert tree.payload() == {"run": 2, "status": {"1": "IDLE", "2": "IDLE"}, "last": {}}


def test_navigation_payload_carries_state_recoveries_and_error():
    shot = BtSnapshot(
        run=3, state="aborted", number_of_recoveries=2, distance_remaining=1.23456,
        error_code=104, error_msg="no path", nodes=[],
    )  # fmt: skip
    payload = convert.navigation_payload(shot)
    assert payload["state"] == "aborted"
    assert payload["recoveries"] == 2
    assert payload["distance_remaining"] == 1.235
    assert (payload["error_code"], payload["error_msg"]) == (104, "no path")
