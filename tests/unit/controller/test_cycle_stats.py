"""The controller's per-goal cycle statistics."""

from __future__ import annotations

import math

import pytest

from aiobt_services.controller.cycle_stats import CycleSchedule, CycleStats


def test_rate_is_cycles_per_robot_second_and_percentiles_are_nearest_rank() -> None:
    stats = CycleStats(0.05)
    for i in range(11):  # 11 cycles over 0.6 robot s: one late by 0.1 s
        stats.record(i * 0.05 + (0.1 if i == 10 else 0.0), 0.001 * (i + 1), 0.0005 * (i + 1))
    assert stats.cycles == 11
    assert stats.rate() == pytest.approx(10 / 0.6)
    assert stats.percentile(50) == pytest.approx(0.006)
    assert stats.percentile(99) == pytest.approx(0.011)
    assert stats.cpu_percentile(99) == pytest.approx(0.0055)
    for update in (0.003, 0.004, 0.002):
        stats.record_update(update)
    assert stats.summary() == (
        "11 cycles, rate 16.67 of 20.00 Hz, cycle p50 6.00 ms p99 11.00 ms max 11.00 ms, "
        "cpu p50 3.00 ms p99 5.50 ms, costmap updates 3 p50 3.00 ms p99 4.00 ms, "
        "slots lost 2 (the sleeps before them: robot p50 nan ms, wall p50 nan ms p90 nan ms)"
    )


def test_too_few_cycles_have_no_rate_and_a_bad_period_is_refused() -> None:
    stats = CycleStats(0.1)
    assert math.isnan(stats.rate())
    assert math.isnan(stats.percentile(50))
    stats.record(3.0, 0.002)
    assert math.isnan(stats.rate())
    assert math.isnan(stats.cpu_percentile(50))  # none recorded
    with pytest.raises(ValueError, match="control period"):
        CycleStats(0.0)


def test_the_schedule_keeps_the_period_from_deadline_to_deadline() -> None:
    schedule = CycleSchedule(0.05, 1.0)
    assert schedule.delay(1.0) == pytest.approx(0.05)  # the work took no clock time
    assert schedule.delay(1.07) == pytest.approx(0.03)  # woke 0.02 late, worked: due 1.10
    assert schedule.delay(1.12) == pytest.approx(0.03)  # due 1.15
    assert schedule.delay(1.17) == pytest.approx(0.03)  # due 1.20
    assert schedule.delay(1.27) == 0.0  # 1.25 was due already: the next at once
    assert schedule.delay(1.27) == pytest.approx(0.03)  # on schedule again: due 1.30


def test_a_cycle_a_period_behind_starts_the_schedule_over_and_so_does_a_clock_reset() -> None:
    schedule = CycleSchedule(0.05, 0.0)
    assert schedule.delay(0.3) == 0.0  # 0.25 s late: no burst of catch-up cycles
    assert schedule.delay(0.3) == pytest.approx(0.05)  # from 0.3 on
    assert schedule.delay(0.01) == pytest.approx(0.05)  # the clock went back: from now
    assert schedule.delay(0.06) == pytest.approx(0.05)
    with pytest.raises(ValueError, match="period"):
        CycleSchedule(0.0, 0.0)


def test_slots_lost_are_counted_with_the_sleeps_before_them() -> None:
    stats = CycleStats(0.05)
    stats.record(0.0, 0.001)
    stats.record_sleep(0.05, 0.005)  # on time at 10x
    stats.record(0.05, 0.001)
    stats.record_sleep(0.15, 0.006)  # robot time ran 25x: two slots skipped
    stats.record(0.20, 0.001)
    stats.record_sleep(0.10, 0.010)  # woke a period late at 10x: one slot skipped
    stats.record(0.30, 0.001)
    stats.record_sleep(0.09, 0.009)  # late, under a period: its slot kept
    stats.record(0.39, 0.001)
    assert stats.summary().endswith(
        "slots lost 3 (the sleeps before them: robot p50 100 ms, wall p50 6.0 ms p90 10.0 ms)"
    )


def test_a_goal_without_lost_slots_has_no_empty_sleep_figures() -> None:
    stats = CycleStats(0.05)
    for i in range(5):
        stats.record(i * 0.05, 0.001)
    assert stats.summary().endswith(", slots lost 0")
