"""The simulation's namespace ``{ns}/sim``: its topics and services by the same rule as
every key, and a service served there is answered there only."""

from __future__ import annotations

import pytest

from aiobt.msgs import Empty
from aiobt.msgs.sim import Ack
from aiobt.transport import Bus, ServiceUnavailable
from aiobt.transport.keys import SIM_POSE, Keys, sim_namespace, sim_topic


def test_the_simulation_s_keys_are_its_namespace_s() -> None:
    robot = Keys("robot")
    assert sim_namespace("robot") == robot.sim.namespace == "robot/sim"
    assert robot.sim.service("reset_pose") == "robot/sim/srv/reset_pose"
    assert robot.sim.topic("pose") == robot.topic(SIM_POSE) == "robot/sim/pose"
    assert robot.topic(sim_topic("target")) == "robot/sim/target"
    assert Keys("fleet/r2").sim.service("step") == "fleet/r2/sim/srv/step"


@pytest.mark.parametrize("bad", ["", "robot/", "robot/*", "/robot"])
def test_a_bad_namespace_is_named(bad: str) -> None:
    with pytest.raises(ValueError, match="namespace"):
        sim_namespace(bad)


async def test_a_service_served_in_the_simulation_s_namespace_is_answered_there_only(
    local_bus: Bus,
) -> None:
    sim = sim_namespace(local_bus.namespace)
    local_bus.serve("obstacles/list", Empty, Ack, lambda _: Ack(ok=True), namespace=sim)
    assert (await local_bus.call("obstacles/list", Empty(), Ack, namespace=sim)).ok
    with pytest.raises(ServiceUnavailable, match=rf"{local_bus.namespace}/srv/obstacles/list"):
        await local_bus.call("obstacles/list", Empty(), Ack, timeout=0.2)
