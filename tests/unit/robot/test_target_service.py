"""``{ns}/sim/srv/follow_target/*`` answered over an in-process bus: a loop refused by
name, a seeded start, hide and stop, and the detection and truth published per scan;
nothing of it outside the simulation's namespace."""

from __future__ import annotations

import argparse
import math

import pytest

from aiobt.msgs import Empty, Msg, PoseStamped
from aiobt.msgs.follow_target import HideTarget, StartTarget, TargetStarted
from aiobt.msgs.sim import Ack
from aiobt.transport import Bus, ServiceUnavailable
from aiobt.transport.keys import sim_namespace
from aiobt_services.robot.mapfile import load_map
from aiobt_services.robot.runner import SimRunner
from aiobt_services.robot.sim import Simulation
from aiobt_services.robot.target_service import add_target_arguments, wire_target
from aiobt_services.robot.worlds import world_path


class Sink:
    """The runner's outputs: the topics published, in order."""

    def __init__(self) -> None:
        self.topics: list[str] = []

    def publish(self, topic: str, msg: Msg) -> None:
        self.topics.append(topic)


def flags(*argv: str) -> argparse.Namespace:
    parser = argparse.ArgumentParser()
    add_target_arguments(parser)
    return parser.parse_args(list(argv))


async def test_start_hide_stop_and_what_each_scan_publishes(local_bus: Bus) -> None:
    world = load_map(world_path("office"))
    world.start = (3.0, 13.6, 0.0)  # in the open plan, west of the loop
    seen: list[PoseStamped] = []
    truth: list[PoseStamped] = []
    local_bus.subscribe("dynamic_pose", PoseStamped, seen.append)
    local_bus.subscribe("sim/target", PoseStamped, truth.append)
    with Simulation(world) as sim:
        sink = Sink()
        targets = wire_target(local_bus, sim, flags("--target-dropout", "0"))
        runner = SimRunner(sim, targets.tap(sink))
        ns = sim_namespace(local_bus.namespace)  # the simulation's services
        with pytest.raises(ServiceUnavailable):  # not in the robot's own namespace
            await local_bus.call("follow_target/start", StartTarget(seed=2), TargetStarted, 0.2)
        wall = StartTarget(waypoints=[(2.0, 9.75), (6.0, 9.75), (6.0, 13.0)])
        refused = await local_bus.call("follow_target/start", wall, TargetStarted, namespace=ns)
        assert not refused.ok
        assert "of a wall" in refused.message
        start = StartTarget(seed=2)
        started = await local_bus.call("follow_target/start", start, TargetStarted, namespace=ns)
        assert started.ok, started.message
        assert 15.0 < started.length < 21.0
        await runner.advance(1.0)
        await local_bus.call("follow_target/hide", HideTarget(seconds=0.5), Ack, namespace=ns)
        await runner.advance(0.45)
        stopped = await local_bus.call("follow_target/stop", Empty(), Ack, namespace=ns)
        assert stopped.ok
        assert "target" not in sim.obstacles
        again = await local_bus.call("follow_target/stop", Empty(), Ack, namespace=ns)
        assert not again.ok
    assert sink.topics.count("scan") == 14  # every output still goes out
    assert [m.header.stamp for m in truth][:3] == [0.1, 0.2, 0.3]
    assert {m.header.frame_id for m in seen} == {"base_link"}
    assert all(m.header.stamp <= 1.0 for m in seen)  # none while hidden (1.0 .. 1.5 s)
    box, robot = truth[0], world.start
    first = next(m for m in seen if m.header.stamp == truth[0].header.stamp)
    x = robot[0] + first.x
    y = robot[1] + first.y
    assert math.hypot(x - box.x, y - box.y) < 0.1


def test_follow_target_at_start_up_is_a_seed() -> None:
    assert flags("--follow-target", "5").follow_target == 5
    assert flags().target_topic == "dynamic_pose"
