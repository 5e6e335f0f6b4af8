"""Global localization, in process (the simulation and the
filter, no transport), seeded.

Run: ``.venv/bin/python -m bench.localization.relocalize [--trials 10] [--seed 1]
[--params sim_robot|nav2]``

- global: the robot at a seeded random free pose; ``reinitialize_global_localization``;
  one turn on the spot, then it wanders by its own lidar (forward at 0.4 m/s, turning
  away from anything within 0.7 m ahead) for at most 10 m. Success: the estimate
  within 0.25 m and 10 degrees at the end, and how far it had driven when it got
  there for good.
- kidnap: moved to :mod:`bench.localization.kidnap` (which reuses this module's
  simulation, driver and helpers).
"""

from __future__ import annotations

import argparse
import math
import time
from dataclasses import dataclass

import numpy as np
import yaml

from aiobt.geometry import Pose2D
from aiobt_services.localization import se2
from aiobt_services.localization.amcl import Amcl
from aiobt_services.localization.laser_model import select_beams
from aiobt_services.localization.likelihood_field import LikelihoodField
from aiobt_services.localization.options import CONFIG_DIR, read_params_file
from aiobt_services.localization.params import AmclParams
from aiobt_services.robot.mapfile import load_map
from aiobt_services.robot.options import add_robot_arguments, sim_config
from aiobt_services.robot.sim import PoseError, Simulation
from aiobt_services.robot.worlds import world_path

STEPS_PER_SCAN = 10  # 10 Hz scans at the 100 Hz physics step


@dataclass(slots=True)
class Run:
    ok: bool
    error: float
    heading_deg: float
    settled_at: float  # m driven when the estimate got there for good; nan: never


OVERRIDES: dict[str, object] = {}  # --set


def _params(name: str, seed: int) -> AmclParams:
    values = {} if name == "nav2" else read_params_file(CONFIG_DIR / f"{name}.yaml")
    return AmclParams.from_mapping({**values, **OVERRIDES, "random_seed": seed})


def _sim(seed: int) -> Simulation:
    parser = argparse.ArgumentParser()
    add_robot_arguments(parser)
    return Simulation(
        load_map(world_path("office")), sim_config(parser.parse_args(["--seed", str(seed)]))
    )


def _field(sim: Simulation, p: AmclParams) -> LikelihoodField:
    w = sim.world
    return LikelihoodField.build(w.grid, w.resolution, (w.origin[0], w.origin[1]),
                                 max_dist=p.laser_likelihood_max_dist, z_hit=p.z_hit,
                                 sigma_hit=p.sigma_hit)  # fmt: skip


def _free_pose(sim: Simulation, rng: np.random.Generator, near: Pose2D | None = None) -> Pose2D:
    for _ in range(10_000):
        if near is None:
            x, y = rng.uniform(0.5, 19.5, 2)
        else:
            a = rng.uniform(-math.pi, math.pi)
            x, y = near.x + 3.0 * math.cos(a), near.y + 3.0 * math.sin(a)
        pose = Pose2D(float(x), float(y), float(rng.uniform(-math.pi, math.pi)))
        try:
            sim.check_free(pose, sim.config.robot.radius + 0.3)
        except PoseError:
            continue
        return pose
    raise RuntimeError("no free pose found")


class Driver:
    """The robot, the filter and the error between them, stepped together."""

    def __init__(self, sim: Simulation, amcl: Amcl) -> None:
        self.sim, self.amcl = sim, amcl
        self.angles = sim.config.lidar.angles()
        self.driven = 0.0
        self.updates = 0  # scans that moved and weighed the particles
        self._turning = 0.0

    def step(self, linear: float | None = None, angular: float = 0.0) -> None:
        sim = self.sim
        before = sim.true_pose
        if linear is None:
            linear, angular = self._wander()
        sim.command(linear, angular)
        sim.step()
        self.driven += before.distance_to(sim.true_pose)
        if sim.steps % STEPS_PER_SCAN == 0:
            scan, o = sim.scan(), sim.odometry.pose
            p = self.amcl.params
            beams = select_beams(scan.ranges, self.angles, max_beams=p.max_beams, range_min=0.05,
                                 range_max=scan.config.range_max,
                                 laser_model_type=p.laser_model_type)  # fmt: skip
            self.updates += self.amcl.on_scan(np.array([o.x, o.y, o.yaw]), beams).updated

    def _wander(self) -> tuple[float, float]:
        ranges = self.sim.scan().ranges if self.sim.steps % 5 == 0 else None
        if ranges is not None:
            ahead = np.abs(self.angles) < math.radians(35)
            if np.min(ranges[ahead]) < 0.7:
                left = np.mean(np.minimum(ranges[(self.angles > 0.3) & (self.angles < 1.6)], 5))
                right = np.mean(np.minimum(ranges[(self.angles < -0.3) & (self.angles > -1.6)], 5))
                self._turning = 1.0 if left >= right else -1.0
            else:
                self._turning = 0.0
        return (0.0, self._turning) if self._turning else (0.4, 0.0)

    def error(self) -> tuple[float, float]:
        if self.amcl.map_to_odom is None:
            return math.inf, math.inf
        o, t = self.sim.odometry.pose, self.sim.true_pose
        est = se2.compose(self.amcl.map_to_odom, np.array([o.x, o.y, o.yaw]))
        return math.hypot(est[0] - t.x, est[1] - t.y), abs(float(se2.angle_diff(est[2], t.yaw)))

    def close_enough(self) -> bool:
        dist, heading = self.error()
        return dist < 0.25 and heading < math.radians(10.0)


def global_trial(seed: int, params: str) -> Run:
    rng = np.random.default_rng(seed)
    with _sim(seed) as sim:
        p = _params(params, seed)
        amcl = Amcl(p)
        amcl.set_map(_field(sim, p))
        sim.teleport(_free_pose(sim, rng))
        amcl.global_localization()
        drive, turned, settled = Driver(sim, amcl), 0.0, math.nan
        last = sim.true_pose.yaw
        while turned < math.tau:
            drive.step(0.0, 1.0)
            turned += abs(math.remainder(sim.true_pose.yaw - last, math.tau))
            last = sim.true_pose.yaw
        while drive.driven < 10.0 and sim.time < 120.0:
            drive.step()
            if sim.steps % STEPS_PER_SCAN == 0:
                good = drive.close_enough()
                settled = (drive.driven if math.isnan(settled) else settled) if good else math.nan
        dist, heading = drive.error()
        return Run(drive.close_enough(), dist, math.degrees(heading), settled)


def table(kind: str, runs: list[Run], unit: str) -> None:
    print(f"\n{kind}: {sum(r.ok for r in runs)}/{len(runs)}")
    print(f"| trial | ok | error m | heading deg | {unit} |\n|---|---|---|---|---|")
    for i, r in enumerate(runs, 1):
        ok = "yes" if r.ok else "no"
        print(f"| {i} | {ok} | {r.error:.2f} | {r.heading_deg:.1f} | {r.settled_at:.1f} |")


def trial_arguments(parser: argparse.ArgumentParser, trials: int) -> None:
    """``--trials``, ``--seed``, ``--params`` and ``--set`` (see :func:`apply_sets`)."""
    parser.add_argument("--trials", type=int, default=trials)
    parser.add_argument("--seed", type=int, default=1)
    parser.add_argument("--params", default="sim_robot", help="sim_robot or nav2")
    parser.add_argument("--set", action="append", default=[], metavar="NAME=VALUE",
                        help="an AMCL parameter over the params file (YAML value)")  # fmt: skip


def apply_sets(items: list[str]) -> None:
    """``--set NAME=VALUE`` items into :data:`OVERRIDES` (values in YAML)."""
    for item in items:
        name, _, text = item.partition("=")
        OVERRIDES[name] = yaml.safe_load(text)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__)
    trial_arguments(parser, trials=10)
    parser.add_argument("--only", choices=("global",), default=None)
    args = parser.parse_args()
    apply_sets(args.set)
    began = time.monotonic()
    if args.only in (None, "global"):
        runs = [global_trial(args.seed + i, args.params) for i in range(args.trials)]
        table("global", runs, "settled after m")
    print(f"\n({time.monotonic() - began:.0f} s wall, params {args.params})")


if __name__ == "__main__":
    main()
