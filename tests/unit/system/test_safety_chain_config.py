"""``safety_chain`` in the system config: off by default; on, the velocity smoother and
the collision monitor run and the controller and behaviors command ``cmd_vel_nav``."""

from __future__ import annotations

from pathlib import Path

import pytest
import yaml

from aiobt.system.commands import available, service_command
from aiobt.system.config import ConfigError, config_from_dict


def test_off_by_default_nothing_changes() -> None:
    config = config_from_dict({})
    assert config.enabled() == ["robot", "planner", "controller", "behaviors", "navigator"]
    assert "--cmd-vel-topic" not in service_command("controller", config)


def test_on_the_chain_runs_between_the_commands_and_the_base() -> None:
    config = config_from_dict({"safety_chain": True, "speed": 4})
    assert config.enabled() == ["robot", "planner", "controller", "behaviors",
                                "velocity_smoother", "collision_monitor", "navigator"]  # fmt: skip
    for name in ("controller", "behaviors"):
        assert service_command(name, config)[-2:] == ["--cmd-vel-topic", "cmd_vel_nav"]
    smoother = service_command("velocity_smoother", config)
    assert smoother[0] == "velocity_smoother"
    assert "--sim-time" in smoother
    assert service_command("collision_monitor", config)[0] == "collision_monitor"
    assert available("velocity_smoother")
    assert available("collision_monitor")


def test_each_link_has_its_own_section() -> None:
    config = config_from_dict({
        "safety_chain": True,
        "services": {"collision_monitor": {"args": ["--params-file", "cm.yaml"]},
                     "velocity_smoother": {"enabled": False}},
    })  # fmt: skip
    assert "velocity_smoother" not in config.enabled()
    assert service_command("collision_monitor", config)[-2:] == ["--params-file", "cm.yaml"]


def test_a_wrong_type_is_refused_by_name() -> None:
    with pytest.raises(ConfigError, match="safety_chain must be bool"):
        config_from_dict({"safety_chain": "yes"})


def test_the_compose_override_runs_the_commands_aiobt_up_runs() -> None:
    repo = Path(__file__).resolve().parents[3]
    base = yaml.safe_load((repo / "docker-compose.yml").read_text())["services"]
    chain = yaml.safe_load((repo / "docker-compose.safety-chain.yml").read_text())["services"]
    config = config_from_dict({"safety_chain": True, "router": {"listen": "tcp/router:7447"}})
    assert sorted(chain) == ["behaviors", "collision-monitor", "controller", "velocity-smoother"]
    for name, spec in chain.items():
        assert spec["command"] == service_command(spec["command"][0], config)
        if name in base:
            continue
        assert {k: v for k, v in spec.items() if k != "command"} == {
            "image": base["planner"]["image"], "build": ".", "env_file": ["zenoh.env"],
            "depends_on": ["router"], "restart": "on-failure", "init": True,
        }  # fmt: skip
