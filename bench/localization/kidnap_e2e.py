"""The kidnap e2e test's scenario (``tests/e2e/test_kidnap.py``), in process and
seeded: the simulation and the filter's own :class:`Amcl` as in
:mod:`.kidnap`, but the robot is driven as the e2e stack drives it, not by its
lidar.

Run: ``.venv/bin/python -m bench.localization.kidnap_e2e [--trials 10] [--seed 1]
[--params sim_robot|nav2] [--set NAME=VALUE ...] [--relocalize-after S]
[--turns N] [--settle N] [--scan-every K [--queue]] [--steps N --pause S]
[--turn-speed RAD_S] [--relocalizations N]``

Each trial: the robot at (2, 9.75) heading east, the filter given that pose; a
pure-pursuit follower (0.5 m/s, look-ahead 0.6 m, as RegulatedPurePursuit's
defaults) drives the e2e goal's path (the corridor y 9.75 east to x 10, then
south to (10, 6)) **from the estimate**; the robot stops while its true lidar
sees anything within 0.45 m ahead (the collision monitor and the controller's
collision check). At true x 5 the simulation carries it to (5.0, 6.75, 0) (the
west room, through the wall), the filter not told, and the follower goes on
following the path where the robot is not.

- the filter alone: sim s until the estimate is within 0.25 m (30 s at most),
  with the follower driving throughout (``--relocalize-after`` 0);
- ``--relocalize-after S``: S sim s after the kidnap, the tree's Relocalize:
  ``reinitialize_global_localization``, ``--settle`` no-motion updates, then
  ``--turns`` turns on the spot at 1 rad/s (Spin's ``max_rotational_vel``) and
  the follower on for 30 s (the path from the estimate). During the turn, two
  local costmaps are fed at 5 Hz, as the behaviors service's is: one in ``map``
  (the lidar laid at the estimate, as that service does) and one in ``odom``
  (Nav2's behavior server: ``local_frame`` odom); the first sim s at which Spin's
  check (the robot's cell at or above inscribed) fails on each is reported: a
  failure is Spin's 703 "the robot is in collision while spinning".
- ``--scan-every K``: the filter reads every K-th scan only (the e2e stack's
  localization service, 20,000 particles at a 4x speed-up, drops scans: "the
  reader falls behind"); with ``--queue`` the scans wait in the service's queue of
  10 instead and an update takes K scan intervals (:class:`_Queued`).
- ``--steps N --pause S``: the turn(s) in N steps with S sim s still after each
  (the relocalizing tree's eighths); ``--turn-speed``: rad/s of the turn.
- ``--relocalizations N``: the tree's Relocalize N times, each with its 30 s of
  following (the next recovery round's, whether or not the last one found the
  robot); the error right after each turn is reported.
"""

from __future__ import annotations

import argparse
import itertools
import math
import time
from collections import deque
from dataclasses import dataclass, field

import numpy as np

from aiobt.costmap.checker import CollisionChecker
from aiobt.costmap.local import LocalCostmap
from aiobt.geometry import Pose2D
from aiobt_services.localization import se2
from aiobt_services.localization.amcl import Amcl, ScanOutcome
from aiobt_services.localization.laser_model import Beams
from aiobt_services.localization.params import AmclParams
from aiobt_services.localization.se2 import FloatArray
from aiobt_services.robot.convert import laser_scan
from aiobt_services.robot.sim import Simulation

from .relocalize import STEPS_PER_SCAN, Driver, _field, _params, _sim, apply_sets, trial_arguments

START = Pose2D(2.0, 9.75, 0.0)
KIDNAP_AT_X = 5.0
KIDNAPPED_TO = Pose2D(5.0, 6.75, 0.0)
PATH = np.array([(2.0, 9.75), (10.0, 9.75), (10.0, 6.0)])
FOUND_M = 0.25
AFTER_S = 30.0
SPEED, LOOKAHEAD, STOP_AHEAD = 0.5, 0.6, 0.45
QUEUE = 10  # the localization service's scan queue
QUEUED = [False]  # --queue: scans through :class:`_Queued`, not :class:`_Dropping`
COSTMAP_PERIOD_STEPS = 20  # 5 Hz at the 100 Hz physics step
CHECK_PERIOD_STEPS = 5  # the behaviors service's 20 Hz cycle


@dataclass(slots=True)
class Trial:
    back_s: float = math.nan  # sim s after the kidnap until within FOUND_M (nan: never)
    collides_map_s: float = math.nan  # Spin's check failed on the map-frame costmap
    collides_odom_s: float = math.nan  # ... on the odom-frame costmap
    after_turns: list[float] = field(default_factory=list)  # error right after each turn, m
    end_error: float = math.nan
    blocked_s: float = 0.0  # sim s the follower was held by an obstacle ahead


def _estimate(drive: Driver) -> Pose2D:
    o = drive.sim.odometry.pose
    if drive.amcl.map_to_odom is None:
        return o
    e = se2.compose(drive.amcl.map_to_odom, np.array([o.x, o.y, o.yaw]))
    return Pose2D(float(e[0]), float(e[1]), float(e[2]))


def _pursuit(here: Pose2D) -> tuple[float, float]:
    """(v, w) towards the point LOOKAHEAD ahead on :data:`PATH` from the nearest one."""
    dense = np.concatenate([np.linspace(a, b, int(np.hypot(*(b - a)) / 0.05) + 1)
                            for a, b in itertools.pairwise(PATH)])  # fmt: skip
    d = np.hypot(dense[:, 0] - here.x, dense[:, 1] - here.y)
    near = int(np.argmin(d))
    ahead = near + np.flatnonzero(d[near:] >= LOOKAHEAD)
    gx, gy = dense[int(ahead[0])] if ahead.size else dense[-1]
    if math.hypot(gx - here.x, gy - here.y) < 0.1:
        return 0.0, 0.0
    bearing = math.remainder(math.atan2(gy - here.y, gx - here.x) - here.yaw, math.tau)
    if abs(bearing) > 0.8:  # RPP's rotate to heading
        return 0.0, math.copysign(1.0, bearing)
    curvature = 2.0 * math.sin(bearing) / LOOKAHEAD
    return SPEED, max(-1.0, min(1.0, SPEED * curvature))


def _blocked(sim: Simulation, angles: np.ndarray) -> bool:
    ranges = sim.scan().ranges
    return bool(np.min(ranges[np.abs(angles) < math.radians(35)]) < STOP_AHEAD)


class _Dropping(Amcl):
    """The filter reading every ``every``-th scan only."""

    def __init__(self, params: AmclParams, every: int) -> None:
        super().__init__(params)
        self.every, self._seen = every, 0

    def on_scan(self, odom_pose: FloatArray, beams: Beams) -> ScanOutcome:
        self._seen += 1
        if self._seen % self.every:
            return ScanOutcome(False, False)
        return super().on_scan(odom_pose, beams)


class _Queued(Amcl):
    """The service's reader: scans wait in a queue of ``QUEUE`` (the oldest dropped
    when full) and an update takes ``every`` scan intervals; a scan that does not
    update (no motion since the last) costs nothing."""

    def __init__(self, params: AmclParams, every: int) -> None:
        super().__init__(params)
        self.every, self._budget = every, 0.0
        self._queue: deque[tuple[FloatArray, Beams]] = deque(maxlen=QUEUE)

    def on_scan(self, odom_pose: FloatArray, beams: Beams) -> ScanOutcome:
        self._queue.append((odom_pose, beams))
        self._budget = min(1.0, self._budget + 1.0 / self.every)
        updated = False
        while self._queue and self._budget >= 1.0:
            outcome = super().on_scan(*self._queue.popleft())
            self._budget -= 1.0 if outcome.updated else 0.0
            updated |= outcome.updated
        return ScanOutcome(updated, False)


class _Follower:
    def __init__(self, drive: Driver) -> None:
        self.drive, self.blocked, self._held = drive, 0.0, False

    def step(self) -> None:
        sim = self.drive.sim
        if sim.steps % 5 == 0:
            self._held = _blocked(sim, self.drive.angles)
        v, w = _pursuit(_estimate(self.drive))
        if self._held and v > 0.0:
            self.blocked += sim.config.dt
            v, w = 0.0, 0.0
        self.drive.step(v, w)


TURN_SPEED = [1.0]  # rad/s of the relocalizing turn (--turn-speed)
STEPPED = [1, 0.0]  # the turn in this many steps, with this many sim s still after each
RELOCALIZATIONS = [1]  # Relocalize this many times (--relocalizations)


def _turn(drive: Driver, turns: float, out: Trial, since: float) -> None:
    """Turn on the spot, feeding a map-frame and an odom-frame local costmap at 5 Hz."""
    sim = drive.sim
    in_map, in_odom = LocalCostmap(), LocalCostmap()
    turned, last = 0.0, sim.true_pose.yaw
    while turned < turns * math.tau:
        drive.step(0.0, TURN_SPEED[0])
        turned += abs(math.remainder(sim.true_pose.yaw - last, math.tau))
        last = sim.true_pose.yaw
        if sim.steps % CHECK_PERIOD_STEPS:
            continue
        est, odom = _estimate(drive), sim.odometry.pose
        if sim.steps % COSTMAP_PERIOD_STEPS == 0:
            scan = laser_scan(sim.scan())
            in_map.add_scan(scan, est)
            in_odom.add_scan(scan, odom)
        if math.isnan(out.collides_map_s) and CollisionChecker(in_map).pose_collides(est):
            out.collides_map_s = sim.time - since
        if math.isnan(out.collides_odom_s) and CollisionChecker(in_odom).pose_collides(odom):
            out.collides_odom_s = sim.time - since


def _note_back(drive: Driver, out: Trial, kidnapped: float) -> None:
    """The first scan time the estimate is within FOUND_M of the truth."""
    sim = drive.sim
    if sim.steps % STEPS_PER_SCAN == 0 and math.isnan(out.back_s) and drive.error()[0] < FOUND_M:
        out.back_s = sim.time - kidnapped


def _relocalize(follow: _Follower, turns: float, settle: int, out: Trial, kidnapped: float) -> None:
    """The tree's Relocalize (reinitialize, ``settle`` no-motion updates, ``turns``
    turns), then the follower on for :data:`AFTER_S`."""
    drive = follow.drive
    drive.amcl.global_localization()
    for _ in range(settle):
        drive.amcl.request_nomotion_update()
        for _ in range(STEPS_PER_SCAN):
            drive.step(0.0, 0.0)
    steps, pause = int(STEPPED[0]), float(STEPPED[1])
    since = drive.sim.time
    for _ in range(steps):
        _turn(drive, turns / steps, out, since)
        for _ in range(round(pause / drive.sim.config.dt)):
            drive.step(0.0, 0.0)
    out.after_turns.append(drive.error()[0])
    began = drive.sim.time
    while drive.sim.time - began < AFTER_S:
        follow.step()
        _note_back(drive, out, kidnapped)


def trial(
    seed: int, params: str, relocalize_after: float, turns: float, settle: int, every: int = 1
) -> Trial:
    out = Trial()
    with _sim(seed) as sim:
        p = _params(params, seed)
        amcl = _Queued(p, every) if QUEUED[0] else _Dropping(p, every)
        amcl.set_map(_field(sim, p))
        sim.teleport(START)
        amcl.initialize(amcl.check_pose(START.x, START.y, START.yaw))
        drive = Driver(sim, amcl)
        follow = _Follower(drive)
        while sim.true_pose.x < KIDNAP_AT_X and sim.time < 60.0:
            follow.step()
        sim.teleport(KIDNAPPED_TO)
        kidnapped = sim.time
        relocalized = relocalize_after <= 0.0
        while sim.time - kidnapped < (AFTER_S if relocalized else relocalize_after + 1e-9):
            follow.step()
            if relocalized:
                _note_back(drive, out, kidnapped)
        for _ in range(0 if relocalized else RELOCALIZATIONS[0]):
            _relocalize(follow, turns, settle, out, kidnapped)
        out.end_error, out.blocked_s = drive.error()[0], follow.blocked
    return out


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__)
    trial_arguments(parser, trials=10)
    parser.add_argument("--relocalize-after", type=float, default=0.0, metavar="S")
    parser.add_argument("--turns", type=float, default=1.0)
    parser.add_argument("--settle", type=int, default=0, metavar="N",
                        help="no-motion updates after the reinitialization")  # fmt: skip
    parser.add_argument("--scan-every", type=int, default=1, metavar="K")
    parser.add_argument("--turn-speed", type=float, default=1.0, metavar="RAD_S")
    parser.add_argument("--queue", action="store_true",
                        help="--scan-every K as a queue of 10, updates K scans long")  # fmt: skip
    parser.add_argument("--steps", type=int, default=1, help="the turn in N steps")
    parser.add_argument("--pause", type=float, default=0.0, metavar="S",
                        help="sim s still after each step")  # fmt: skip
    parser.add_argument("--relocalizations", type=int, default=1, metavar="N")
    args = parser.parse_args()
    apply_sets(args.set)
    TURN_SPEED[0] = args.turn_speed
    QUEUED[0] = args.queue
    STEPPED[:] = [args.steps, args.pause]
    RELOCALIZATIONS[0] = args.relocalizations
    began = time.monotonic()
    runs = []
    print(
        "| seed | back after sim s | Spin 703 on map / odom costmap after s | error after "
        "turn m | error at end m | held s |\n|---|---|---|---|---|---|"
    )
    for seed in range(args.seed, args.seed + args.trials):
        r = trial(seed, args.params, args.relocalize_after, args.turns, args.settle,
                  args.scan_every)  # fmt: skip
        runs.append(r)
        print(f"| {seed} | {r.back_s:.1f} | {r.collides_map_s:.1f} / {r.collides_odom_s:.1f} "
              f"| {' '.join(f'{e:.2f}' for e in r.after_turns)} | {r.end_error:.2f} "
              f"| {r.blocked_s:.1f} |",
              flush=True)  # fmt: skip
    ok = sum(r.end_error < FOUND_M for r in runs)
    back = sum(not math.isnan(r.back_s) for r in runs)
    print(f"\nback within {FOUND_M} m at some point: {back}/{len(runs)}; at the end: "
          f"{ok}/{len(runs)}; Spin's check failed on the map-frame costmap in "
          f"{sum(not math.isnan(r.collides_map_s) for r in runs)}, on the odom-frame in "
          f"{sum(not math.isnan(r.collides_odom_s) for r in runs)}")  # fmt: skip
    turns = [[e < FOUND_M for e in r.after_turns] for r in runs]
    if any(turns):
        each = " ".join(f"{sum(t[i] for t in turns)}/{len(runs)}" for i in range(len(turns[0])))
        print(f"within {FOUND_M} m right after turn 1, 2, ...: {each}; after any: "
              f"{sum(any(t) for t in turns)}/{len(runs)}")  # fmt: skip
    print(
        f"({time.monotonic() - began:.0f} s wall, params {args.params}, set {args.set}, "
        f"relocalize after {args.relocalize_after} s, turns {args.turns}, settle {args.settle}, "
        f"scan every {args.scan_every}, queue {args.queue}, turn speed {args.turn_speed} "
        f"rad/s, {args.steps} steps, pause {args.pause} s)"
    )


if __name__ == "__main__":
    main()
