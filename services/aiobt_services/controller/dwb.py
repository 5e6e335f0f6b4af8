"""A DWB-style sampling controller (the ``DWB`` controller id).

Samples (v, w) pairs in the dynamic window reachable within one control
period, rolls each out for ``sim_time`` (all at once, as numpy arrays), drops
the ones that hit an obstacle, and scores the rest on distance to the path,
distance to a local goal along the path, path alignment and obstacle cost.
Within the goal's xy tolerance it rotates in place to the goal heading.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from aiobt.costmap import NO_INFORMATION
from aiobt.costmap.checker import CollisionChecker
from aiobt.geometry import (
    FloatArray,
    PlanarPath,
    Pose2D,
    Velocity,
    integrate_arc,
    turn_rate,
    wrap_angle,
)

from .base import ControlContext, PlanFollower
from .errors import no_valid_control
from .speed_limit import SpeedLimit
from .tracking import project_onto_path, search_stop


@dataclass(slots=True)
class DWBParams:
    min_vel_x: float = 0.0
    max_vel_x: float = 0.5
    max_vel_theta: float = 1.8
    acc_lim_x: float = 2.5
    acc_lim_theta: float = 3.2
    vx_samples: int = 12
    vtheta_samples: int = 21
    sim_time: float = 1.5
    sim_steps: int = 15
    local_path_length: float = 2.0
    forward_point_distance: float = 0.325
    path_dist_scale: float = 32.0
    goal_dist_scale: float = 24.0
    path_align_scale: float = 32.0
    obstacle_scale: float = 0.02
    rotate_to_goal_vel: float = 1.0


class DWBController(PlanFollower):
    """Dynamic-window sampling controller scored by path, goal and obstacle critics."""

    __slots__ = ("_base", "params")
    name = "DWB"

    def __init__(self, params: DWBParams | None = None) -> None:
        super().__init__()
        self.params = params or DWBParams()
        self._base = (self.params.max_vel_x, self.params.max_vel_theta)

    def set_speed_limit(self, limit: SpeedLimit) -> None:
        """Nav2's ``KinematicsHandler::setSpeedLimit``: the velocity limits scaled together,
        so the trajectories keep their shape (an absolute limit above the maximum: none)."""
        ratio = limit.ratio(self._base[0])
        self.params.max_vel_x = self._base[0] * ratio
        self.params.max_vel_theta = self._base[1] * ratio

    def compute_velocity(self, pose: Pose2D, speed: Velocity, ctx: ControlContext) -> Velocity:
        path = self._require_path()
        goal = path.goal
        if pose.distance_to(goal) < ctx.goal_xy_tolerance:
            cmd = self._rotate_to(wrap_angle(goal.yaw - pose.yaw), speed, ctx)
            self.trajectory = self._rolled_out(pose, cmd)
            return cmd
        stop = search_stop(path, self._segment, self.params.local_path_length)
        self._segment = project_onto_path(path, pose, self._segment, stop).segment
        local = self._local_path(path)
        v, w = self._samples(speed, ctx.dt)
        xs, ys, yaws = self._rollout(pose, v, w)
        near_goal = pose.distance_to(goal) < self.params.max_vel_x * self.params.sim_time
        score = self._score(xs, ys, yaws, local, ctx.collision, align=not near_goal)
        best = int(np.argmin(score))
        if not math.isfinite(float(score[best])):
            raise no_valid_control(
                f"DWB found no valid trajectory among {score.size} samples (all collide)"
            )
        # Nav2's DWB publishes the best trajectory as its local_plan
        self.trajectory = np.vstack(
            ([[pose.x, pose.y, pose.yaw]], np.column_stack((xs[best], ys[best], yaws[best])))
        )
        return Velocity(float(v[best]), float(w[best]))

    def _rolled_out(self, pose: Pose2D, cmd: Velocity) -> FloatArray:
        p = self.params
        times = np.linspace(0.0, p.sim_time, p.sim_steps + 1)
        return integrate_arc(pose, cmd, times)

    def _local_path(self, path: PlanarPath) -> FloatArray:
        seg = path.segment_lengths()[self._segment :]
        count = int((np.cumsum(seg) <= self.params.local_path_length).sum()) + 2
        return path.xy[self._segment : self._segment + count]

    def _samples(self, speed: Velocity, dt: float) -> tuple[FloatArray, FloatArray]:
        p = self.params
        window = max(dt, 0.1)
        # Nav2's OneDVelocityIterator clamps the current speed into the limits first, so a
        # robot faster than a new speed limit samples under it at once
        v_now = min(max(speed.v, p.min_vel_x), p.max_vel_x)
        w_now = min(max(speed.w, -p.max_vel_theta), p.max_vel_theta)
        v_lo = max(p.min_vel_x, v_now - p.acc_lim_x * window)
        v_hi = min(p.max_vel_x, max(v_now + p.acc_lim_x * window, v_lo))
        w_lo = max(-p.max_vel_theta, w_now - p.acc_lim_theta * window)
        w_hi = min(p.max_vel_theta, w_now + p.acc_lim_theta * window)
        grid_v, grid_w = np.meshgrid(
            np.linspace(v_lo, v_hi, p.vx_samples), np.linspace(w_lo, w_hi, p.vtheta_samples)
        )
        return grid_v.ravel(), grid_w.ravel()

    def _rollout(
        self, pose: Pose2D, v: FloatArray, w: FloatArray
    ) -> tuple[FloatArray, FloatArray, FloatArray]:
        p = self.params
        t = np.linspace(p.sim_time / p.sim_steps, p.sim_time, p.sim_steps)[None, :]
        vv, ww = v[:, None], w[:, None]
        yaw = pose.yaw + ww * t
        straight = np.abs(ww) < 1e-6
        safe_w = np.where(straight, 1.0, ww)
        x_arc = pose.x + vv / safe_w * (np.sin(yaw) - math.sin(pose.yaw))
        y_arc = pose.y - vv / safe_w * (np.cos(yaw) - math.cos(pose.yaw))
        x_line = pose.x + vv * t * math.cos(pose.yaw)
        y_line = pose.y + vv * t * math.sin(pose.yaw)
        return np.where(straight, x_line, x_arc), np.where(straight, y_line, y_arc), yaw

    def _score(
        self,
        xs: FloatArray,
        ys: FloatArray,
        yaws: FloatArray,
        local: FloatArray,
        collision: CollisionChecker | None,
        align: bool,
    ) -> FloatArray:
        p = self.params
        ends = np.column_stack((xs[:, -1], ys[:, -1]))
        ahead = ends + p.forward_point_distance * np.column_stack(
            (np.cos(yaws[:, -1]), np.sin(yaws[:, -1]))
        )
        path_dist = _min_distance(ends, local)
        # off near the goal: the point ahead would sit past the path's end
        align_dist = _min_distance(ahead, local) if align else 0.0
        to_goal = ends - local[-1]
        goal_dist = np.hypot(to_goal[:, 0], to_goal[:, 1])
        score: FloatArray = (
            p.path_dist_scale * path_dist
            + p.goal_dist_scale * goal_dist
            + p.path_align_scale * align_dist
        )
        if collision is None:
            return score
        costs = collision.costmap.costs_at(np.column_stack((xs.ravel(), ys.ravel()))).reshape(
            xs.shape
        )
        blocked = collision.lethal_mask(costs).any(axis=1)
        known = np.where(costs == NO_INFORMATION, 0, costs)
        score = score + p.obstacle_scale * known.max(axis=1)
        result: FloatArray = np.where(blocked, np.inf, score)
        return result

    def _rotate_to(self, angle_error: float, speed: Velocity, ctx: ControlContext) -> Velocity:
        p = self.params
        return Velocity(
            0.0, turn_rate(angle_error, p.rotate_to_goal_vel, p.acc_lim_theta, speed.w, ctx.dt)
        )


def _min_distance(points: FloatArray, polyline: FloatArray) -> FloatArray:
    """Distance of each point (S, 2) to the nearest vertex of ``polyline`` (P, 2)."""
    diff = points[:, None, :] - polyline[None, :, :]
    distance: FloatArray = np.sqrt((diff * diff).sum(axis=2).min(axis=1))
    return distance
