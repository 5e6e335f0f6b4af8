"""How well one scan tells the truth from a look-alike pose, per laser model: in
process, the simulation's lidar (its default noise and dropouts) at exact poses.

Run: ``.venv/bin/python -m bench.localization.separation [--headings 12] [--seed 1]``

At each spot (the west room's, where the kidnap e2e test's relocalization settled
on the mirror image) and each of ``--headings`` headings: one scan taken at the
truth, weighed at the truth and at its point mirror image through the room's
centre (3.53, 4.28), turned by 180 degrees. Two figures per model: the exact
poses' likelihood ratio (truth / mirror) and a cloud's (200 particles each, 5 cm
and 2 degrees of spread: what a filter holding both modes sees), the median over
the headings and the smallest. Above 1: the truth weighs more.
"""

from __future__ import annotations

import argparse
import math
import statistics

import numpy as np

from aiobt.geometry import Pose2D
from aiobt_services.localization.amcl import laser_model
from aiobt_services.localization.laser_model import select_beams
from aiobt_services.localization.params import AmclParams
from aiobt_services.robot.sim import PoseError

from .relocalize import _field, _sim

CENTRE = (3.53, 4.28)  # the west room's centre of near point symmetry
SPOTS = {
    "kidnap spot (5.00, 6.75)": (5.0, 6.75),
    "(5.16, 6.43)": (5.16, 6.43),
    "east wall (6.50, 6.90)": (6.5, 6.9),
    "north-east corner (6.50, 8.00)": (6.5, 8.0),
    "inside the door (3.50, 8.00)": (3.5, 8.0),
    "south wall (3.72, 0.70)": (3.72, 0.70),
}
MODELS = ("likelihood_field", "likelihood_field_prob")


def _mirror(pose: Pose2D) -> np.ndarray:
    return np.array(
        [
            2 * CENTRE[0] - pose.x,
            2 * CENTRE[1] - pose.y,
            math.remainder(pose.yaw + math.pi, math.tau),
        ]
    )


def _log_mean(model_log: np.ndarray) -> float:
    top = float(model_log.max())
    return top + math.log(float(np.mean(np.exp(model_log - top))))


def spot_ratios(
    xy: tuple[float, float], headings: int, seed: int
) -> dict[str, list[tuple[float, float]]]:
    """Per model, (log exact ratio, log cloud ratio) for each heading."""
    rng = np.random.default_rng(seed)
    out: dict[str, list[tuple[float, float]]] = {m: [] for m in MODELS}
    with _sim(seed) as sim:
        params = {m: AmclParams(laser_model_type=m) for m in MODELS}
        models = {m: laser_model(p, _field(sim, p)) for m, p in params.items()}
        angles = sim.config.lidar.angles()
        for k in range(headings):
            truth = Pose2D(xy[0], xy[1], math.remainder(k * math.tau / headings, math.tau))
            try:
                sim.teleport(truth)
            except PoseError:
                continue
            sim.step()
            scan = sim.scan()
            jitter = rng.normal(0.0, 1.0, (200, 3)) * np.array([0.05, 0.05, math.radians(2)])
            poses = np.array([[truth.x, truth.y, truth.yaw], _mirror(truth)])
            clouds = [poses[0] + jitter, poses[1] + jitter]
            for m, model in models.items():
                top = scan.config.range_max
                beams = select_beams(scan.ranges, angles, max_beams=60, range_min=0.05,
                                     range_max=top, laser_model_type=m)  # fmt: skip
                logs = [_logs(model.weigh(c, beams, converged=False)) for c in [poses, *clouds]]
                exact = float(logs[0][0] - logs[0][1])
                out[m].append((exact, _log_mean(logs[1]) - _log_mean(logs[2])))
    return out


def _logs(likelihood: tuple[np.ndarray, float]) -> np.ndarray:
    factors, scale = likelihood
    with np.errstate(divide="ignore"):
        logs: np.ndarray = np.log(factors) + scale
    return logs


def _fmt(logs: list[float]) -> str:
    med, low = statistics.median(logs), min(logs)
    return f"{math.exp(med):.3g} (min {math.exp(low):.3g})"


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--headings", type=int, default=12)
    parser.add_argument("--seed", type=int, default=1)
    args = parser.parse_args()
    print("| spot | model | exact poses: truth / mirror, median (min) | clouds: median (min) |")
    print("|---|---|---|---|")
    for name, xy in SPOTS.items():
        for m, rows in spot_ratios(xy, args.headings, args.seed).items():
            exact, cloud = [r[0] for r in rows], [r[1] for r in rows]
            print(f"| {name} | {m} | {_fmt(exact)} | {_fmt(cloud)} |")


if __name__ == "__main__":
    main()
