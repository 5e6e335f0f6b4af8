"""The odometry taken from the service's ring at each scan (no callback per message)
gives the filter exactly what handing every message to ``on_odom`` gave."""

from __future__ import annotations

import math

import numpy as np

from aiobt.msgs import Msg, Odometry, PoseStamped, PoseWithCovarianceStamped
from aiobt_services.localization.node import LocalizationNode
from aiobt_services.localization.params import AmclParams
from aiobt_services.localization.se2 import wrap

from .test_node import _grid, _odom, _scan

START = (1.0, 3.0, 0.5)  # the truth in map when the odometry reads (0, 0, 0)


class Ring:
    """The ring as the node sees it: what came since the last take, oldest first."""

    def __init__(self) -> None:
        self.pending: list[Odometry] = []

    def take(self) -> list[Odometry]:
        out, self.pending = self.pending, []
        return out


def _drive(seconds: float, restart_at: float) -> list[tuple[float, tuple[float, float, float]]]:
    """(stamp, odometry pose) at 50 Hz with jittered stamps along an arc; at
    ``restart_at`` the simulation restarts (stamps from 0 again)."""
    rng = np.random.default_rng(7)
    out, x, y, yaw, stamp, back = [], 0.0, 0.0, 0.0, 0.0, False
    while stamp < seconds:
        x, y = x + 0.008 * math.cos(yaw), y + 0.008 * math.sin(yaw)
        yaw = float(wrap(yaw + 0.012))
        stamp += 0.02 + float(rng.uniform(-0.004, 0.004))
        if stamp >= restart_at and not back:
            stamp, back = 0.013, True
        out.append((stamp, (x, y, yaw)))
    return out


def _truth(odom: tuple[float, float, float]) -> tuple[float, float, float]:
    sx, sy, syaw = START
    x, y, yaw = odom
    c, s = math.cos(syaw), math.sin(syaw)
    return (sx + c * x - s * y, sy + s * x + c * y, float(wrap(syaw + yaw)))


def _wire(out: list[tuple[str, Msg]]) -> list[tuple[str, bytes]]:
    return [(topic, msg.to_json()) for topic, msg in out]


def _node(ring: Ring | None) -> LocalizationNode:
    params = AmclParams.from_mapping({"random_seed": 1, "update_min_d": 0.05})
    node = (LocalizationNode(params) if ring is None
            else LocalizationNode(params, odometry=ring.take))  # fmt: skip
    assert node.on_map(_grid()).ok
    assert node.on_initialpose(PoseWithCovarianceStamped.from_xy_yaw(*START)).ok
    return node


def test_scans_take_the_same_odometry_and_give_the_same_outputs_as_per_message() -> None:
    ring = Ring()
    fed, ringed = _node(None), _node(ring)
    track = _drive(4.0, restart_at=3.0)
    jobs = updates = 0
    for j, (stamp, here) in enumerate(track):
        msg = _odom(stamp, *here)
        poses = fed.on_odom(msg)  # every message in the loop, as the callback path did
        ring.pending.append(msg)  # into the ring: nothing runs
        assert _wire(ringed.pose_for(msg)) == _wire(poses)  # the pose stream, while read
        i = j - 2  # a scan with message i, read once two newer messages came
        if i < 3 or i % 5 != 2:
            continue
        # stamped at an odometry stamp, or between two
        scan_at = track[i][0] if i % 10 == 2 else track[i][0] - 0.007
        scan = _scan(scan_at, _truth(track[i - 1][1]))
        a, b = fed.scan_job(scan), ringed.scan_job(scan)
        assert (a is None) == (b is None)
        if a is not None and b is not None:
            jobs += 1
            assert a.stamp == b.stamp
            assert np.array_equal(a.odom_pose, b.odom_pose)
            out_a, out_b = fed.update(a), ringed.update(b)
            assert _wire(out_a) == _wire(out_b)
            updates += bool(out_a)
        assert _wire(fed.correction(scan_at)) == _wire(ringed.correction(scan_at))
    assert jobs > 10  # the filter did run, both ways
    assert updates > 5
    # the pose stream: the correction composed with the odometry (x, y and heading)
    stamp, (ox, oy, oyaw) = track[-1]
    ((_, pose),) = ringed.pose_for(_odom(stamp, ox, oy, oyaw))
    correction = ringed.amcl.map_to_odom
    assert correction is not None
    assert isinstance(pose, PoseStamped)
    cx, cy, cyaw = (float(v) for v in correction)
    c, s = math.cos(cyaw), math.sin(cyaw)
    expected = (cx + c * ox - s * oy, cy + s * ox + c * oy, float(wrap(cyaw + oyaw)))
    assert np.allclose((pose.x, pose.y, pose.yaw), expected, atol=1e-9)
    assert pose.header.stamp == stamp
    counted = ("scans", "updates", "skipped_no_odom", "skipped_before_reset", "skipped_still")
    assert [getattr(fed.stats, n) for n in counted] == [getattr(ringed.stats, n) for n in counted]


def test_an_initial_pose_marks_the_newest_odometry_in_the_ring() -> None:
    """A scan taken before the pose was given is not weighed (the node's reset mark is
    the newest odometry's stamp): the ring's messages count though not yet taken."""
    ring = Ring()
    node = _node(ring)
    ring.pending += [_odom(1.0, 0.0, 0.0, 0.0), _odom(2.0, 0.0, 0.0, 0.0)]
    assert node.on_initialpose(PoseWithCovarianceStamped.from_xy_yaw(3.0, 1.0, 0.0)).ok
    assert node.on_scan(_scan(1.5, (1.0, 3.0, 0.0))) == []
    assert node.stats.skipped_before_reset == 1
    ring.pending.append(_odom(3.0, 0.0, 0.0, 0.0))
    assert node.reinitialize_global_localization().ok
    node.on_scan(_scan(2.5, (3.0, 1.0, 0.0)))
    assert node.stats.skipped_before_reset == 2
