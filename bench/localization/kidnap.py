"""The kidnapped robot, in process and seeded: the simulation (pybullet stepped by
hand, the lidar ray-cast against the office world's walls, odometry with its
default error) drives the filter's own logic (:class:`Amcl`, no transport), and
the simulation's truth judges it.

Run: ``.venv/bin/python -m bench.localization.kidnap [--trials 20] [--seed 1]
[--params sim_robot|nav2] [--set NAME=VALUE ...] [--trace N | --corridor S [--gone]]``

Each trial: the robot at a seeded free pose, the filter given it (initial pose);
it wanders by its own lidar for 2 m, then the simulation moves it 3 m (a seeded
direction, to a free pose, through walls if need be) without telling the
filter, and it wanders on for 30 s of sim time. Success: the estimate within
0.25 m of the truth within those 30 s (issue 33). Per trial: sim seconds and
filter updates until back, the error at the end, the tracking error before the
kidnap and once back, and the particle count after it. A control run of each
seed without the kidnap gives the tracking error and particle count of a
filter that was never lost, so a recovery setting that costs tracking shows.

``--corridor S``: the other side of the trade, the robot never lost: S sim
seconds back and forth along the corridor past seven boxes that are not on the
map (each seed); the worst error and the most particles show whether the
recovery drew random particles and moved the estimate away, and the largest
long-beam share (``recovery_min_long_beams``'s gate) how near it came to it.
``--gone`` turns it round: the boxes on the filter's map and not in the world.

``--trace N`` prints trial N's recovery averages, the gate's last long-beam share
and the particle count at every scan (what :mod:`bench/localization/README.md`
explains failures with).
"""

from __future__ import annotations

import argparse
import math
import statistics
import time
from dataclasses import dataclass, field

import numpy as np

from aiobt.geometry import Pose2D
from aiobt_services.localization.amcl import Amcl
from aiobt_services.localization.likelihood_field import LikelihoodField
from aiobt_services.localization.params import AmclParams
from aiobt_services.robot.obstacles import ObstacleSpec
from aiobt_services.robot.sim import Simulation

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

KIDNAP_M = 3.0
FOUND_M = 0.25
AFTER_S = 30.0


@dataclass(slots=True)
class Trial:
    """One seeded trial's figures (``nan``: never back)."""

    back_s: float = math.nan
    back_updates: float = math.nan
    end_error: float = math.nan
    before_rms: float = math.nan  # tracking before the kidnap (or the whole control run)
    after_rms: float = math.nan  # tracking from back to the end
    particles_mean: float = math.nan
    particles_max: int = 0
    trace: list[str] = field(default_factory=list)

    @property
    def ok(self) -> bool:
        return not math.isnan(self.back_s)


def _rms(errors: list[float]) -> float:
    return math.sqrt(sum(e * e for e in errors) / len(errors)) if errors else math.nan


def trial(seed: int, params: str, *, kidnap: bool = True, trace: bool = False) -> Trial:
    """One run; ``kidnap=False`` is its control (the same drive, never moved)."""
    rng = np.random.default_rng(1000 + seed)
    out = Trial()
    with _sim(seed) as sim:
        p = _params(params, seed)
        amcl = Amcl(p)
        amcl.set_map(_field(sim, p))
        start = _free_pose(sim, rng)
        sim.teleport(start)
        amcl.initialize(amcl.check_pose(start.x, start.y, start.yaw))
        drive = Driver(sim, amcl)
        before: list[float] = []
        while drive.driven < 2.0 and sim.time < 30.0:
            drive.step()
            if sim.steps % STEPS_PER_SCAN == 0:
                before.append(drive.error()[0])
        out.before_rms = _rms(before[len(before) // 2 :])  # once settled on the start
        target = _free_pose(sim, rng, near=sim.true_pose)
        if kidnap:
            sim.teleport(target)
        kidnapped, updates, after, counts = sim.time, drive.updates, [], []
        while sim.time - kidnapped < AFTER_S:
            drive.step()
            if sim.steps % STEPS_PER_SCAN:
                continue
            error = drive.error()[0]
            counts.append(len(amcl.particles))
            if trace:
                out.trace.append(_trace_line(sim.time - kidnapped, error, amcl))
            if out.ok:
                after.append(error)
            elif error < FOUND_M:
                out.back_s, out.back_updates = sim.time - kidnapped, drive.updates - updates
        out.end_error = drive.error()[0]
        out.after_rms = _rms(after)
        out.particles_mean = statistics.fmean(counts)
        out.particles_max = max(counts)
        if not kidnap:
            out.before_rms = _rms(before[len(before) // 2 :] + after)
    return out


BOXES = [(5.0, 10.4), (7.0, 9.1), (9.0, 10.4), (11.0, 9.1), (13.0, 10.4), (6.0, 9.2), (8.5, 10.5)]
CORRIDOR_Y = 9.75


def _map_with_boxes(sim: Simulation, p: AmclParams) -> LikelihoodField:
    """The filter's field with :data:`BOXES` drawn on its map (0.6 m squares)."""
    w = sim.world
    grid = w.grid.copy()
    for x, y in BOXES:
        c0, r0 = (int((x - 0.3 - w.origin[0]) / w.resolution),
                  int((y - 0.3 - w.origin[1]) / w.resolution))  # fmt: skip
        size = round(0.6 / w.resolution)
        grid[r0 : r0 + size, c0 : c0 + size] = 100
    return LikelihoodField.build(grid, w.resolution, (w.origin[0], w.origin[1]),
                                 max_dist=p.laser_likelihood_max_dist, z_hit=p.z_hit,
                                 sigma_hit=p.sigma_hit)  # fmt: skip


def corridor(
    seed: int, params: str, seconds: float, *, gone: bool = False
) -> tuple[float, int, float]:
    """The worst error (m), the most particles and the largest share of long beams
    (:mod:`aiobt_services.localization.long_beams`, when the gate is on) over
    ``seconds`` of driving the corridor (x 3..15) back and forth past :data:`BOXES`,
    the filter never misled. ``gone``: the boxes are on the filter's map and not in
    the world (furniture moved away: beams longer than the map says from the
    right pose, which the long-beam gate cannot tell from a kidnap)."""
    with _sim(seed) as sim:
        p = _params(params, seed)
        amcl = Amcl(p)
        amcl.set_map(_map_with_boxes(sim, p) if gone else _field(sim, p))
        sim.teleport(Pose2D(2.0, CORRIDOR_Y, 0.0))
        amcl.initialize(amcl.check_pose(2.0, CORRIDOR_Y, 0.0))
        for i, (x, y) in enumerate([] if gone else BOXES):
            sim.spawn(ObstacleSpec(f"box{i}", "box", Pose2D(x, y, 0.3), size_x=0.6, size_y=0.6))
        drive, heading, worst, most, long = Driver(sim, amcl), 0.0, 0.0, 0, 0.0
        while sim.time < seconds:
            t = sim.true_pose
            heading = math.pi if t.x > 15.0 else 0.0 if t.x < 3.0 else heading
            turn = math.remainder(heading - t.yaw, math.tau)
            across = (t.y - CORRIDOR_Y) * math.cos(heading)
            if abs(turn) > 0.5:
                drive.step(0.0, math.copysign(0.8, turn))
            else:
                drive.step(0.4, max(-0.5, min(0.5, turn - 1.5 * across)))
            if sim.steps % STEPS_PER_SCAN == 0 and sim.time > 3.0:
                worst, most = max(worst, drive.error()[0]), max(most, len(amcl.particles))
                long = max(long, amcl.long_beams)
        return worst, most, long


def _trace_line(after: float, error: float, amcl: Amcl) -> str:
    r = amcl.recovery
    return (f"{after:5.1f} s  error {error:6.2f} m  w_slow {r.w_slow:.3f} w_fast "
            f"{r.w_fast:.3f} w_diff {r.w_diff:.3f}  long beams {amcl.long_beams:.2f}  "
            f"particles {len(amcl.particles)}")  # fmt: skip


def _print(kind: str, runs: list[Trial]) -> None:
    back = [r.back_s for r in runs if r.ok]
    figures = f"; median {statistics.median(back):.1f} s, worst {max(back):.1f} s" if back else ""
    print(f"\n{kind}: back within {FOUND_M} m in {AFTER_S:.0f} s: {len(back)}/{len(runs)}{figures}")
    print(
        "| trial | back after sim s | updates | error at end m | tracking before / after "
        "RMS m | particles mean / max |\n|---|---|---|---|---|---|"
    )
    for i, r in enumerate(runs, 1):
        print(f"| {i} | {r.back_s:.1f} | {r.back_updates:.0f} | {r.end_error:.2f} | "
              f"{r.before_rms:.3f} / {r.after_rms:.3f} | {r.particles_mean:.0f} / "
              f"{r.particles_max} |")  # fmt: skip


def _control(runs: list[Trial]) -> None:
    rms = [r.before_rms for r in runs]
    mean = statistics.fmean(r.particles_mean for r in runs)
    print(f"\ncontrol (no kidnap): tracking RMS median {statistics.median(rms):.3f} m, worst "
          f"{max(rms):.3f} m; worst end error {max(r.end_error for r in runs):.2f} m; "
          f"particles mean {mean:.0f}, max {max(r.particles_max for r in runs)}")  # fmt: skip


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__)
    trial_arguments(parser, trials=20)
    parser.add_argument("--trace", type=int, default=0, metavar="N", help="trace trial N")
    parser.add_argument("--corridor", type=float, default=0.0, metavar="S",
                        help="only the corridor drive past boxes, S sim s per seed")  # fmt: skip
    parser.add_argument("--gone", action="store_true",
                        help="with --corridor: the boxes on the map, not in the world")  # fmt: skip
    args = parser.parse_args()
    apply_sets(args.set)
    began = time.monotonic()
    seeds = [args.seed + i for i in range(args.trials)]
    if args.corridor:
        for seed in seeds:
            worst, most, long = corridor(seed, args.params, args.corridor, gone=args.gone)
            print(f"corridor seed {seed}: worst error {worst:.2f} m, most particles {most}, "
                  f"long beams at most {long:.2f}")  # fmt: skip
        print(f"({time.monotonic() - began:.0f} s wall, params {args.params}, set {args.set})")
        return
    runs = [trial(s, args.params, trace=args.trace == i) for i, s in enumerate(seeds, 1)]
    _print("kidnap", runs)
    _control([trial(s, args.params, kidnap=False) for s in seeds])
    for line in runs[args.trace - 1].trace if args.trace else []:
        print(line)
    print(f"\n({time.monotonic() - began:.0f} s wall, params {args.params}, set {args.set})")


if __name__ == "__main__":
    main()
