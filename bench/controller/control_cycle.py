"""Controller benchmark: compute time per control cycle, and path-following accuracy.

Run: ``.venv/bin/python -m bench.controller.control_cycle``

1. Time of one ``FollowPathSession.step`` (tracking feedback, goal/progress
   checks, controller, collision check) with a full 5 x 5 m local costmap
   (0.05 m cells, obstacles everywhere off a 1.6 m corridor), for RPP and DWB,
   against the same RPP cycle without a costmap (baseline) in the same run;
   plus one lidar update of the local costmap (clear/mark + inflation), per scan and
   as the controller takes them (5 Hz of robot time, the window moved first).
2. Accuracy on a fixed course (straight, left and right curves, a U-turn)
   with a kinematic unicycle (accel limits 2.5 m/s^2, 3.2 rad/s^2, dt 0.05 s).
"""

from __future__ import annotations

import argparse
import math
import time

import numpy as np

from aiobt.costmap.checker import CollisionChecker
from aiobt.costmap.local import LocalCostmap
from aiobt.geometry import PlanarPath, Pose2D, Velocity
from aiobt.msgs import LaserScan
from aiobt.robot.state import RobotState
from aiobt_services.controller.session import (
    ControllerConfig,
    FollowPathSession,
    FollowRequest,
)
from aiobt_services.controller.unicycle import Unicycle


def polyline(points: list[tuple[float, float]], spacing: float = 0.05) -> PlanarPath:
    return PlanarPath.through(points, spacing)


def course() -> PlanarPath:
    """Straight 3 m, left quarter r 1.5, 2 m, right quarter r 1, 2 m, U-turn r 1, 3 m."""
    pts: list[tuple[float, float]] = [(0.0, 0.0), (3.0, 0.0)]
    pts += [
        (3.0 + 1.5 * math.sin(a), 1.5 - 1.5 * math.cos(a)) for a in np.linspace(0, math.pi / 2, 40)
    ]
    pts += [(4.5, 3.5)]
    pts += [(5.5 - math.cos(a), 3.5 + math.sin(a)) for a in np.linspace(0, math.pi / 2, 30)]
    pts += [(7.5, 4.5)]
    pts += [(7.5 + math.sin(a), 5.5 - math.cos(a)) for a in np.linspace(0, math.pi, 60)]
    pts += [(4.5, 6.5)]
    return polyline(pts)


def full_costmap(rng: np.random.Generator) -> LocalCostmap:
    costmap = LocalCostmap()
    costmap.follow(Pose2D(0.0, 0.0, 0.0))
    xs = rng.uniform(-2.5, 2.5, 4000)
    ys = rng.uniform(-2.5, 2.5, 4000)
    keep = np.abs(ys) > 0.8
    # inflated once and published, as a cycle between scans sees it
    costmap.publish(costmap.staged(lambda window: window.mark_points(xs[keep], ys[keep])))
    return costmap


def time_cycles(controller_id: str, costmap: LocalCostmap | None, cycles: int) -> np.ndarray:
    path = polyline([(-2.0, 0.0), (2.4, 0.0)])
    checker = CollisionChecker(costmap) if costmap is not None else None
    config = ControllerConfig(failure_tolerance=1e9)
    session = FollowPathSession(FollowRequest(path, controller_id), config, 0.0, checker)
    out = np.empty(cycles)
    for i in range(cycles):
        x = -1.5 + 1.5 * (i % 100) / 100.0  # sweep the first half of the corridor
        state = RobotState(Pose2D(x, 0.02, 0.01), Velocity(0.4, 0.0), float(i) * 0.05)
        start = time.perf_counter_ns()
        session.step(float(i) * 0.05, {"map": state})
        out[i] = (time.perf_counter_ns() - start) / 1e3
    return out


def time_scan_updates(
    costmap: LocalCostmap,
    updates: int,
    rng: np.random.Generator,
    step: float = 0.01,
    rebuild: bool = False,
    ahead: float = 0.0,
) -> np.ndarray:
    """``step`` m of travel between scans; ``rebuild``: the whole window re-inflated
    with each (as every move of the window did before it shifted its grids);
    ``ahead``: the window centred that far ahead of the scan's pose (the robot's newest
    pose when the controller takes the scan)."""
    out = np.empty(updates)
    for i in range(updates):
        ranges = rng.uniform(0.5, 4.0, 360).tolist()
        scan = LaserScan(
            angle_min=-math.pi, angle_max=math.pi, angle_increment=2 * math.pi / 360,
            range_min=0.05, range_max=12.0, ranges=ranges,
        )  # fmt: skip
        pose = Pose2D(step * i, 0.0, 0.0)
        start = time.perf_counter_ns()
        if rebuild:
            costmap.costmap.layers_replaced()
        costmap.add_scan(scan, pose, Pose2D(pose.x + ahead, 0.0, 0.0))  # inflated, published
        out[i] = (time.perf_counter_ns() - start) / 1e3
    return out


def follow_course(controller_id: str) -> dict[str, float]:
    path = course()
    robot = Unicycle(Pose2D(0.0, 0.0, 0.0), max_linear_accel=2.5, max_angular_accel=3.2)
    session = FollowPathSession(FollowRequest(path, controller_id), ControllerConfig(), 0.0, None)
    errors: list[float] = []
    now = 0.0
    while now < 120.0:
        step = session.step(now, {"map": RobotState(robot.pose, robot.velocity, now)})
        if step.feedback is not None:
            errors.append(abs(step.feedback.cross_track_error))
        if step.finished:
            break
        robot.step(step.cmd, 0.05)
        now += 0.05
    goal = path.goal
    return {
        "ok": float(step.succeeded),
        "mean": float(np.mean(errors)),
        "max": float(np.max(errors)),
        "time": now,
        "final_xy": robot.pose.distance_to(goal),
        "length": path.length(),
    }


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--cycles", type=int, default=3000)
    args = parser.parse_args()
    rng = np.random.default_rng(7)
    costmap = full_costmap(rng)
    lethal = float((costmap.costmap.master >= 253).mean())
    print(f"local costmap 100x100 cells, {lethal:.0%} inscribed/lethal after inflation")
    runs = {
        "RPP, no costmap (baseline)": time_cycles("FollowPath", None, args.cycles),
        "RPP, full local costmap": time_cycles("FollowPath", costmap, args.cycles),
        "DWB, full local costmap (252 samples)": time_cycles("DWB", costmap, args.cycles),
    }
    base = float(np.percentile(runs["RPP, no costmap (baseline)"], 50))
    print("| control cycle | p50 us | p99 us | p50 vs baseline |\n|---|---|---|---|")
    for name, t in runs.items():
        p50, p99 = np.percentile(t, [50, 99])
        print(f"| {name} | {p50:.0f} | {p99:.0f} | {p50 / base:.2f}x |")
    updates = {  # a cell (0.05 m) per scan is 0.5 m/s with the lidar at 10 Hz
        "local costmap update per scan (360 beams + inflation), window still": (0.0, False, 0.0),
        "the same, window moving a cell per scan (grids shifted)": (0.05, False, 0.0),
        "the same, window moving a cell per scan, rebuilt (before)": (0.05, True, 0.0),
        # the controller's update at 5 Hz (Nav2's update_frequency) at 0.5 m/s: 2 cells
        # between updates, the window at the newest pose, half a cell past the scan's
        "one update at 5 Hz: window moved 2 cells to the newest pose, then the scan": (
            0.1,
            False,
            0.025,
        ),
    }
    for name, (step, rebuild, ahead) in updates.items():
        scans = time_scan_updates(full_costmap(rng), 300, rng, step, rebuild, ahead)
        p50, p99 = np.percentile(scans, [50, 99])
        print(f"| {name} | {p50:.0f} | {p99:.0f} | - |")
    print(
        "\n| controller | course length m | reached | mean |cte| m | max |cte| m | time to goal s |"
    )
    print("|---|---|---|---|---|---|")
    for cid in ("FollowPath", "DWB"):
        r = follow_course(cid)
        print(
            f"| {cid} | {r['length']:.1f} | {'yes' if r['ok'] else 'no'} "
            f"(final {r['final_xy']:.3f} m) | {r['mean']:.3f} | {r['max']:.3f} | {r['time']:.1f} |"
        )


if __name__ == "__main__":
    main()
