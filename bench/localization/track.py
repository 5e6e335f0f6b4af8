"""Tracking, in process and seeded: the filter given the true start pose, the robot
wandering by its own lidar (:class:`.relocalize.Driver`: 0.4 m/s, turning away
from walls) for ``--seconds`` of sim time, the estimate judged against the truth
at every scan; and the CPU of each filter update (thread time of
``Amcl.on_scan``).

Run: ``.venv/bin/python -m bench.localization.track [--trials 10] [--seconds 120]
[--params sim_robot|nav2] [--set NAME=VALUE ...]``

Per seed and over all: position error RMS, p99 and max, heading RMS (the first 5
sim s left out: the initial pose's spread), updates, particles (mean), CPU per
update p50 / p99 / mean, and the updates' CPU per sim second (the share of a core
the filter's own work takes at 1x, without the service's messaging). ``--set
min_particles=2000 --set max_particles=2000`` holds the filter at 2,000 particles
(the issue's cost case: 2,000 x 60 beams).
"""

from __future__ import annotations

import argparse
import math
import statistics
import time

import numpy as np

from aiobt_services.localization.amcl import Amcl, ScanOutcome
from aiobt_services.localization.laser_model import Beams
from aiobt_services.localization.params import AmclParams
from aiobt_services.localization.se2 import FloatArray

from .relocalize import (
    STEPS_PER_SCAN,
    Driver,
    _field,
    _free_pose,
    _params,
    _sim,
    apply_sets,
    trial_arguments,
)

SETTLE_S = 5.0


class _Timed(Amcl):
    """:class:`Amcl` that records each update's thread time."""

    def __init__(self, params: AmclParams) -> None:
        super().__init__(params)
        self.cpu: list[float] = []

    def on_scan(self, odom_pose: FloatArray, beams: Beams) -> ScanOutcome:
        start = time.thread_time()
        outcome = super().on_scan(odom_pose, beams)
        if outcome.updated:
            self.cpu.append(time.thread_time() - start)
        return outcome


def trial(seed: int, params: str, seconds: float) -> tuple[np.ndarray, list[float], list[int]]:
    """(errors: rows position, heading; CPU per update; particle counts)."""
    rng = np.random.default_rng(2000 + seed)
    with _sim(seed) as sim:
        p = _params(params, seed)
        amcl = _Timed(p)
        amcl.set_map(_field(sim, p))
        start = _free_pose(sim, rng)
        sim.teleport(start)
        amcl.initialize(amcl.check_pose(start.x, start.y, start.yaw))
        drive, errors, counts = Driver(sim, amcl), [], []
        while sim.time < seconds:
            drive.step()
            if sim.steps % STEPS_PER_SCAN == 0 and sim.time > SETTLE_S:
                errors.append(drive.error())
                counts.append(len(amcl.particles))
        return np.array(errors), amcl.cpu, counts


def _line(
    name: str, errors: np.ndarray, cpu: list[float], counts: list[int], seconds: float
) -> str:
    dist, heading = errors[:, 0], errors[:, 1]
    ms = np.array(cpu) * 1e3
    return (
        f"| {name} | {100 * math.sqrt(float(np.mean(dist**2))):.1f} | "
        f"{100 * float(np.percentile(dist, 99)):.1f} | {100 * float(dist.max()):.1f} | "
        f"{math.degrees(math.sqrt(float(np.mean(heading**2)))):.2f} | {len(cpu)} | "
        f"{statistics.fmean(counts):.0f} | {np.percentile(ms, 50):.2f} / "
        f"{np.percentile(ms, 99):.2f} / {np.mean(ms):.2f} | {100 * sum(cpu) / seconds:.1f} |"
    )


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__)
    trial_arguments(parser, trials=10)
    parser.add_argument("--seconds", type=float, default=120.0, help="sim s per seed")
    args = parser.parse_args()
    apply_sets(args.set)
    began = time.monotonic()
    print("| seed | position RMS cm | p99 cm | max cm | heading RMS deg | updates | "
          "particles | CPU per update p50 / p99 / mean ms | % of a core at 1x |")  # fmt: skip
    print("|---|---|---|---|---|---|---|---|---|")
    errors, cpu, counts = [], [], []
    for seed in range(args.seed, args.seed + args.trials):
        e, c, n = trial(seed, args.params, args.seconds)
        print(_line(str(seed), e, c, n, args.seconds))
        errors.append(e)
        cpu += c
        counts += n
    print(_line("all", np.vstack(errors), cpu, counts, args.seconds * args.trials))
    print(f"\n({time.monotonic() - began:.0f} s wall, params {args.params}, set {args.set})")


if __name__ == "__main__":
    main()
