"""``aiobt demo``: the main job, on the real system.

Brings the whole system up at a sim speed-up (router, robot, planner,
controller, behaviors, navigator: the processes of ``aiobt up``), then patrols
four goals of the small world through the navigator; the third starts with
the robot walled in by boxes, so no path exists until the navigator's first
recovery (then the boxes are taken away, see :mod:`aiobt.demo.boxes`). Progress
shows goal k of n, distance remaining and recoveries; at the end a PNG (map,
inflated costmap, planned paths, the driven tracks as estimated and in truth, goals,
recoveries) is
written to the path it prints. The services' output goes to a log file next
to it. Exit status 0 only when every goal was reached.
"""

from __future__ import annotations

import argparse
import asyncio
import logging
import sys
from pathlib import Path
from typing import TextIO

from aiobt.demo.mission import PATROL, Patrol
from aiobt.demo.picture import render
from aiobt.demo.record import Leg, Record
from aiobt.display import plural
from aiobt.embed import Feedback, connect
from aiobt.system import ConfigError, Fatal, SystemConfig, load_config, run_system
from aiobt.transport import BusSettings
from aiobt.transport.endpoints import free_endpoint

HEALTH_TIMEOUT = 60.0  # s of wall time for every service to come up


def add_arguments(parser: argparse.ArgumentParser) -> None:
    add = parser.add_argument
    add("--speed", type=float, default=2.0, help="sim speed-up (default: %(default)s)")
    add("--out", default="out/demo", metavar="DIR", help="PNG and log (default: %(default)s)")
    add("--listen", metavar="ENDPOINT", help="the router's (default: a free loopback port)")
    add(
        "--no-safety-chain",
        dest="safety_chain",
        action="store_false",
        help="without the velocity smoother and the collision monitor between the commands "
        "and the base (they run by default)",
    )


class FileSink:
    """The services' output into a log file; a crash or restart also on the terminal."""

    def __init__(self, log: TextIO, out: TextIO) -> None:
        self.log = log
        self.out = out

    def line(self, name: str, text: str) -> None:
        self.log.write(f"{name:>10} | {text}\n")

    def event(self, name: str, text: str) -> None:
        self.log.write(f"{name:>10} * {text}\n")
        self.log.flush()
        # crashes and restarts reach the terminal; coming up and a slow stop at the end
        # (killed after its grace) are the log's
        if text != "up" and not text.startswith("did not stop within"):
            self.out.write(f"  [{name}] {text}\n")


class StoryLines(logging.Handler):
    """The demo's own log lines (``aiobt.demo``: the boxes put in the robot's way and
    taken away, a path not drawn) as lines of its output, between the progress lines."""

    def __init__(self, out: TextIO) -> None:
        super().__init__(logging.INFO)
        self.out = out
        self.live = out.isatty()

    def emit(self, record: logging.LogRecord) -> None:
        warning = "warning: " if record.levelno >= logging.WARNING else ""
        text = f"  {warning}{record.getMessage()}"
        self.out.write(f"\r{text:<90}\n" if self.live else f"{text}\n")
        self.out.flush()

    def attach(self) -> None:
        story = logging.getLogger("aiobt.demo")
        story.setLevel(logging.INFO)
        story.propagate = False  # not also as a log record on stderr
        story.addHandler(self)


class ProgressLine:
    def __init__(self, out: TextIO) -> None:
        self.out = out
        self.live = out.isatty()

    def __call__(self, number: int, leg: Leg, feedback: Feedback) -> None:
        if not self.live:
            return
        distance, recoveries = feedback.distance_remaining, feedback.number_of_recoveries
        text = (
            f"\r  goal {number + 1}/{len(PATROL)} {leg.name}: "
            f"{distance:5.2f} m to go, {plural(recoveries, 'recovery')}"
        )
        self.out.write(f"{text:<90}")
        self.out.flush()

    def done(self, number: int, leg: Leg) -> None:
        mark = "reached" if leg.reached else f"NOT reached ({leg.result})"
        prefix = "\r" if self.live else ""
        line = (
            f"{prefix}  goal {number + 1}/{len(PATROL)} {leg.name}: {mark} "
            f"in {leg.seconds:.1f} s sim, {plural(leg.recoveries, 'recovery')}"
        )
        self.out.write(f"{line:<90}\n")
        self.out.flush()


async def demo(config: SystemConfig, out_dir: Path, out: TextIO) -> int:
    record = Record()
    progress = ProgressLine(out)
    StoryLines(out).attach()
    with (out_dir / "services.log").open("w") as log:
        async with run_system(config, FileSink(log, out)) as system:
            down = await system.wait_healthy(HEALTH_TIMEOUT)
            if down:
                out.write(f"aiobt demo: not up after {HEALTH_TIMEOUT:g} s: {', '.join(down)}\n")
                return 1
            out.write(f"system up (services' output in {out_dir / 'services.log'})\n")
            settings = BusSettings(connect=(config.router.listen,), namespace=config.namespace)
            async with connect(settings=settings, sim_time=True, server_timeout=30.0) as robot:
                patrol = Patrol(robot, record, progress)
                patrol.attach()
                for number, leg in enumerate(patrol.legs):
                    await patrol.drive(number, leg)
                    progress.done(number, leg)
    picture = out_dir / "patrol.png"
    title = f"aiobt demo: a patrol of {len(PATROL)} goals, small world, sim at x{config.speed:g}"
    picture.write_bytes(render(record, title=title))
    reached = sum(leg.reached for leg in record.legs)
    recoveries = sum(leg.recoveries for leg in record.legs)
    total = len(record.legs)
    recovered = plural(recoveries, "recovery")
    if record.tracking.pairs:  # in the simulation: the estimate against the truth
        out.write(f"{record.tracking.summary()}\n")
    out.write(f"{reached} of {total} goals reached, {recovered}; picture: {picture}\n")
    return 0 if reached == len(record.legs) else 1


def run(args: argparse.Namespace) -> int:
    listen = args.listen or free_endpoint()
    try:
        config = load_config(
            None,
            {
                "world": "small",
                "speed": args.speed,
                "router": {"listen": listen},
                "safety_chain": args.safety_chain,
            },
        )
    except ConfigError as exc:
        print(f"aiobt demo: {exc}", file=sys.stderr)
        return 2
    print(f"aiobt demo: the whole system at x{config.speed:g} sim speed, {len(PATROL)} goals")
    out_dir = Path(args.out)
    out_dir.mkdir(parents=True, exist_ok=True)
    try:
        return asyncio.run(demo(config, out_dir, sys.stdout))
    except Fatal as exc:
        print(f"aiobt demo: {exc}", file=sys.stderr)
        return 1
