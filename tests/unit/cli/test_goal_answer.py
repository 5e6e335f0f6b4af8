"""``aiobt goal``: which goal the navigator started after the put, and what became of it."""

from __future__ import annotations

from aiobt.cli.goal_answer import GoalAnswer
from aiobt.msgs import BtSnapshot, GoalState, GoalStatus


def status(goal_id: str, state: GoalState, reason: str = "") -> GoalStatus:
    return GoalStatus(goal_id=goal_id, status=state, reason=reason)


def snapshot(goal_id: str, ticks: int) -> BtSnapshot:
    return BtSnapshot(run=1, state="navigating", goal_id=goal_id, ticks=ticks, nodes=[])


def test_a_refused_goal_gives_the_navigators_reason() -> None:
    answer = GoalAnswer()
    answer.expect()
    answer.on_status(status("ours", GoalState.ACCEPTED))
    answer.on_status(status("ours", GoalState.EXECUTING))
    assert answer.verdict() is None
    answer.on_status(status("ours", GoalState.ABORTED, "the goal pose (40, 40) is outside the map"))
    verdict = answer.verdict()
    assert verdict is not None
    assert not verdict.running
    assert verdict.state is GoalState.ABORTED
    assert "outside the map" in verdict.reason


def test_a_goal_is_running_once_its_tree_has_ticked() -> None:
    answer = GoalAnswer()
    answer.expect()
    answer.on_status(status("ours", GoalState.ACCEPTED))
    answer.on_snapshot(snapshot("ours", ticks=0))  # started, not yet checked and ticked
    assert answer.verdict() is None
    answer.on_snapshot(snapshot("ours", ticks=3))
    verdict = answer.verdict()
    assert verdict is not None
    assert verdict.running


def test_the_goal_it_preempts_and_goals_before_the_put_are_not_taken_for_it() -> None:
    answer = GoalAnswer()
    answer.on_status(status("before", GoalState.ACCEPTED))  # before expect(): not ours
    answer.expect()
    answer.on_status(status("before", GoalState.ABORTED, "preempted by goal ours"))
    answer.on_snapshot(snapshot("before", ticks=50))
    assert answer.verdict() is None
    answer.on_status(status("ours", GoalState.ACCEPTED))
    assert answer.goal_id == "ours"
    assert answer.verdict() is None
