"""What the router's denial log costs: a mutual-TLS router with the access-control
rules, with its denial log (the default) and without (``--no-denial-log``), paired.

    python -m bench.deploy.denial_log --seconds 30 --pairs 3 [--busy 2] [--rates 4]
    python -m bench.deploy.denial_log --hold 8 --rates 4 --baseline-python ../main/.venv/bin/python

The denial log turns on Zenoh's access-control log at trace level: Zenoh writes a line
per message it routes, from its routing threads, into a pipe the router's Python
reader empties (``aiobt.transport.refusals``). Here the router
(``aiobt router --config router-robot.json5 --access-control deploy/access-control.json5``)
routes the robot host's streams between three sessions of this process, each with
its certificate: ``robot`` puts pose and odometry at 50 Hz, the scan at 10 Hz;
``controller`` subscribes to them and puts ``cmd_vel`` at 20 Hz; ``web`` subscribes
to all of it. Per run: the router's CPU (``/proc/<pid>/stat``, % of one core), and at
the controller each pose's latency (put to arrival, one clock) and the gaps between
poses (50 Hz: 20 ms apart when nothing holds them). ``--busy N``: N processes
spinning at ordinary priority for the whole run (a loaded machine, as
``bench.system.report --busy``). ``--rates K``: every stream K times as often (a
robot host routes more than these four streams, to more subscribers). The runs of a
pair alternate which goes first.

``--hold S``: the router's reader of Zenoh's log is held off the CPU for the first S
seconds of each run (:mod:`bench.deploy.held_reader`), both runs with the denial log;
the pair is this tree against ``--baseline-python``'s checkout (the code before: a
pipe, which the routing threads wait on once it is full), or without it the denial
log against none.
"""

from __future__ import annotations

import argparse
import asyncio
import statistics
import subprocess
import sys
import tempfile
import time
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from aiobt.deploy.certs import CertPlan, write_certs
from aiobt.deploy.zenoh_configs import write_configs
from aiobt.msgs import LaserScan, Odometry, PoseStamped, Twist
from aiobt.testing.bus import ServiceProcess, exit_on_sigterm, spawn_service
from aiobt.transport import Bus, BusSettings, open_bus
from aiobt.transport.endpoints import free_port
from bench.system.procstat import cpu_seconds
from bench.system.report import spin

REPO = Path(__file__).resolve().parents[2]
RULES = REPO / "deploy" / "access-control.json5"
POSE_HZ, SCAN_HZ, CMD_HZ = 50.0, 10.0, 20.0  # the robot's defaults, the controller's
BEAMS = 360


async def _every(period: float, put: object, stop: asyncio.Event) -> None:
    """Call ``put()`` every ``period`` s (on a fixed schedule) until ``stop``."""
    loop = asyncio.get_running_loop()
    due = loop.time()
    while not stop.is_set():
        put()  # type: ignore[operator]
        due += period
        await asyncio.sleep(max(0.0, due - loop.time()))


def _settings(certs: Path, name: str, endpoint: str) -> BusSettings:
    return BusSettings(
        connect=(endpoint,), config_file=str(certs / f"{name}.json5"), connect_timeout=20.0
    )


async def _load(
    certs: Path, endpoint: str, seconds: float, rates: float
) -> tuple[list[float], list[float]]:
    """The robot's streams for ``seconds``; the poses' latencies and arrival times (s)."""
    latencies: list[float] = []
    arrivals: list[float] = []

    def on_pose(pose: PoseStamped) -> None:
        now = time.monotonic()
        latencies.append(now - pose.header.stamp)
        arrivals.append(now)

    scan = LaserScan(
        angle_min=-3.14, angle_max=3.14, angle_increment=6.28 / BEAMS, range_min=0.1,
        range_max=12.0, ranges=[5.0] * BEAMS,
    )  # fmt: skip
    async with (
        open_bus(_settings(certs, "robot", endpoint)) as robot,
        open_bus(_settings(certs, "controller", endpoint)) as controller,
        open_bus(_settings(certs, "web", endpoint)) as web,
    ):
        _subscribe_all(web)
        controller.subscribe("pose", PoseStamped, callback=on_pose)
        controller.subscribe("odom", Odometry, callback=lambda _: None)
        controller.subscribe("scan", LaserScan, callback=lambda _: None)
        pose, odom = robot.publisher("pose", PoseStamped), robot.publisher("odom", Odometry)
        scans, cmd = robot.publisher("scan", LaserScan), controller.publisher("cmd_vel", Twist)
        stop = asyncio.Event()

        def put_pose() -> None:
            stamped = PoseStamped.from_xy_yaw(1.0, 2.0)
            stamped.header.stamp = time.monotonic()  # this process's clock: the latency
            pose.put(stamped)
            odom.put(Odometry())

        tasks = [
            asyncio.create_task(_every(1 / (rates * POSE_HZ), put_pose, stop)),
            asyncio.create_task(_every(1 / (rates * SCAN_HZ), lambda: scans.put(scan), stop)),
            asyncio.create_task(
                _every(1 / (rates * CMD_HZ), lambda: cmd.put(Twist.planar(0.3, 0.0)), stop)
            ),
        ]
        await asyncio.sleep(seconds)
        stop.set()
        await asyncio.gather(*tasks)
    return latencies, arrivals


def _subscribe_all(web: Bus) -> None:
    for name, model in (("pose", PoseStamped), ("odom", Odometry), ("scan", LaserScan),
                        ("cmd_vel", Twist)):  # fmt: skip
        web.subscribe(name, model, callback=lambda _: None)


@dataclass(frozen=True, slots=True)
class Variant:
    label: str
    denial_log: bool = True
    python: str = sys.executable  # a baseline checkout's, to run its router
    hold: float = 0.0  # s the router's log reader is held off at first


def _router(certs: Path, variant: Variant) -> tuple[ServiceProcess, str]:
    endpoint = f"tls/127.0.0.1:{free_port()}"
    args = ["--listen", endpoint, "--config", str(certs / "router-robot.json5"),
            "--access-control", str(RULES)]  # fmt: skip
    args += [] if variant.denial_log else ["--no-denial-log"]
    script = str(Path(__file__).with_name("held_reader.py"))
    program = [variant.python, script, *args]  # run by that Python (ServiceProcess: ours)
    launch = ["-c", f"import os; os.execv({variant.python!r}, {program!r})"]
    router = spawn_service(launch, env={"AIOBT_BENCH_HOLD": str(variant.hold)})
    if not router.wait_for_output("listening on", 30.0):
        router.cleanup()
        raise RuntimeError(f"the router did not start:\n{router.output()}")
    return router, endpoint


def run(certs: Path, variant: Variant, seconds: float, rates: float) -> dict[str, float]:
    router, endpoint = _router(certs, variant)
    try:
        cpu0, wall0 = cpu_seconds(router.pid), time.monotonic()
        latencies, arrivals = asyncio.run(_load(certs, endpoint, seconds, rates))
        cpu = 100.0 * (cpu_seconds(router.pid) - cpu0) / (time.monotonic() - wall0)
    finally:
        router.cleanup()
    lat = np.array(latencies[10:]) * 1e3  # ms; the first poses wait for the routes
    gaps = np.diff(np.array(arrivals[10:])) * 1e3
    return {
        "router CPU %": cpu,
        "poses": float(len(arrivals)),
        "latency p50 ms": float(np.percentile(lat, 50)),
        "latency p99 ms": float(np.percentile(lat, 99)),
        "latency max ms": float(lat.max()),
        "gap p99 ms": float(np.percentile(gaps, 99)),
        "gap max ms": float(gaps.max()),
    }


def _variants(args: argparse.Namespace) -> tuple[Variant, Variant]:
    if args.hold and args.baseline_python:
        return (
            Variant(f"this tree, reader held {args.hold:g} s", hold=args.hold),
            Variant(
                f"baseline, reader held {args.hold:g} s",
                python=args.baseline_python,
                hold=args.hold,
            ),
        )
    return (
        Variant("denial log", hold=args.hold),
        Variant("no denial log", denial_log=False, hold=args.hold),
    )


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--seconds", type=float, default=30.0)
    parser.add_argument("--pairs", type=int, default=3)
    parser.add_argument("--busy", type=int, default=0, help="processes spinning meanwhile")
    parser.add_argument("--rates", type=float, default=1.0, help="streams K times as often")
    parser.add_argument("--hold", type=float, default=0.0, help="s the log reader is held off")
    parser.add_argument("--baseline-python", default=None, help="a baseline checkout's Python")
    exit_on_sigterm()
    args = parser.parse_args()
    variants = _variants(args)
    busy: list[subprocess.Popen[bytes]] = [spin() for _ in range(args.busy)]
    results: dict[str, list[dict[str, float]]] = {v.label: [] for v in variants}
    try:
        with tempfile.TemporaryDirectory() as tmp:
            certs = Path(tmp)
            plan = CertPlan()
            write_certs(certs, plan)
            write_configs(certs, plan)
            for pair in range(args.pairs):
                for variant in variants if pair % 2 == 0 else variants[::-1]:
                    figures = run(certs, variant, args.seconds, args.rates)
                    results[variant.label].append(figures)
                    print(f"pair {pair + 1} {variant.label}: " + ", ".join(
                        f"{k} {v:.1f}" for k, v in figures.items()), flush=True)  # fmt: skip
    finally:
        for proc in busy:
            proc.kill()
            proc.wait()
    _summary(results)
    return 0


def _summary(results: dict[str, list[dict[str, float]]]) -> None:
    print("\nmin / median / max over the runs:")
    labels = list(results)
    print(f"  {'':16s} " + "   ".join(f"{label:>30s}" for label in labels))
    for key in results[labels[0]][0]:
        cells = []
        for label in labels:
            values = [r[key] for r in results[label]]
            cells.append(f"{min(values):.1f} / {statistics.median(values):.1f} / {max(values):.1f}")
        print(f"  {key:16s} " + "   ".join(f"{cell:>30s}" for cell in cells))


if __name__ == "__main__":
    sys.exit(main())
