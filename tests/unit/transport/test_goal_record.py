"""The server side of one goal's reply stream: what is sent, in which order (no Zenoh)."""

from __future__ import annotations

from typing import Any

from aiobt.msgs import GoalState
from aiobt.transport.actions import protocol as p
from aiobt.transport.actions.goals import GoalRecord, WaitingGoals


class FakeQuery:
    """Records replies and the drop, as a zenoh.Query would send them."""

    key_expr = "robot/action/wait/goal"

    def __init__(self) -> None:
        self.sent: list[tuple[bytes, bytes]] = []  # (attachment, payload)
        self.dropped = 0

    def reply(self, key_expr: str, payload: bytes, **kwargs: Any) -> None:
        assert not self.dropped, "reply after the stream ended"
        self.sent.append((kwargs.get("attachment", b""), payload))

    def drop(self) -> None:
        self.dropped += 1


def record(goal_id: str = "g1") -> tuple[GoalRecord, FakeQuery]:
    query = FakeQuery()
    return GoalRecord(goal_id, query), query  # type: ignore[arg-type]


RESULT = p.result_tag(GoalState.SUCCEEDED)


def test_a_goal_finished_before_its_acknowledgement_sends_the_result_alone() -> None:
    goal, query = record()
    goal.finish(RESULT, b'{"error_code": 0}')
    goal.acknowledge()  # the deferred acknowledgement comes too late: nothing more is sent
    assert query.sent == [(RESULT, b'{"error_code": 0}')]
    assert query.dropped == 1


def test_a_running_goal_is_acknowledged_once_then_streams_feedback_and_result() -> None:
    goal, query = record()
    goal.acknowledge()
    goal.acknowledge()
    goal.reply(b'{"time_left": 1.0}', p.FEEDBACK)
    goal.finish(RESULT, b"{}")
    goal.reply(b'{"time_left": 0.5}', p.FEEDBACK)  # late feedback after the end: dropped
    goal.finish(RESULT, b"{}")
    assert [tag for tag, _ in query.sent] == [p.ACCEPTED, p.FEEDBACK, RESULT]
    assert query.dropped == 1


def test_feedback_before_the_acknowledgement_sends_accepted_first() -> None:
    goal, query = record()
    goal.reply(b'{"time_left": 1.0}', p.FEEDBACK)
    assert [tag for tag, _ in query.sent] == [p.ACCEPTED, p.FEEDBACK]


def test_result_queries_waiting_on_the_goal_get_the_result_and_end() -> None:
    goal, _query = record()
    waiter = FakeQuery()
    goal.waiters.append(waiter)  # type: ignore[arg-type]
    goal.finish(RESULT, b'{"error_code": 0}')
    assert waiter.sent == [(RESULT, b'{"error_code": 0}')]
    assert waiter.dropped == 1
    assert goal.waiters == []


def test_result_tags_round_trip() -> None:
    for state in GoalState:
        assert p.parse_result_tag(p.result_tag(state)) is state
    assert p.parse_result_tag(p.ACCEPTED) is None
    assert p.parse_result_tag(b"result:banana") is None


def test_waiting_goals_are_taken_by_id_or_all_in_order() -> None:
    waiting = WaitingGoals()
    first, second, third = (record(goal_id)[0] for goal_id in ("a", "b", "c"))
    for goal in (first, second, third):
        waiting.add(goal)
    assert waiting.take("b") == [second]
    assert waiting.take("b") == []  # canceled once: a second cancel names nothing
    assert waiting.get("b") is None
    assert waiting.take("unknown") == []
    assert waiting.get("c") is third
    assert waiting.take("") == [first, third]
    assert waiting.take("") == []


def test_a_goal_leaving_the_queue_removes_only_itself() -> None:
    waiting = WaitingGoals()
    goal, _ = record("a")
    again, _ = record("a")  # another record under the same id (not the waiting one)
    waiting.add(goal)
    waiting.discard(again)
    assert waiting.get("a") is goal
    waiting.discard(goal)
    waiting.discard(goal)
    assert waiting.take("") == []


def test_a_rejected_goal_gets_the_reason_alone_and_nothing_after() -> None:
    goal, query = record()
    goal.reject("action server shutting down")
    goal.acknowledge()
    goal.finish(RESULT, b"{}")
    assert query.sent == [(p.REJECTED, b"action server shutting down")]
    assert query.dropped == 1


def test_an_acknowledged_goal_is_not_rejected() -> None:
    goal, query = record()
    goal.acknowledge()
    goal.reject("too late")
    assert query.sent == [(p.ACCEPTED, b"")]
    assert query.dropped == 0
