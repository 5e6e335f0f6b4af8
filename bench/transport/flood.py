"""A 10,000 messages/s flood on topics the services subscribe to: their other work, flooded
against unflooded, in one run.

Run: ``.venv/bin/python -m bench.transport.flood [--seconds 5] [--speed 4] [--repeat 1]``

A router, the robot (small world, ``--speed``) and the planner as processes on
loopback. For each flood, the service is called back to back for ``--seconds``
unflooded (calm), then for ``--seconds`` while ``aiobt.testing.flood_proc``
publishes 10,000 messages/s on the topic from another process (flooded):

- robot, ``initialpose`` and ``cmd_vel``: ``sim/srv/obstacles/list`` service replies and
  the sim speed-up (sim seconds on ``{ns}/clock`` per wall second);
- planner, ``pose``: ``is_path_valid`` replies;
- control: the same flood on ``flood_sink``, a key only a third process
  (``bench.transport.flood_sink``) subscribes to, while the robot is measured:
  what the flood costs the robot through the machine alone (flooder, router
  and sink on the same 2 cores), not through its subscriptions.

Reports per flood the ratios flooded / calm of the speed-up and of the median
reply, the median reply against the same service's under the control flood
(flooded / control: what the subscription itself costs), the largest reply,
the RSS growth of the flooded process, and the messages sent; the target
(issue 14) is the other work within 10 % of normal and memory flat. The
flooder and the router are on the same 2 cores as the service: their CPU is
part of what a flood costs the machine, hence the control.
"""

from __future__ import annotations

import argparse
import asyncio
import contextlib
import os
import uuid
from collections.abc import Iterator, Sequence

from aiobt.msgs import Clock, Empty, Header, IsPathValid, Path, PoseStamped
from aiobt.msgs.sim import ObstacleList
from aiobt.testing.bus import ServiceProcess, exit_on_sigterm, running_router, spawn_service
from aiobt.testing.flood import MIB, Call, Figures, Flood, flood_and_measure
from aiobt.transport import Bus, BusSettings, open_bus
from aiobt.transport.keys import sim_namespace

TRUTH = ("--pose-source", "truth")  # the robot's {ns}/pose is the truth (no localization)

POSE = '{"x": 0.5, "y": 0.5, "yaw": 0.0}'
SINK = Flood("flood_sink", "PoseStamped", POSE)


@contextlib.contextmanager
def processes() -> Iterator[list[ServiceProcess]]:
    started: list[ServiceProcess] = []
    try:
        yield started
    finally:
        for proc in started:
            proc.cleanup()


async def start(spawn: list[ServiceProcess], bus: Bus, argv: Sequence[str], name: str) -> int:
    proc = spawn_service(argv)
    spawn.append(proc)
    if not await bus.presence(bus.keys.topic(f"nodes/{name}")).wait(60.0):
        raise SystemExit(f"{name} did not come up:\n{proc.output()}")
    return proc.pid


def row(name: str, calm: Figures, flooded: Figures, sent: int, control: float) -> str:
    """A table row; ``control``: the median reply of the same service under the control
    flood (0 for the control itself)."""
    speed = f"{flooded.speed / calm.speed:.2f}" if calm.speed else "-"
    versus = f"{flooded.reply_median / control:.2f}" if control else "-"
    return (
        f"| {name} | {sent} | {speed} | {calm.reply_median * 1e3:.1f} | "
        f"{flooded.reply_median * 1e3:.1f} | {flooded.reply_median / calm.reply_median:.2f} | "
        f"{versus} | {flooded.reply_max * 1e3:.0f} | {flooded.rss_growth / MIB:.1f} |"
    )


async def run(args: argparse.Namespace) -> None:
    with running_router() as (_, endpoint), processes() as started:
        settings = BusSettings(connect=(endpoint,), namespace=f"flood{uuid.uuid4().hex[:6]}")
        where = ["--connect", endpoint, "--namespace", settings.namespace]

        def spawn(argv: Sequence[str]) -> ServiceProcess:
            proc = spawn_service(argv)
            started.append(proc)
            return proc

        async with open_bus(settings) as bus:
            # the planner's start without localization: the robot's pose is the truth's
            robot_argv = ["-m", "aiobt_services.robot", *where, "--world", "small", *TRUTH]
            robot = await start(started, bus, [*robot_argv, "--speed", str(args.speed)], "robot")
            planner = await start(started, bus, ["-m", "aiobt_services.planner", *where], "planner")
            clock = bus.subscribe("clock", Clock, queue_size=1)
            sink = spawn(["-m", "bench.transport.flood_sink", *where])
            if not await asyncio.to_thread(sink.wait_for_output, "ready", 30.0):
                raise SystemExit(f"the flood sink did not start:\n{sink.output()}")

            async def obstacles() -> object:
                return await bus.call("obstacles/list", Empty(), ObstacleList, timeout=20.0,
                                      namespace=sim_namespace(bus.namespace))  # fmt: skip

            path = Path(header=Header(frame_id="map"), poses=[
                PoseStamped.from_xy_yaw(0.0, 0.0, 0.0), PoseStamped.from_xy_yaw(1.0, 0.5, 0.0)
            ])  # fmt: skip
            request = IsPathValid.Request(path=path)

            async def valid() -> object:
                name = IsPathValid.service_name
                return await bus.call(name, request, IsPathValid.Response, timeout=20.0)

            cases: list[tuple[str, Flood, Call, bool, int]] = [
                ("control: robot, flood on flood_sink", SINK, obstacles, True, robot),
                ("control: planner, flood on flood_sink", SINK, valid, False, planner),
                ("robot, initialpose", Flood("initialpose", "PoseStamped", POSE), obstacles, True,
                 robot),
                ("robot, cmd_vel", Flood("cmd_vel", "Twist", "{}"), obstacles, True, robot),
                ("planner, pose", Flood("pose", "PoseStamped", POSE), valid, False, planner),
            ]  # fmt: skip
            for _ in range(args.repeat):
                control: dict[int, float] = {}  # pid -> median reply under the control flood
                for name, flood, call, sim, pid in cases:
                    calm, flooded, sent = await flood_and_measure(
                        spawn, settings, flood, call, clock if sim else None, pid, args.seconds
                    )
                    if flood is SINK:
                        control[pid] = flooded.reply_median
                    versus = control[pid] if flood is not SINK else 0.0
                    print(row(name, calm, flooded, sent, versus), flush=True)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--seconds", type=float, default=5.0, help="length of each phase")
    parser.add_argument("--speed", type=float, default=4.0, help="the robot's sim speed-up")
    parser.add_argument("--repeat", type=int, default=1, help="rounds of the three floods")
    exit_on_sigterm()
    args = parser.parse_args()
    before = os.getloadavg()
    print(
        "| flood (10,000 msg/s) | sent | speed-up flooded/calm | reply calm ms | "
        "reply flooded ms | flooded/calm | flooded/control | reply max ms | RSS growth MiB |\n"
        "|---|---|---|---|---|---|---|---|---|",
        flush=True,
    )
    asyncio.run(run(args))
    print(f"load average before {before}, after {os.getloadavg()}")


if __name__ == "__main__":
    main()
