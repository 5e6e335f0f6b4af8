"""Command-line options of the controller and behavior services, and the shared run helpers."""

from __future__ import annotations

import argparse
import asyncio
import logging

import pytest

from aiobt.system.service import module_main, run_service, unless_stopped
from aiobt.transport import BusUnavailable
from aiobt_services.behaviors.main import add_arguments as add_behavior_arguments
from aiobt_services.controller.main import add_arguments, config_from, costmap_from


def _parser(add) -> argparse.ArgumentParser:
    parser = argparse.ArgumentParser()
    add(parser)
    return parser


def test_options_configure_rate_speed_tolerances_and_costmap():
    args = _parser(add_arguments).parse_args(
        ["--rate", "10", "--max-speed", "0.3", "--failure-tolerance", "0", "--robot-radius", "0.3"]
    )
    config = config_from(args)
    assert config.control_period == pytest.approx(0.1)
    assert config.failure_tolerance == 0.0
    assert config.controllers["FollowPath"]().params.desired_linear_vel == 0.3  # type: ignore[attr-defined]
    assert config.controllers["DWB"]().params.max_vel_x == 0.3  # type: ignore[attr-defined]
    assert costmap_from(args).costmap.inflation.inscribed_radius == 0.3
    assert costmap_from(args).update_period == pytest.approx(0.2)  # Nav2's 5 Hz
    faster = _parser(add_arguments).parse_args(["--costmap-update-frequency", "20"])
    assert costmap_from(faster).update_period == pytest.approx(0.05)


@pytest.mark.parametrize("add", [add_arguments, add_behavior_arguments])
@pytest.mark.parametrize(
    "bad",
    [
        ["--rate", "0"],
        ["--rate", "nan"],
        ["--pose-timeout", "-1"],
        ["--costmap-update-frequency", "0"],
    ],
)
def test_bad_option_values_are_refused_naming_the_flag(add, bad, capsys):
    with pytest.raises(SystemExit):
        _parser(add).parse_args(bad)
    assert bad[0] in capsys.readouterr().err


async def test_unless_stopped_gives_the_result_or_cancels_the_work_on_stop():
    never = asyncio.Event()
    done = asyncio.create_task(never.wait())
    assert await unless_stopped(asyncio.sleep(0, result="clock"), done) == "clock"

    stopper = asyncio.create_task(asyncio.sleep(0))
    cancelled = asyncio.Event()

    async def waits_forever() -> str:
        try:
            await asyncio.Event().wait()
        finally:
            cancelled.set()
        return "unreachable"

    assert await unless_stopped(waits_forever(), stopper) is None
    await asyncio.sleep(0)
    assert cancelled.is_set()
    done.cancel()


def test_run_service_maps_an_unreachable_bus_to_exit_code_1(caplog):
    async def unreachable() -> None:
        raise BusUnavailable("no router at tcp/127.0.0.1:1")

    async def fine() -> None:
        return None

    log = logging.getLogger("aiobt_services.test")
    with caplog.at_level(logging.ERROR):
        assert run_service(unreachable(), log, "svc") == 1
    assert "svc: no router at tcp/127.0.0.1:1" in caplog.text
    assert run_service(fine(), log, "svc") == 0


def test_module_main_parses_the_service_options_then_runs(monkeypatch):
    seen: list[argparse.Namespace] = []
    configured: dict[str, object] = {}
    monkeypatch.setattr(logging, "basicConfig", lambda **kw: configured.update(kw))

    def add(parser: argparse.ArgumentParser) -> None:
        parser.add_argument("--rate", type=float)

    def run(args: argparse.Namespace) -> int:
        seen.append(args)
        return 7

    assert module_main("prog", None, add, run, ["-vv", "--rate", "5"]) == 7
    assert seen[0].rate == 5.0
    assert configured["level"] == logging.DEBUG
