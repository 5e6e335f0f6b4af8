"""The one list of services (aiobt.system.catalog) is where the CLI's service commands,
`aiobt up`'s config keys and order, and the real-time defaults come from."""

from __future__ import annotations

import argparse
import importlib

import pytest

from aiobt.cli.main import COMMANDS
from aiobt.system.catalog import (
    SAFETY_CHAIN,
    SERVICE_NAMES,
    SERVICES,
    realtime_priority,
    service,
)
from aiobt.system.commands import available
from aiobt.system.config import ConfigError, SystemConfig, config_from_dict


def test_every_service_is_an_aiobt_command_by_module_path() -> None:
    for spec in SERVICES:
        assert COMMANDS[spec.name] == (spec.module, spec.summary)
        assert available(spec.name)
    assert not available("teleport")


def test_aiobt_up_takes_its_service_keys_and_order_from_the_list() -> None:
    assert tuple(SystemConfig().services) == SERVICE_NAMES
    by_default = [s.name for s in SERVICES if s.enabled]  # route: off, as in Nav2
    without = [name for name in by_default if name not in SAFETY_CHAIN]
    assert SystemConfig().enabled() == by_default  # the safety chain too, by default
    assert SystemConfig(safety_chain=False).enabled() == without
    with pytest.raises(ConfigError, match=r"unknown service services.plannr \(known: robot, "):
        config_from_dict({"services": {"plannr": {}}}, "cfg.yaml")


@pytest.mark.parametrize("name", [s.name for s in SERVICES if s.realtime_priority is not None])
def test_each_service_gives_its_listed_realtime_default(name: str) -> None:
    parser = argparse.ArgumentParser()
    importlib.import_module(service(name).module).add_arguments(parser)
    assert parser.parse_args(["--realtime-priority"]).realtime_priority == realtime_priority(name)
    assert parser.parse_args([]).realtime_priority is None


def test_an_unknown_name_is_refused_with_the_known_ones() -> None:
    with pytest.raises(KeyError, match=f"known: {', '.join(SERVICE_NAMES)}"):
        service("plannr")
    with pytest.raises(KeyError, match="no --realtime-priority option"):
        realtime_priority("behaviors")
