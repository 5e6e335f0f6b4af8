"""TreeView: the monitor's model of the navigator's tree, and how it fits a screen."""

from __future__ import annotations

from aiobt.cli.status import parse_token
from aiobt.monitor import TreeView
from aiobt.msgs.bt import BtNode, BtNodeStatus, BtSnapshot, BtTransition, BtTransitions, BtTree


def _tree(run: int = 1, leaves: int = 3) -> BtTree:
    nodes = [
        BtNode(uid=1, parent=None, path="T/Seq", id="Sequence", name="Sequence", kind="Control")
    ]
    nodes += [
        BtNode(uid=k + 2, parent=1, path=f"T/Seq/L{k}", id="Wait", name=f"L{k}", kind="Action")
        for k in range(leaves)
    ]
    return BtTree(run=run, tree_id="T", nodes=nodes)


def _changes(run: int, *pairs: tuple[int, str]) -> BtTransitions:
    moves = [BtTransition(uid=uid, previous="IDLE", status=status) for uid, status in pairs]
    return BtTransitions(run=run, transitions=moves)


def test_transitions_and_snapshots_of_the_current_run_update_statuses() -> None:
    view = TreeView()
    view.on_tree(_tree())
    applied = view.on_transitions(_changes(1, (1, "RUNNING"), (2, "SUCCESS")))
    assert [(node.name, status) for node, status in applied] == [
        ("Sequence", "RUNNING"), ("L0", "SUCCESS"),
    ]  # fmt: skip
    running = [BtNodeStatus(uid=3, status="RUNNING")]
    shot = BtSnapshot(run=1, nodes=running, state="navigating", distance_remaining=2.5)
    view.on_snapshot(shot.model_copy(update={"number_of_recoveries": 1}))
    lines = view.render()
    assert "navigating" in lines[0]
    assert "recoveries 1  distance 2.50 m" in lines[0]
    assert lines[1:] == [
        "RUNNING  Sequence",
        "SUCCESS    Wait [L0]",
        "RUNNING    Wait [L1]",
        "IDLE       Wait [L2]",
    ]


def test_messages_of_another_run_are_dropped() -> None:
    view = TreeView()
    assert view.on_transitions(_changes(1, (1, "RUNNING"))) == []  # no structure yet
    view.on_tree(_tree(run=2))
    assert view.on_transitions(_changes(1, (1, "RUNNING"))) == []
    view.on_snapshot(BtSnapshot(run=1, nodes=[BtNodeStatus(uid=1, status="FAILURE")]))
    assert view.status[1] == "IDLE"
    assert view.snapshot is None


def test_a_tree_taller_than_the_screen_shows_its_active_branch_then_cuts() -> None:
    view = TreeView()
    view.on_tree(_tree(leaves=30))
    view.on_transitions(_changes(1, (1, "RUNNING"), (20, "RUNNING")))
    lines = view.render(height=6)
    assert lines[1:] == ["RUNNING  Sequence", "RUNNING    Wait [L18]"]
    view.on_transitions(_changes(1, *((uid, "SUCCESS") for uid in range(2, 20))))
    lines = view.render(height=6)
    assert len(lines) == 6
    assert lines[-1] == "... 27 more nodes (a taller terminal shows them)"


def test_waiting_for_the_tree_says_so() -> None:
    assert TreeView().render() == ["waiting for the navigator's tree (bt/tree)..."]


def test_status_reads_namespace_and_service_from_a_token() -> None:
    assert parse_token("fleet/r1/nodes/planner") == ("fleet/r1", "planner")
    assert parse_token("robot/nodes/a/b") is None
    assert parse_token("nodes/planner") is None
