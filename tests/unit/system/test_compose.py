"""Nav2's composition (:mod:`aiobt.system.compose`): the safety chain's two services from
one command line, each with its own flags, parameters, token name and errors; and how
``aiobt up`` and the test stack run it (``use_composition``)."""

from __future__ import annotations

import argparse
import dataclasses
from pathlib import Path

import pytest

from aiobt.cli.main import COMMANDS, _full_parser
from aiobt.system import compose
from aiobt.system.commands import available, processes, service_command
from aiobt.system.config import ConfigError, config_from_dict
from aiobt.system.runner import System
from aiobt.system.service import Component, time_sources
from aiobt.system.supervisor import Supervisor
from aiobt.testing.stack import StackConfig
from aiobt.transport import Bus
from aiobt_services.collision_monitor.main import DEFAULT_PARAMS
from aiobt_services.collision_monitor.params import MonitorConfigError
from aiobt_services.velocity_smoother.params import SmootherConfigError

CONNECT = ["--connect", "tcp/127.0.0.1:7447", "--namespace", "ns"]


def parse(argv: list[str]) -> argparse.Namespace:
    full = ["safety_chain", *CONNECT, *argv]
    return _full_parser(full).parse_args(full)


def test_a_flag_two_services_define_is_refused_by_name_and_shared_ones_are_not() -> None:
    shared = frozenset({"--connect", "--sim-time"})
    flags = {
        "a": frozenset({"--connect", "--sim-time", "--odom-topic", "--x"}),
        "b": frozenset({"--connect", "--sim-time", "--odom-topic", "--y"}),
    }
    assert compose.flag_clashes(flags, shared) == ["--odom-topic: a and b"]
    assert compose.flag_clashes({"a": flags["a"], "c": frozenset({"--y"})}, shared) == []


def test_the_safety_chain_shares_only_the_bus_clock_and_priority_flags() -> None:
    assert {"--connect", "--sim-time", "--clock-timeout", "--realtime-priority"} <= (
        compose.shared_flags()
    )
    assert COMMANDS["safety_chain"][0] == "aiobt.system.compose"
    assert available("safety_chain")


def test_each_service_takes_its_own_flags_from_the_one_command_line() -> None:
    args = parse(["--sim-time", "--max-accel", "1.0", "0", "2.0", "--disabled",
                  "--params-file", str(DEFAULT_PARAMS), "--realtime-priority"])  # fmt: skip
    assert args.max_accel == [1.0, 0.0, 2.0]
    assert args.disabled
    assert args.sim_time
    assert args.realtime_priority == 90
    smoother, monitor = compose.build(compose.components_of("safety_chain"), args)
    assert (smoother.name, monitor.name) == ("velocity_smoother", "collision_monitor")
    assert smoother.odometry is None  # its timer ramps on the 100 Hz clock
    assert monitor.odometry == "odom"  # its time from the odometry it reads anyway
    assert "cmd_vel_nav -> cmd_vel_smoothed" in smoother.detail
    assert "cmd_vel_smoothed -> cmd_vel" in monitor.detail


@pytest.mark.parametrize(
    ("argv", "error", "named"),
    [
        (["--max-accel", "-1", "0", "1"], SmootherConfigError, "max_accel"),
        (["--params-file", "/nonexistent.yaml"], MonitorConfigError, "/nonexistent.yaml"),
    ],
)
def test_a_bad_parameter_is_each_services_own_error(
    argv: list[str], error: type[Exception], named: str, caplog: pytest.LogCaptureFixture
) -> None:
    args = parse(argv)
    with pytest.raises(error, match=named):
        compose.build(compose.components_of("safety_chain"), args)
    assert compose.run(args) == 2  # refused at start, as each alone
    assert named in caplog.text


def test_an_unknown_composition_is_named() -> None:
    with pytest.raises(compose.CompositionError, match=r"no composition 'chain' .*safety_chain"):
        compose.components_of("chain")


def test_up_runs_the_chain_composed_only_when_asked() -> None:
    separate = config_from_dict({"speed": 4})
    assert "safety_chain" not in processes(separate)
    config = config_from_dict({
        "speed": 4, "use_composition": True,
        "services": {"collision_monitor": {"args": ["--params-file", "cm.yaml"]},
                     "velocity_smoother": {"args": ["--max-accel", "1", "0", "1"]}},
    })  # fmt: skip
    assert processes(config) == ["robot", "localization", "planner", "controller",
                                  "behaviors", "safety_chain", "navigator"]  # fmt: skip
    command = service_command("safety_chain", config)
    assert command[0] == "safety_chain"
    assert "--sim-time" in command
    assert command[-6:] == ["--max-accel", "1", "0", "1", "--params-file", "cm.yaml"]
    assert service_command("controller", config)[-2:] == ["--cmd-vel-topic", "cmd_vel_nav"]
    one_off = config_from_dict(
        {"use_composition": True, "services": {"collision_monitor": {"enabled": False}}}
    )
    assert "velocity_smoother" in processes(one_off)  # one link alone is not composed
    assert "safety_chain" not in processes(one_off)


def test_composition_with_certificates_is_refused(tmp_path: Path) -> None:
    (tmp_path / "ca.pem").write_text("")
    router = {"listen": "tls/127.0.0.1:7447", "certs": str(tmp_path)}
    assert not config_from_dict({"router": router}).use_composition
    with pytest.raises(ConfigError, match=r"use_composition with router\.certs"):
        config_from_dict({"use_composition": True, "router": router})
    # a default of true (once the lead flips it) leaves a deployment with certificates separate
    defaulted = dataclasses.replace(config_from_dict({"router": router}), use_composition=True)
    assert "safety_chain" not in processes(defaulted)
    assert {"velocity_smoother", "collision_monitor"} <= set(processes(defaulted))


def test_the_test_stack_runs_one_process_with_both_tokens_and_both_extras() -> None:
    config = StackConfig(
        safety_chain=True,
        use_composition=True,
        extra={
            "velocity_smoother": ["--max-accel", "1", "0", "1"],
            "collision_monitor": ["--disabled"],
        },
    )
    assert "safety_chain" in config.services
    assert not {"velocity_smoother", "collision_monitor"} & set(config.services)
    assert config.tokens("safety_chain") == ("velocity_smoother", "collision_monitor")
    assert config.tokens("controller") == ("controller",)
    command = config.command("safety_chain", "tcp/127.0.0.1:1", "ns")
    assert command[2] == "safety_chain"
    assert "--sim-time" in command
    assert command[-5:] == ["--max-accel", "1", "0", "1", "--disabled"]


async def test_up_takes_a_composed_process_as_up_once_both_tokens_are(
    local_bus: Bus,
) -> None:
    config = config_from_dict({"use_composition": True})
    supervisor = Supervisor(config.restart, Sink())
    system = System(config, supervisor, ["safety_chain"])
    system._watch(local_bus)
    local_bus.declare_token("nodes/velocity_smoother")
    assert await system.wait_healthy(0.3) == ["safety_chain"]  # the monitor's is missing
    local_bus.declare_token("nodes/collision_monitor")
    assert await system.wait_healthy(5.0) == []


class Sink:
    def line(self, name: str, text: str) -> None: ...

    def event(self, name: str, text: str) -> None: ...


def test_composed_the_monitor_shares_the_smoothers_clock() -> None:
    def start(bus: Bus, clock: object) -> None: ...

    smoother = Component("velocity_smoother", start)
    monitor = Component("collision_monitor", start, odometry="odom")
    assert time_sources([monitor]) == {"collision_monitor": "odom"}  # alone: no clock at all
    assert time_sources([smoother]) == {"velocity_smoother": None}
    both = {"velocity_smoother": None, "collision_monitor": None}  # the clock is there anyway
    assert time_sources([smoother, monitor]) == both
