"""CPU time of processes from ``/proc/<pid>/stat``, as % of one core over a phase."""

from __future__ import annotations

import os
import time
from collections.abc import Mapping
from dataclasses import dataclass

TICKS = os.sysconf("SC_CLK_TCK")


def cpu_seconds(pid: int) -> float:
    """User + system CPU seconds of process ``pid`` (its threads included)."""
    with open(f"/proc/{pid}/stat") as source:
        text = source.read()
    fields = text[text.rindex(")") + 2 :].split()  # the command may hold spaces
    return (int(fields[11]) + int(fields[12])) / TICKS  # utime, stime: fields 14, 15


@dataclass(frozen=True, slots=True)
class Sample:
    wall: float
    cpu: dict[str, float]


def sample(pids: Mapping[str, int]) -> Sample:
    return Sample(time.monotonic(), {name: cpu_seconds(pid) for name, pid in pids.items()})


def percent_of_core(first: Sample, last: Sample) -> dict[str, float]:
    """Each process's CPU between two samples, in % of one core."""
    wall = last.wall - first.wall
    if wall <= 0.0:
        raise ValueError(f"samples must be taken in order, got {wall:.3f} s apart")
    return {name: 100.0 * (last.cpu[name] - first.cpu[name]) / wall for name in first.cpu}
