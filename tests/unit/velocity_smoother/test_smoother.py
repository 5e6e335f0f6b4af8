"""The smoother's timer (Nav2's openLoopTestTimer, approxClosedLoopTestTimer, the
timeout, the deadband, scale_velocities) on a hand-advanced time line."""

from __future__ import annotations

import math

import numpy as np
import pytest

from aiobt_services.velocity_smoother import SmootherParams, VelocitySmoother

PERIOD = 0.05  # 20 Hz


def run(smoother: VelocitySmoother, seconds: float, start: float = 0.0) -> list[float]:
    """vx published over ``seconds`` of timer ticks (None: not published, left out)."""
    out = []
    for i in range(round(seconds / PERIOD)):
        cmd = smoother.update(start + i * PERIOD)
        if cmd is not None:
            out.append(float(cmd[0]))
    return out


def test_nothing_is_published_before_the_first_command() -> None:
    assert run(VelocitySmoother(), 1.0) == []


def test_open_loop_ramps_clamps_times_out_and_stops_publishing() -> None:
    smoother = VelocitySmoother(SmootherParams(deadband_velocity=(0.2, 0.0, 0.0),
                                               scale_velocities=True))  # fmt: skip
    smoother.command((1.0, 0.0, 0.0), 0.0)  # above max_velocity 0.5
    vels = run(smoother, 1.5)
    assert 19 < len(vels) < 30  # Nav2's bounds for 1.5 s with a 1 s timeout
    assert vels[-1] == 0.0  # timed out: ramped down to a stop
    first = next(v for v in vels if v != 0.0)
    assert first > 0.2  # the deadband hid the smaller ones
    assert max(vels) == pytest.approx(0.5)
    assert all(v <= 0.5 for v in vels)
    assert smoother.update(2.0) is None  # stopped: silent until a new command


def test_closed_loop_starts_from_the_measured_velocity() -> None:
    params = SmootherParams(feedback="CLOSED_LOOP", max_accel=(0.5, 0.0, 3.2))
    smoother = VelocitySmoother(params)
    smoother.command((1.0, 0.0, 0.0), 0.0)
    vels: list[float] = []
    for i in range(30):
        now = i * PERIOD
        smoother.odom.add(now, np.array([vels[-1] if vels else 0.0, 0.0, 0.0]))
        out = smoother.update(now)
        if out is not None:
            vels.append(float(out[0]))
    steps = np.diff(vels)
    assert np.all(steps < 0.5 / 20 + 1e-3)  # Nav2: accel 0.5 / 20 Hz
    assert vels[-1] == 0.0
    assert all(v <= 0.5 for v in vels)


def test_closed_loop_follows_a_base_slower_than_commanded() -> None:
    smoother = VelocitySmoother(SmootherParams(feedback="CLOSED_LOOP"))
    smoother.command((0.5, 0.0, 0.0), 0.0)
    smoother.odom.add(0.0, np.array([0.1, 0.0, 0.0]))  # the base lags
    out = smoother.update(0.0)
    assert out is not None
    assert out[0] == pytest.approx(0.1 + 2.5 / 20)


def test_a_stale_command_is_ramped_to_zero_after_velocity_timeout() -> None:
    smoother = VelocitySmoother(SmootherParams(velocity_timeout=0.5))
    smoother.command((0.5, 0.0, 1.0), 0.0)
    for i in range(10):
        assert smoother.update(i * PERIOD) is not None
    cruising = smoother.update(0.5)
    assert cruising is not None
    assert cruising[0] == pytest.approx(0.5)
    after = smoother.update(0.55)
    assert after is not None
    assert after[0] == pytest.approx(0.5 - 2.5 / 20)


def test_nan_and_inf_commands_are_dropped_and_counted() -> None:
    smoother = VelocitySmoother()
    smoother.command((0.3, 0.0, 0.0), 0.0)
    assert not smoother.command((math.nan, 0.0, 0.0), 0.01)
    assert not smoother.command((0.0, 0.0, math.inf), 0.02)
    assert smoother.rejected == 2
    vels = run(smoother, 0.5)
    assert vels[-1] == pytest.approx(0.3)


def test_scale_velocities_keeps_the_direction_of_the_change() -> None:
    params = SmootherParams(scale_velocities=True, max_accel=(0.5, 0.0, 3.2))
    smoother = VelocitySmoother(params)
    smoother.command((0.5, 0.0, 1.0), 0.0)
    out = smoother.update(0.0)
    assert out is not None
    assert out[0] == pytest.approx(0.5 / 20)
    assert out[2] / out[0] == pytest.approx(1.0 / 0.5)  # curvature kept, theta scaled down


def test_without_scaling_each_axis_ramps_on_its_own() -> None:
    smoother = VelocitySmoother(SmootherParams(max_accel=(0.5, 0.0, 3.2)))
    smoother.command((0.5, 0.0, 1.0), 0.0)
    out = smoother.update(0.0)
    assert out is not None
    assert out[0] == pytest.approx(0.5 / 20)
    assert out[2] == pytest.approx(3.2 / 20)


def test_a_new_command_after_stopping_starts_again() -> None:
    smoother = VelocitySmoother(SmootherParams(velocity_timeout=0.2))
    smoother.command((0.2, 0.0, 0.0), 0.0)
    run(smoother, 2.0)
    assert smoother.update(2.0) is None
    smoother.command((0.2, 0.0, 0.0), 2.05)
    out = smoother.update(2.1)
    assert out is not None
    assert out[0] == pytest.approx(0.125)


def test_an_update_sooner_than_a_period_moves_by_the_time_since_the_last() -> None:
    smoother = VelocitySmoother()
    smoother.command((0.5, 0.0, 0.0), 0.0)
    first = smoother.update(0.0)
    assert first is not None
    assert first[0] == pytest.approx(2.5 * PERIOD)  # the first: a whole period's worth
    sooner = smoother.update(0.03)
    assert sooner is not None
    assert sooner[0] == pytest.approx(2.5 * PERIOD + 2.5 * 0.03)
    late = smoother.update(0.03 + 3 * PERIOD)  # never more than a period's worth
    assert late is not None
    assert late[0] == pytest.approx(sooner[0] + 2.5 * PERIOD)
