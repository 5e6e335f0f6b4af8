"""bench.system.report's planner rows: the spread, and the first trip against the rest."""

from __future__ import annotations

from bench.system.report import Figures, planner_rows


def test_the_first_trip_is_shown_against_the_slowest_of_the_others() -> None:
    figures = Figures(round_trips=[0.080, 0.012, 0.045, 0.010])
    spread, first = planner_rows(figures)
    assert spread.startswith("| planner round trip ms p50 / p99 / max (n=4, failed 0) |")
    assert "| 80.0 / 45.0 |" in first


def test_with_one_trip_there_is_nothing_to_set_it_against() -> None:
    _, first = planner_rows(Figures(round_trips=[0.02]))
    assert "| n/a |" in first
