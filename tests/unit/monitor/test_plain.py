"""``aiobt monitor --plain``: the changes a person reads, not every transition."""

from __future__ import annotations

from aiobt.monitor.plain import PlainLog
from aiobt.msgs.bt import BtNode, BtSnapshot, BtTree

PIPE = BtNode(uid=1, parent=None, path="T/Pipe", id="PipelineSequence", name="Pipe", kind="Control")
PLAN = BtNode(
    uid=2, parent=1, path="T/Pipe/Plan", id="ComputePathToPose", name="ComputePathToPose",
    kind="Action",
)  # fmt: skip
CLEAR = BtNode(
    uid=3, parent=1, path="T/Pipe/Clear", id="ClearEntireCostmap", name="ClearGlobal", kind="Action"
)
TREE = BtTree(run=1, tree_id="T", nodes=[PIPE, PLAN, CLEAR], source="nav.xml")


def shot(stamp: float, state: str = "navigating", recoveries: int = 0, **kw: object) -> BtSnapshot:
    return BtSnapshot.model_validate(
        {"run": 1, "stamp": stamp, "state": state, "goal_id": "g1", "action": "navigate_to_pose",
         "number_of_recoveries": recoveries, "nodes": [], **kw}
    )  # fmt: skip


def test_replanning_that_succeeds_again_says_nothing_new() -> None:
    log = PlainLog()
    assert log.on_tree(TREE)[0] == "tree T (run 1, 3 nodes) from nav.xml"
    assert log.on_snapshot(shot(100.0)) == ["    0.0 s  navigating: navigate_to_pose goal g1"]
    lines = [
        log.on_transition(node, status, stamp)
        for node, status, stamp in [
            (PIPE, "RUNNING", 100.0),  # a control node: its children tell
            (PLAN, "RUNNING", 100.0),
            (PLAN, "SUCCESS", 100.2),
            (PLAN, "IDLE", 100.2),  # reset
            (PLAN, "RUNNING", 101.0),  # the replanning a second later
            (PLAN, "SUCCESS", 101.1),
            (PLAN, "RUNNING", 102.0),
            (PLAN, "FAILURE", 102.1),  # now it fails: worth a line
            (PLAN, "RUNNING", 103.0),  # and trying again after a failure too
            (CLEAR, "SUCCESS", 103.0),
        ]
    ]
    assert [line for line in lines if line is not None] == [
        "    0.0 s  RUNNING  ComputePathToPose",
        "    0.2 s  SUCCESS  ComputePathToPose",
        "    2.1 s  FAILURE  ComputePathToPose",
        "    3.0 s  RUNNING  ComputePathToPose",
        "    3.0 s  SUCCESS  ClearEntireCostmap [ClearGlobal]",
    ]


def test_recoveries_and_the_end_each_get_a_line() -> None:
    log = PlainLog()
    log.on_tree(TREE)
    log.on_snapshot(shot(10.0))
    assert log.on_snapshot(shot(12.0, recoveries=1)) == ["    2.0 s  recovery 1"]
    assert log.on_snapshot(shot(12.5, recoveries=1)) == []
    end = shot(20.0, state="aborted", error_code=104, error_msg="no progress")
    assert log.on_snapshot(end) == ["   10.0 s  navigation aborted: error 104 no progress"]
    assert log.on_snapshot(end) == []


def test_a_navigation_that_ended_before_the_monitor_came_is_said_without_a_time() -> None:
    log = PlainLog()
    log.on_tree(TREE)
    assert log.on_snapshot(shot(50.0, state="succeeded")) == ["the last navigation succeeded"]
