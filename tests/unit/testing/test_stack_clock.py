"""NavStack's services on the simulation's clock or the wall's, as asked or as `aiobt up`."""

from __future__ import annotations

import pytest

from aiobt.system.config import SystemConfig
from aiobt.testing.stack import SIM_TIME, StackConfig

ENDPOINT = "tcp/127.0.0.1:1"


def on_sim_time(config: StackConfig) -> set[str]:
    return {s for s in config.services if "--sim-time" in config.command(s, ENDPOINT, "ns")}


def test_by_default_every_clock_follower_is_on_sim_time_at_any_speed() -> None:
    for speed in (1.0, 4.0):
        config = StackConfig(speed=speed, safety_chain=True)
        assert on_sim_time(config) == set(SIM_TIME) & set(config.services)
        assert on_sim_time(config)  # the chain, controller, behaviors, navigator


def test_wall_time_leaves_every_service_on_its_own_clock() -> None:
    config = StackConfig(speed=1.0, safety_chain=True, sim_time=False)
    assert on_sim_time(config) == set()
    assert "--clock-timeout" not in config.command("controller", ENDPOINT, "ns")


@pytest.mark.parametrize("speed", [1.0, 2.0, 10.0])
def test_unset_follows_aiobt_ups_rule(speed: float) -> None:
    config = StackConfig(speed=speed, safety_chain=True, sim_time=None)
    assert config.uses_sim_time == SystemConfig(speed=speed).uses_sim_time
    assert bool(on_sim_time(config)) == (speed != 1.0)
