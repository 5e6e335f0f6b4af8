"""``safety_chain`` in the system config: on by default, the velocity smoother and the
collision monitor run and the controller and behaviors command ``cmd_vel_nav``; off,
the controller and behaviors command the base directly."""

from __future__ import annotations

from pathlib import Path

import pytest

from aiobt.system.commands import available, service_command
from aiobt.system.config import ConfigError, config_from_dict
from tests import compose_files

CHAIN = ["robot", "localization", "planner", "controller", "behaviors", "velocity_smoother",
         "collision_monitor", "navigator"]  # fmt: skip


def test_on_by_default_the_chain_runs_between_the_commands_and_the_base() -> None:
    config = config_from_dict({"speed": 4})
    assert config.safety_chain
    assert config.enabled() == CHAIN
    for name in ("controller", "behaviors"):
        assert service_command(name, config)[-2:] == ["--cmd-vel-topic", "cmd_vel_nav"]
    smoother = service_command("velocity_smoother", config)
    assert smoother[0] == "velocity_smoother"
    assert "--sim-time" in smoother
    assert service_command("collision_monitor", config)[0] == "collision_monitor"
    assert available("velocity_smoother")
    assert available("collision_monitor")


def test_off_the_commands_go_to_the_base() -> None:
    config = config_from_dict({"safety_chain": False})
    assert config.enabled() == [
        "robot", "localization", "planner", "controller", "behaviors", "navigator",
    ]  # fmt: skip
    assert "--cmd-vel-topic" not in service_command("controller", config)
    assert "--cmd-vel-topic" not in service_command("behaviors", config)


def test_each_link_has_its_own_section() -> None:
    config = config_from_dict({
        "services": {"collision_monitor": {"args": ["--params-file", "cm.yaml"]},
                     "velocity_smoother": {"enabled": False}},
    })  # fmt: skip
    assert "velocity_smoother" not in config.enabled()
    assert service_command("collision_monitor", config)[-2:] == ["--params-file", "cm.yaml"]


def test_a_wrong_type_is_refused_by_name() -> None:
    with pytest.raises(ConfigError, match="safety_chain must be bool"):
        config_from_dict({"safety_chain": "yes"})


def test_compose_runs_the_chain_as_aiobt_up_does(tmp_path: Path) -> None:
    services = compose_files.load("docker-compose.yml")["services"]
    certs = compose_files.make_certs(tmp_path)
    for prefix, namespace in (("", "robot"), ("robot2-", "robot2")):
        config = compose_files.up_config(certs, namespace=namespace)
        for name in ("controller", "behaviors", "velocity-smoother", "collision-monitor"):
            command = services[prefix + name]["command"]
            expected = compose_files.in_containers(service_command(command[0], config), certs)
            assert command == expected, prefix + name
