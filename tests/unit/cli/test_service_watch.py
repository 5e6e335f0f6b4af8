"""``aiobt navigate`` tells when a service goes away and when it is back."""

from __future__ import annotations

from aiobt.cli.service_watch import ServiceNews


def test_a_service_going_and_coming_back_is_two_lines_one_already_up_none() -> None:
    lines: list[str] = []
    news = ServiceNews(lines.append)
    news.listener("controller")(True)  # up when the watch began: nothing to say
    assert lines == []
    news.listener("planner")(False)
    news.listener("planner")(True)
    assert lines == ["planner went away (aiobt up restarts a crashed service)", "planner is back"]
