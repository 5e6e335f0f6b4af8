"""Ratios of several runs of one benchmark, summarised against the issue's targets."""

from __future__ import annotations

import os
import statistics


def load() -> str:
    """The 1-minute load average: the ratios rise when other processes want the CPU."""
    return f"{os.getloadavg()[0]:.2f}"


def summarize(ratios: dict[str, list[float]], targets: dict[str, float], loads: list[str]) -> str:
    """One row per probe: its ratio in every run, the median and how many runs met the target."""
    lines = [
        f"{len(loads)} runs, load average after each: {' '.join(loads)}",
        "",
        "| probe | target | median | range | runs within target | every run |",
        "|---|---|---|---|---|---|",
    ]
    for name, values in ratios.items():
        target = targets.get(name)
        within = f"{sum(v <= target for v in values)} of {len(values)}" if target else "-"
        lines.append(
            f"| {name} | {f'{target:.1f}x' if target else '-'} | {statistics.median(values):.2f}x "
            f"| {min(values):.2f}x-{max(values):.2f}x | {within} "
            f"| {' '.join(f'{v:.3f}' for v in values)} |"
        )
    return "\n".join(lines)
