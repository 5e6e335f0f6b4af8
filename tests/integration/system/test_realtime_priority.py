"""``--realtime-priority`` on real service processes: the threads run under SCHED_FIFO
(read back from the kernel), Zenoh's with the event loop, and the error when the system
does not permit it."""

from __future__ import annotations

import contextlib
import os
import shutil
import subprocess
import sys
from collections.abc import Callable, Sequence

import pytest

from aiobt.msgs import ComputePathToPose, PoseStamped
from aiobt.testing.bus import ServiceProcess, free_endpoint, port_of, spawn_service, wait_port
from aiobt.transport import Bus, BusSettings, open_bus

from ..services import TRUTH, common, up

pytestmark = [pytest.mark.integration, pytest.mark.timeout(120)]
Spawn = Callable[[Sequence[str]], ServiceProcess]
ZENOH_THREADS = ("rx-", "tx-", "net-", "app-", "acc-")  # Zenoh's own (tokio) threads


def fifo_permitted() -> bool:
    probe = "import os; os.sched_setscheduler(0, os.SCHED_FIFO, os.sched_param(1))"
    return (
        subprocess.run([sys.executable, "-c", probe], capture_output=True, timeout=30).returncode
        == 0
    )


needs_fifo = pytest.mark.skipif(
    not hasattr(os, "sched_setscheduler") or not fifo_permitted(),
    reason="SCHED_FIFO not permitted here (needs root or CAP_SYS_NICE)",
)


def threads(pid: int) -> dict[int, tuple[str, int, int]]:
    """Each thread of ``pid``: its name, scheduling policy and priority (from the kernel)."""
    out = {}
    for name in os.listdir(f"/proc/{pid}/task"):
        tid = int(name)
        with open(f"/proc/{pid}/task/{tid}/comm") as comm:
            out[tid] = (
                comm.read().strip(),
                os.sched_getscheduler(tid),
                os.sched_getparam(tid).sched_priority,
            )
    return out


@needs_fifo
async def test_the_event_loop_zenohs_threads_and_the_threads_it_starts_run_fifo(
    spawn: Spawn, bus: Bus, bus_settings: BusSettings
) -> None:
    robot = spawn(["-m", "aiobt_services.robot", "--speed", "2", "--realtime-priority",
                   *TRUTH, *common(bus_settings)])  # fmt: skip
    planner = spawn(["-m", "aiobt_services.planner", "--realtime-priority", *common(bus_settings)])
    controller = spawn(["-m", "aiobt_services.controller", "--sim-time", "--realtime-priority",
                        "80", *common(bus_settings)])  # fmt: skip
    navigator = spawn(["-m", "aiobt_services.navigator", "--sim-time", "--realtime-priority",
                       *common(bus_settings)])  # fmt: skip
    raised = (("robot", robot, 90), ("planner", planner, 70), ("controller", controller, 80),
              ("navigator", navigator, 60))  # fmt: skip
    for name, proc, _ in raised:
        await up(bus, name, proc)
    before = threads(planner.pid)
    client = bus.action_client("compute_path_to_pose", ComputePathToPose)
    for _ in range(100):  # until the planner has the map and the robot's pose (bounded)
        sent = await client.send_goal(
            ComputePathToPose.Goal(goal=PoseStamped.from_xy_yaw(4.0, 9.75, 0.0)),
            server_timeout=10.0,
        )
        result = await sent.result(timeout=20.0)
        if result.error_code == 0:
            break
    assert result.error_code == 0, result.error_msg

    for _, proc, level in raised:
        seen = threads(proc.pid)
        assert seen[proc.pid][1:] == (os.SCHED_FIFO, level), (proc.args, seen)  # the loop's
        zenoh = [t for t in seen.values() if t[0].startswith(ZENOH_THREADS)]
        assert zenoh, seen
        # the threads that deliver the robot's state to the loop: not left behind it
        assert all(t[1:] == (os.SCHED_FIFO, level) for t in zenoh), seen
        assert f"real-time priority {level} (SCHED_FIFO)" in proc.output()
    # the searches ran in threads the loop started after it was raised: they inherit it
    started = {tid: t for tid, t in threads(planner.pid).items() if tid not in before}
    assert (os.SCHED_FIFO, 70) in [t[1:] for t in started.values()], (before, started)


@needs_fifo
@pytest.mark.skipif(shutil.which("setpriv") is None, reason="needs setpriv (util-linux)")
def test_without_the_right_the_service_stops_with_an_error_naming_the_fix(
    bus_settings: BusSettings,
) -> None:
    command = ["setpriv", "--bounding-set", "-sys_nice", sys.executable, "-m",
               "aiobt_services.planner", "--realtime-priority", *common(bus_settings)]  # fmt: skip
    done = subprocess.run(command, capture_output=True, text=True, timeout=60)
    assert done.returncode == 1, done.stderr
    assert "planner: --realtime-priority 70: not permitted to use SCHED_FIFO" in done.stderr
    assert "CAP_SYS_NICE" in done.stderr
    assert "planner up" not in done.stderr


@needs_fifo
async def test_the_router_runs_fifo_with_all_its_threads_and_carries_messages() -> None:
    endpoint = free_endpoint()
    # without numpy's BLAS pool, which starts at import, before any option is read
    router = spawn_service(["-m", "aiobt.cli.router", "--listen", endpoint,
                            "--realtime-priority"], env={"OPENBLAS_NUM_THREADS": "1"})  # fmt: skip
    try:
        assert wait_port(port_of(endpoint), 30.0), router.output()
        settings = BusSettings(mode="client", connect=(endpoint,), namespace="rt",
                               connect_timeout=10.0)  # fmt: skip
        async with open_bus(settings) as one, open_bus(settings) as two:
            heard = two.latest("probe", PoseStamped)
            publisher = one.publisher("probe", PoseStamped)
            for _ in range(100):  # until the subscription is matched (bounded)
                publisher.put(PoseStamped.from_xy_yaw(1.0, 2.0, 0.0))
                with contextlib.suppress(TimeoutError):
                    await heard.wait_latest(0.1)
                    break
            got = heard.get()
            assert got is not None, "nothing carried through the router"
            assert got.x == 1.0
        seen = threads(router.pid)
        assert [t for t in seen.values() if t[0].startswith(ZENOH_THREADS)], seen
        # every thread: Zenoh's, and the reader of its log lines (refused sessions)
        assert all(t[1:] == (os.SCHED_FIFO, 60) for t in seen.values()), seen
        assert router.wait_for_output("real-time priority 60 (SCHED_FIFO)", 10.0), router.output()
    finally:
        router.cleanup()


@needs_fifo
@pytest.mark.skipif(shutil.which("setpriv") is None, reason="needs setpriv (util-linux)")
def test_a_router_without_the_right_stops_with_the_error() -> None:
    command = ["setpriv", "--bounding-set", "-sys_nice", sys.executable, "-m", "aiobt.cli.router",
               "--listen", "tcp/127.0.0.1:0", "--realtime-priority", "55"]  # fmt: skip
    done = subprocess.run(command, capture_output=True, text=True, timeout=60)
    assert done.returncode == 1, done.stderr
    assert "router: --realtime-priority 55: not permitted to use SCHED_FIFO" in done.stderr
    assert "listening" not in done.stderr
