"""The controller's per-goal cycle statistics."""

from __future__ import annotations

import math

import pytest

from aiobt_services.controller.cycle_stats import CycleStats


def test_rate_is_cycles_per_robot_second_and_percentiles_are_nearest_rank() -> None:
    stats = CycleStats(0.05)
    for i in range(11):  # 11 cycles over 0.6 robot s: one late by 0.1 s
        stats.record(i * 0.05 + (0.1 if i == 10 else 0.0), 0.001 * (i + 1))
    assert stats.cycles == 11
    assert stats.rate() == pytest.approx(10 / 0.6)
    assert stats.percentile(50) == pytest.approx(0.006)
    assert stats.percentile(99) == pytest.approx(0.011)
    assert stats.summary() == (
        "11 cycles, rate 16.67 of 20.00 Hz, cycle p50 6.00 ms p99 11.00 ms max 11.00 ms"
    )


def test_too_few_cycles_have_no_rate_and_a_bad_period_is_refused() -> None:
    stats = CycleStats(0.1)
    assert math.isnan(stats.rate())
    assert math.isnan(stats.percentile(50))
    stats.record(3.0, 0.002)
    assert math.isnan(stats.rate())
    with pytest.raises(ValueError, match="control period"):
        CycleStats(0.0)
