"""Separate processes: a killed or hung server, the zenoh CLI, auth, clean exits, no leaks."""

from __future__ import annotations

import asyncio
import json
import os
import signal
import subprocess
import sys
import textwrap
import threading
import time
from collections.abc import Callable, Iterator, Sequence
from pathlib import Path

import pytest

from aiobt.msgs import GoalState, PoseStamped, Twist, Wait
from aiobt.testing.bus import (
    ServiceProcess,
    free_endpoint,
    running_router,
    spawn_service,
    start_router,
)
from aiobt.transport import (
    ActionClient,
    Bus,
    BusSettings,
    BusUnavailable,
    ClientGoal,
    GoalLost,
    open_bus,
)
from aiobt.transport.settings import Mode

pytestmark = pytest.mark.integration
Spawn = Callable[[Sequence[str]], ServiceProcess]
SERVER = "tests.integration.transport.action_server_proc"
ZENOH_CLI = Path(sys.executable).with_name("zenoh")
WaitClient = ActionClient[Wait.Goal, Wait.Result, Wait.Feedback]
WaitGoal = ClientGoal[Wait.Goal, Wait.Result, Wait.Feedback]


def start_server(spawn: Spawn, settings: BusSettings) -> ServiceProcess:
    args = ["-m", SERVER, "--connect", settings.connect[0], "--namespace", settings.namespace]
    return spawn(args)


async def goal_under_way(
    bus: Bus, bus_settings: BusSettings, spawn: Spawn
) -> tuple[ServiceProcess, WaitClient, WaitGoal]:
    """A server process running a long ``wait`` goal that has sent feedback already."""
    server = start_server(spawn, bus_settings)
    client = bus.action_client("wait", Wait)
    goal = await client.send_goal(Wait.Goal(time=30.0), server_timeout=10.0)
    async for _ in goal.feedback():
        break
    return server, client, goal


async def test_killed_server_fails_the_goal_fast_and_a_restart_serves_again(
    bus: Bus, bus_settings: BusSettings, spawn: Spawn
) -> None:
    server, client, goal = await goal_under_way(bus, bus_settings, spawn)
    server.kill()
    killed = time.monotonic()
    with pytest.raises(GoalLost, match="lost: the server is gone: its session closed"):
        await goal.result(timeout=5.0)
    assert time.monotonic() - killed < 1.5
    start_server(spawn, bus_settings)
    again = await client.send_goal(Wait.Goal(time=0.1), server_timeout=10.0)
    result = await again.result(timeout=5.0)
    assert result.total_elapsed_time >= 0.1


async def test_hung_server_is_noticed_within_the_lease(
    bus: Bus, bus_settings: BusSettings, spawn: Spawn
) -> None:
    server, _, goal = await goal_under_way(bus, bus_settings, spawn)
    os.kill(server.pid, signal.SIGSTOP)
    try:
        hung = time.monotonic()
        with pytest.raises(GoalLost, match=r"the server is not answering: nothing from it for"):
            await goal.result(timeout=5.0)
        assert time.monotonic() - hung < 2.0  # lease 1000 ms
    finally:
        os.kill(server.pid, signal.SIGCONT)
        server.kill()


async def test_goal_from_the_zenoh_command_line(bus: Bus, router_endpoint: str) -> None:
    sub = bus.subscribe("goal_pose", PoseStamped)
    await asyncio.sleep(0.3)  # the CLI publishes once, at once: let the subscription settle
    command = [
        str(ZENOH_CLI),
        "--mode",
        "client",
        "--connect",
        router_endpoint,
        "put",
        "-k",
        f"{bus.namespace}/goal_pose",
        "-v",
        '{"x": 1.5, "y": -2.0, "yaw": 0.5}',
    ]
    proc = await asyncio.create_subprocess_exec(
        *command, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE
    )
    try:
        _, stderr = await asyncio.wait_for(proc.communicate(), 30.0)
    finally:
        if proc.returncode is None:
            proc.kill()
            await proc.wait()
    assert proc.returncode == 0, stderr.decode()
    goal = await sub.next(timeout=5.0)
    assert (goal.x, goal.y, goal.header.frame_id) == (1.5, -2.0, "map")
    assert goal.yaw == pytest.approx(0.5)


def test_user_password_auth(tmp_path: Path, spawn: Spawn) -> None:
    """The documented setup: credentials in a config file, no other flag (mode, scouting
    and the router endpoint come from aiobt's defaults, not Zenoh's peer defaults)."""
    (tmp_path / "users.txt").write_text("robot:s3cret\n")
    users = {"dictionary_file": str(tmp_path / "users.txt")}
    (tmp_path / "router.json5").write_text(json.dumps({"transport": {"auth": {"usrpwd": users}}}))

    def client_config(user: str, password: str) -> str:
        path = tmp_path / f"client-{user}-{password}.json5"
        usrpwd = {"user": user, "password": password}
        path.write_text(json.dumps({"transport": {"auth": {"usrpwd": usrpwd}}}))
        return str(path)

    async def outcome(endpoint: str, config: str | None, mode: Mode | None = None) -> str:
        settings = BusSettings(
            connect=(endpoint,), config_file=config, connect_timeout=1.0, mode=mode
        )
        try:
            async with open_bus(settings) as bus:
                return "talks" if bus.session.info.routers_zid() else "open but unconnected"
        except BusUnavailable:
            return "refused"

    with running_router(extra_args=["--config", str(tmp_path / "router.json5")]) as (_, ep):
        assert asyncio.run(outcome(ep, client_config("robot", "s3cret"))) == "talks"
        assert asyncio.run(outcome(ep, client_config("robot", "wrong"))) == "refused"
        assert asyncio.run(outcome(ep, None)) == "refused"
        # a peer told to connect there is refused too, not left running on its own
        assert asyncio.run(outcome(ep, client_config("robot", "s3cret"), "peer")) == "talks"
        assert asyncio.run(outcome(ep, client_config("robot", "wrong"), "peer")) == "refused"
        # a service process with a wrong password gives up and says why (exit code 1)
        service = spawn(
            [
                "-m",
                "aiobt.cli.main",
                "planner",
                "--connect",
                ep,
                "--config",
                client_config("robot", "wrong"),
                "--connect-timeout",
                "1",
            ]
        )
        service.popen.wait(timeout=30)
        assert service.popen.returncode == 1, service.output()
        assert "cannot open the Zenoh session" in service.output()
        assert "planner up" not in service.output()


@pytest.fixture
def hung_router() -> Iterator[str]:
    """A router process that accepts TCP connections but never answers (SIGSTOP)."""
    router, endpoint = start_router()
    os.kill(router.pid, signal.SIGSTOP)
    try:
        yield endpoint
    finally:
        os.kill(router.pid, signal.SIGCONT)
        router.cleanup()


@pytest.mark.parametrize("far_end", ["nothing listening", "hung router"])
def test_a_service_waiting_for_its_router_stops_on_sigterm(
    spawn: Spawn, far_end: str, request: pytest.FixtureRequest
) -> None:
    endpoint = (
        free_endpoint()
        if far_end == "nothing listening"
        else request.getfixturevalue("hung_router")
    )
    service = spawn(["-m", "aiobt.cli.main", "planner", "--connect", endpoint])
    assert service.wait_for_output("cannot open the Zenoh session yet", timeout=30.0), (
        service.output()
    )
    started = time.monotonic()
    os.kill(service.pid, signal.SIGTERM)
    service.popen.wait(timeout=15)
    assert service.popen.returncode == 0, service.output()
    # at worst one link handshake (2 s) is under way when the signal comes
    assert time.monotonic() - started < 4.0


def test_connect_timeout_holds_against_a_hung_router(spawn: Spawn, hung_router: str) -> None:
    started = time.monotonic()
    service = spawn(
        ["-m", "aiobt.cli.main", "planner", "--connect", hung_router, "--connect-timeout", "3"]
    )
    service.popen.wait(timeout=30)
    took = time.monotonic() - started
    assert service.popen.returncode == 1, service.output()
    assert "cannot open the Zenoh session" in service.output()
    assert took < 6.0  # 3 s + start-up; Zenoh's own handshake timeout alone is 10 s


def test_process_with_open_entities_exits_cleanly(router_endpoint: str) -> None:
    script = textwrap.dedent(f"""
        import asyncio
        from aiobt.msgs import Twist, Wait, ClearCostmapResponse, ClearEntireCostmap
        from aiobt.transport import BusSettings, open_bus

        async def main():
            settings = BusSettings(connect=("{router_endpoint}",), namespace="exit_test")
            async with open_bus(settings) as bus:
                bus.subscribe("cmd_vel", Twist, callback=print)
                bus.latched_publisher("map_x", Twist).put(Twist())
                bus.subscribe("map_x", Twist, latched=True)
                bus.serve("clear", ClearEntireCostmap.Request, ClearCostmapResponse,
                          lambda r: ClearCostmapResponse())
                async def execute(goal, handle):
                    await asyncio.sleep(10)
                    return Wait.Result()
                bus.action_server("wait", Wait, execute)
                bus.action_client("wait", Wait)
                await asyncio.sleep(0.2)

        asyncio.run(main())
    """)
    started = time.monotonic()
    done = subprocess.run([sys.executable, "-c", script], capture_output=True, timeout=30)
    assert done.returncode == 0, done.stderr.decode()
    assert time.monotonic() - started < 10


async def test_no_threads_left_after_the_bus_closes(bus_settings: BusSettings) -> None:
    before = {t.ident for t in threading.enumerate()}
    async with open_bus(bus_settings) as server, open_bus(bus_settings) as client:
        events: list[str] = []

        async def execute(goal: Wait.Goal, handle: object) -> Wait.Result:
            events.append("ran")
            return Wait.Result()

        server.action_server("wait", Wait, execute)
        goal = await client.action_client("wait", Wait).send_goal(
            Wait.Goal(time=0), server_timeout=5.0
        )
        await goal.result(timeout=5.0)
    assert events == ["ran"]
    leftover = [t.name for t in threading.enumerate() if t.ident not in before]
    assert leftover == []


async def test_sessions_reconnect_after_a_router_restart() -> None:
    router, endpoint = start_router()
    try:
        settings = BusSettings(connect=(endpoint,), namespace="restart", connect_timeout=10.0)
        async with open_bus(settings) as talker, open_bus(settings) as listener:
            sub = listener.subscribe("cmd_vel", Twist)
            pub = talker.publisher("cmd_vel", Twist)
            assert await pub.wait_for_subscribers(5.0)
            pub.put(Twist.planar(1.0, 0.0))
            assert (await sub.next(timeout=5.0)).linear.x == 1.0
            router.kill()
            router, _ = start_router(endpoint)
            assert await pub.wait_for_subscribers(10.0)
            pub.put(Twist.planar(2.0, 0.0))
            assert (await sub.next(timeout=5.0)).linear.x == 2.0
    finally:
        router.cleanup()


def child_pids() -> set[int]:
    """PIDs whose parent is this process (zombies included: an unreaped child counts)."""
    children = set()
    for entry in Path("/proc").iterdir():
        if not entry.name.isdigit():
            continue
        try:
            stat = (entry / "stat").read_text()
        except OSError:
            continue  # gone meanwhile
        if int(stat.rsplit(")", 1)[1].split()[1]) == os.getpid():
            children.add(int(entry.name))
    return children


def test_router_and_service_processes_leave_nothing_behind() -> None:
    before = child_pids()
    with running_router() as (router, endpoint):
        server = spawn_service(["-m", SERVER, "--connect", endpoint, "--namespace", "leftover"])
        try:
            assert server.wait_for_output("ready", 20.0), server.output()

            async def one_goal() -> GoalState:
                settings = BusSettings(connect=(endpoint,), namespace="leftover")
                async with open_bus(settings) as bus:
                    client = bus.action_client("wait", Wait)
                    goal = await client.send_goal(Wait.Goal(time=0.05), server_timeout=10.0)
                    await goal.result(timeout=5.0)
                    return goal.status

            assert asyncio.run(one_goal()) is GoalState.SUCCEEDED
            assert child_pids() - before == {router.pid, server.pid}
        finally:
            server.cleanup()
    assert child_pids() - before == set()
