"""``--realtime-priority`` (Nav2's ``use_realtime_priority``): the option on the robot,
controller and planner, the call it makes, and the error when it is not permitted."""

from __future__ import annotations

import argparse
import logging
import os
from collections.abc import Callable

import pytest

from aiobt.system.realtime import RealtimePriorityError, raise_priority, realtime_if_asked
from aiobt.system.service import run_service
from aiobt_services.controller.main import add_arguments as controller_arguments
from aiobt_services.navigator.main import add_arguments as navigator_arguments
from aiobt_services.planner.main import add_arguments as planner_arguments
from aiobt_services.robot.main import add_arguments as robot_arguments

SERVICES: list[tuple[Callable[[argparse.ArgumentParser], None], int]] = [
    (robot_arguments, 90),
    (controller_arguments, 90),  # Nav2's
    (planner_arguments, 70),  # below the control loop and the simulation
    (navigator_arguments, 60),  # below the planner: it asks for the plans
]


def _parse(add: Callable[[argparse.ArgumentParser], None], argv: list[str]) -> argparse.Namespace:
    parser = argparse.ArgumentParser()
    add(parser)
    return parser.parse_args(argv)


@pytest.mark.parametrize(("add", "default"), SERVICES)
def test_off_unless_given_alone_the_services_default_or_the_value_given(add, default):
    assert _parse(add, []).realtime_priority is None
    assert _parse(add, ["--realtime-priority"]).realtime_priority == default
    assert _parse(add, ["--realtime-priority", "42"]).realtime_priority == 42


@pytest.mark.parametrize(("add", "default"), SERVICES)
@pytest.mark.parametrize("bad", ["0", "100", "-5", "high", "9.5"])
def test_a_priority_outside_1_to_99_is_refused_naming_the_flag(add, default, bad, capsys):
    with pytest.raises(SystemExit):
        _parse(add, ["--realtime-priority", bad])
    err = capsys.readouterr().err
    assert "--realtime-priority" in err
    assert "1..99" in err


def test_raise_priority_sets_sched_fifo_on_the_calling_thread(monkeypatch):
    calls: list[tuple[int, int, int]] = []
    monkeypatch.setattr(
        os,
        "sched_setscheduler",
        lambda pid, policy, param: calls.append((pid, policy, param.sched_priority)),
    )
    assert realtime_if_asked(None) == ""
    assert calls == []  # not asked: the policy is left alone
    assert realtime_if_asked(77) == ", real-time priority 77 (SCHED_FIFO)"
    assert calls == [(0, os.SCHED_FIFO, 77)]  # pid 0: this thread only, not the process


def test_not_permitted_names_the_option_and_the_fix(monkeypatch):
    def refuse(*_: object) -> None:
        raise PermissionError(1, "Operation not permitted")

    monkeypatch.setattr(os, "sched_setscheduler", refuse)
    with pytest.raises(RealtimePriorityError) as caught:
        raise_priority(90)
    message = str(caught.value)
    assert message.startswith("--realtime-priority 90: not permitted")
    assert "CAP_SYS_NICE" in message
    assert "rtprio 99" in message  # limits.conf
    assert "cap_add: [SYS_NICE]" in message  # docker-compose


def test_without_sched_fifo_the_error_says_linux_only(monkeypatch):
    monkeypatch.delattr(os, "sched_setscheduler")
    with pytest.raises(RealtimePriorityError, match="not available on this system"):
        raise_priority(90)


def test_the_service_exits_1_with_the_error_logged(monkeypatch, caplog):
    async def refused() -> None:
        raise RealtimePriorityError("--realtime-priority 90: not permitted to use SCHED_FIFO")

    with caplog.at_level(logging.ERROR):
        assert run_service(refused(), logging.getLogger("aiobt_services.test"), "robot") == 1
    assert "robot: --realtime-priority 90: not permitted" in caplog.text


def test_the_robot_refuses_it_at_speed_max_where_it_would_never_sleep(monkeypatch, caplog):
    from aiobt_services.robot import main as robot_main

    raised: list[int] = []
    monkeypatch.setattr(os, "sched_setscheduler", lambda *a: raised.append(1))
    args = _parse(robot_arguments, ["--speed", "max", "--realtime-priority"])
    with caplog.at_level(logging.ERROR):
        assert robot_main.run(args) == 2
    assert "--realtime-priority with --speed max" in caplog.text
    assert raised == []  # refused before anything was raised or started
