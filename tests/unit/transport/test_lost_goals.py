"""LostGoals: the goals a client gave up for lost are canceled once each when their
server is back, retried while its cancel queryable is not routed yet."""

from __future__ import annotations

import logging

import pytest

from aiobt.transport.actions import lost
from aiobt.transport.actions.lost import LostGoals
from aiobt.transport.services import ServiceError

pytestmark = pytest.mark.timeout(10)


class FakeServer:
    def __init__(self, unanswered: int = 0, running: tuple[str, ...] = ()) -> None:
        self.unanswered = unanswered  # cancel requests that get no answer first
        self.running = set(running)
        self.requests: list[str] = []

    async def cancel(self, goal_id: str, timeout: float) -> list[str]:  # noqa: ASYNC109
        self.requests.append(goal_id)
        if self.unanswered:
            self.unanswered -= 1
            raise ServiceError(f"cancel: no service answered ({timeout} s)")
        if goal_id in self.running:
            self.running.discard(goal_id)
            return [goal_id]
        return []


async def test_each_lost_goal_is_canceled_once_when_the_server_is_back(
    caplog: pytest.LogCaptureFixture,
) -> None:
    server = FakeServer(running=("a",))
    goals = LostGoals("robot/action/follow_path", server.cancel)
    goals.add("a")
    goals.add("b")
    goals.server_back()
    goals.server_back()  # a second return of the token: nothing left to cancel
    await goals.settled()
    assert server.requests == ["a", "b"]
    warned = [r.getMessage() for r in caplog.records if r.levelno == logging.WARNING]
    assert warned == [
        "action robot/action/follow_path: goal a, lost while the server was out of reach, "
        "was still running there: canceled it"
    ]


async def test_an_unanswered_cancel_is_retried_then_reported(
    monkeypatch: pytest.MonkeyPatch, caplog: pytest.LogCaptureFixture
) -> None:
    monkeypatch.setattr(lost, "RETRY_PAUSE", 0.0)
    server = FakeServer(unanswered=lost.ATTEMPTS)
    goals = LostGoals("robot/action/spin", server.cancel)
    goals.add("c")
    goals.server_back()
    await goals.settled()
    assert server.requests == ["c"] * lost.ATTEMPTS
    assert "could not cancel goal c" in caplog.text


async def test_nothing_lost_nothing_sent() -> None:
    server = FakeServer()
    goals = LostGoals("robot/action/spin", server.cancel)
    goals.server_back()
    await goals.settled()
    assert server.requests == []
