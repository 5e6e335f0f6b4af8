"""Steps/s and real-time factor of the default world, robot driving, lidar at 10 Hz.

Run: ``.venv/bin/python -m bench.robot.sim_speed [--seconds 60]``

Three runs in one process, same world, same sim duration:
- ``physics only``: bare ``stepSimulation`` on the world (walls + robot), the
  floor no simulator can beat: the baseline of the ratios;
- ``sim``: :class:`Simulation` stepping with the robot wandering (velocity
  limits, odometry, battery, bumper), no publication;
- ``service loop``: :class:`SimRunner` as the service runs it, robot wandering,
  odom/pose at 50 Hz, lidar at 10 Hz, battery, clock at 100 Hz, every message
  built and serialised to JSON (what goes to Zenoh), single-threaded.
"""

from __future__ import annotations

import argparse
import math
import time
from collections.abc import Callable

import numpy as np
import numpy.typing as npt

from aiobt.msgs import LaserScan, Msg
from aiobt_services.robot.mapfile import load_map
from aiobt_services.robot.runner import SimRunner
from aiobt_services.robot.sim import Simulation
from aiobt_services.robot.worlds import OFFICE


class JsonSink:
    """Serialises every message as the Zenoh publisher would; hands scans to a listener."""

    def __init__(self, on_scan: Callable[[LaserScan], None]) -> None:
        self.count = 0
        self.bytes = 0
        self._on_scan = on_scan

    def publish(self, topic: str, msg: Msg) -> None:
        self.count += 1
        self.bytes += len(msg.to_json())
        if isinstance(msg, LaserScan):
            self._on_scan(msg)


class Wanderer:
    """Drive forward; turn away while something is close ahead (uses a 10 Hz scan)."""

    def __init__(self, sim: Simulation) -> None:
        self.sim = sim
        angles = sim.config.lidar.angles()
        self.front = np.abs(angles) < math.radians(35)
        self.turn = 0.0

    def on_scan(self, ranges: npt.NDArray[np.float64]) -> None:
        self.turn = 1.5 if np.min(ranges[self.front]) < 0.8 else 0.0

    def command(self) -> None:
        self.sim.command(0.0 if self.turn else 0.8, self.turn)


def physics_only(seconds: float) -> float:
    with Simulation(load_map(OFFICE)) as sim:
        step = sim._physics.call
        n = round(seconds / sim.config.dt)
        t0 = time.perf_counter()
        for _ in range(n):
            step("stepSimulation")
        return n / (time.perf_counter() - t0)


def sim_only(seconds: float) -> float:
    with Simulation(load_map(OFFICE)) as sim:
        wander = Wanderer(sim)
        n, every = round(seconds / sim.config.dt), round(0.1 / sim.config.dt)
        t0 = time.perf_counter()
        for i in range(n):
            if i % every == 0:
                wander.on_scan(sim.scan().ranges)
            wander.command()
            sim.step()
        return n / (time.perf_counter() - t0)


def service_loop(seconds: float) -> tuple[float, float, int]:
    with Simulation(load_map(OFFICE)) as sim:
        wander = Wanderer(sim)
        sink = JsonSink(lambda scan: wander.on_scan(scan.ranges_array()))
        runner = SimRunner(sim, sink)
        n = round(seconds / sim.config.dt)
        t0 = time.perf_counter()
        for _ in range(n):
            wander.command()  # reacts to the published 10 Hz scan, as a controller would
            runner.tick()
        rate = n / (time.perf_counter() - t0)
        travelled = sim.odometry.pose
        return rate, math.hypot(travelled.x, travelled.y), sink.count


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--seconds", type=float, default=60.0, help="sim seconds per run")
    args = parser.parse_args(argv)
    dt = 0.01
    base = physics_only(args.seconds)
    sim_rate = sim_only(args.seconds)
    loop_rate, moved, msgs = service_loop(args.seconds)
    print(f"world office (20 x 20 m), dt {dt} s, {args.seconds:g} s of sim time per run")
    print(f"{'run':<16}{'steps/s':>10}{'x real time':>13}{'vs physics':>12}")
    for name, rate in (("physics only", base), ("sim", sim_rate), ("service loop", loop_rate)):
        print(f"{name:<16}{rate:>10.0f}{rate * dt:>13.1f}{rate / base:>12.2f}")
    print(f"service loop: {msgs} messages serialised, odometry end {moved:.1f} m from start")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
