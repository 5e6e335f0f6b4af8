"""``aiobt foxglove --no-server --mcap FILE`` records a navigation of the whole stack."""

from __future__ import annotations

import itertools
import json
from collections import defaultdict
from collections.abc import Iterator
from pathlib import Path
from typing import Any

import foxglove
import pytest
from mcap.reader import make_reader
from mcap_protobuf.decoder import DecoderFactory

from aiobt.foxglove.channels import Channels
from aiobt.msgs import GoalState, NavigateToPose, PoseStamped
from aiobt.testing.bus import ServiceProcess, spawn_service
from aiobt.testing.navwatch import ServerGoals
from aiobt.testing.stack import NavStack, StackConfig, running_stack
from aiobt.transport import open_bus

pytestmark = [pytest.mark.integration, pytest.mark.e2e]

GOAL = (1.0, 0.8, 0.0)  # small world: open floor from the start at the origin


# channels of the services `aiobt up` leaves off by default (the route, following and
# docking servers), of the safety chain's monitor and of the localization (a stack whose
# robot stands in for them has none): this stack may not run them, so nothing need be
# recorded on them
OFF_BY_DEFAULT = {
    "/collision_monitor", "/route", "/route_graph", "/followed", "/docks", "/particle_cloud",
    "/amcl_pose",
}  # fmt: skip


def every_topic() -> set[str]:
    """The channels of the services this stack runs."""
    return Channels.create(foxglove.Context()).topics() - OFF_BY_DEFAULT


@pytest.fixture
def stack() -> Iterator[NavStack]:
    with running_stack(StackConfig(world="small", speed=2.0)) as running:
        yield running


def start_recorder(stack: NavStack, path: Path) -> ServiceProcess:
    args = ["-m", "aiobt.cli.main", "foxglove", "--connect", stack.endpoint]
    return spawn_service(
        [*args, "--namespace", stack.namespace, "--no-server", "--mcap", str(path)]
    )


def read_back(path: Path) -> dict[str, list[tuple[int, Any]]]:
    """topic -> [(log_time, decoded message)] in file order."""
    out: dict[str, list[tuple[int, Any]]] = defaultdict(list)
    with path.open("rb") as f:
        protobuf = DecoderFactory()
        for schema, channel, message in make_reader(f).iter_messages(log_time_order=False):
            if channel.message_encoding == "json":
                decoded = json.loads(message.data)
            else:
                decode = protobuf.decoder_for(channel.message_encoding, schema)
                assert decode is not None, channel
                decoded = decode(message.data)
            out[channel.topic].append((message.log_time, decoded))
    return out


@pytest.mark.timeout(240)
async def test_recording_holds_every_channel_in_time_order(stack: NavStack, tmp_path: Path) -> None:
    path = tmp_path / "run.mcap"
    recorder = start_recorder(stack, path)
    try:
        async with open_bus(stack.settings()) as bus:
            goals = ServerGoals(bus, [NavigateToPose])
            await stack.wait_ready(bus, timeout=90.0)
            # its token comes after its subscriptions: a goal put now reaches the bridge too
            bridged = await bus.presence(bus.keys.topic("nodes/foxglove")).wait(60.0)
            assert bridged, recorder.output()
            pub = bus.publisher("goal_pose", PoseStamped, reliable=True)
            for _ in range(6):  # the navigator's subscription may not be routed at once
                pub.put(PoseStamped.from_xy_yaw(*GOAL))
                if await goals.wait_for(lambda: bool(goals.states["navigate_to_pose"]), 10.0):
                    break
            ended = await goals.wait_for(
                lambda: goals.ended("navigate_to_pose", GoalState.SUCCEEDED) >= 1, 120.0
            )
            assert ended, f"{goals.states}\n{stack.logs()}"
            goals.close()
        assert recorder.stop(timeout=15.0) == 0, recorder.output()
        recorded = read_back(path)
    finally:
        recorder.cleanup()
    missing = every_topic() - recorded.keys()
    assert not missing, f"no messages on {sorted(missing)}"
    for topic, messages in recorded.items():
        times = [t for t, _ in messages]
        assert times == sorted(times), f"{topic}: log times out of order"
    scan_stamps = [m.timestamp.ToNanoseconds() for _, m in recorded["/scan"]]
    assert len(scan_stamps) > 10
    assert all(a < b for a, b in itertools.pairwise(scan_stamps)), "scan stamps"
    goal = recorded["/goal"][0][1]
    assert (goal.pose.position.x, goal.pose.position.y) == GOAL[:2]
    assert recorded["/plan"][-1][1].poses, "an empty plan"
    local_plans = [m for _, m in recorded["/local_plan"]]
    assert any(len(m.poses) >= 2 and m.frame_id == "map" for m in local_plans)
    local_costmap = recorded["/local_costmap"][-1][1]
    assert (local_costmap.column_count, local_costmap.cell_size.x) == (100, 0.05)
    costs = recorded["/global_costmap"][-1][1].data
    assert b"\xfe" in costs, "no lethal cell in the costmap"  # the small world's walls
    assert recorded["/navigator/feedback"][-1][1]["distance_remaining"] >= 0.0
    assert recorded["/sim/pose"][-1][1].frame_id == "map"  # `aiobt foxglove` records the truth


@pytest.mark.timeout(240)
async def test_the_navigator_records_each_navigation_to_its_own_mcap(tmp_path: Path) -> None:
    runs = tmp_path / "runs"
    config = StackConfig(world="small", speed=2.0, extra={"navigator": ["--mcap-dir", str(runs)]})
    with running_stack(config) as stack:
        async with open_bus(stack.settings()) as bus:
            await stack.wait_ready(bus, timeout=90.0)
            client = bus.action_client(NavigateToPose.name, NavigateToPose)
            assert await client.wait_for_server(60.0), stack.logs()
            for goal in (GOAL, (0.0, 0.0, 0.0)):  # there and back: two navigations
                sent = await client.send_goal(
                    NavigateToPose.Goal(pose=PoseStamped.from_xy_yaw(*goal)), server_timeout=10.0
                )
                result = await sent.result(120.0)
                assert sent.status is GoalState.SUCCEEDED, f"{result}\n{stack.logs()}"
        files = sorted(runs.glob("*.mcap"))  # each closed before its result was sent
        assert [f.name.split("_", 2)[-1][:16] for f in files] == ["navigate_to_pose"] * 2
        for path in files:
            recorded = read_back(path)
            missing = every_topic() - recorded.keys() - {"/goal"}  # goals sent as actions
            assert missing == {"/sim/pose"}, f"{path.name}: no messages on {sorted(missing)}"
            # the navigator is a navigation service: its recording never reads the truth
            times = [t for t, _ in recorded["/pose"]]
            assert times == sorted(times), f"{path.name}: /pose out of order"
        first, second = (read_back(f)["/pose"] for f in files)
        assert first[-1][0] <= second[0][0], "the second navigation's recording started first"
