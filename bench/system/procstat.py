"""CPU time of processes from ``/proc/<pid>/stat``, as % of one core over a phase."""

from __future__ import annotations

import contextlib
import os
import time
from collections.abc import Iterable, Mapping
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


@dataclass(frozen=True, slots=True)
class Machine:
    """Every process's CPU seconds (``/proc/<pid>/stat``, by pid) and the CPU seconds
    stolen by the hypervisor (``/proc/stat``, all cores summed)."""

    wall: float
    cpu: dict[int, float]
    steal: float


def machine() -> Machine:
    cpu: dict[int, float] = {}
    for entry in os.scandir("/proc"):
        if entry.name.isdigit():
            with contextlib.suppress(OSError, ValueError, IndexError):  # gone meanwhile
                cpu[int(entry.name)] = cpu_seconds(int(entry.name))
    with open("/proc/stat") as source:
        return Machine(time.monotonic(), cpu, stolen_seconds(source.readline()))


def stolen_seconds(line: str) -> float:
    """``/proc/stat``'s ``cpu`` line: user nice system idle iowait irq softirq steal ..."""
    name, *ticks = line.split()
    if name != "cpu" or len(ticks) < 8:
        raise ValueError(f"not /proc/stat's all-cores line: {line!r}")
    return int(ticks[7]) / TICKS


def others_percent(first: Machine, last: Machine, stack: Iterable[int]) -> tuple[float, float]:
    """Between two samples, in % of one core: the CPU of every process but ``stack``'s
    (one started meanwhile counts whole; one that ended meanwhile is missed), and the CPU
    stolen. Per process, not ``/proc/stat``'s busy time: beside one spinning process that
    read 117-124 % of a core in the idle phase, where the processes' own times give 100.5."""
    wall = last.wall - first.wall
    if wall <= 0.0:
        raise ValueError(f"samples must be taken in order, got {wall:.3f} s apart")
    skip = set(stack)
    used = sum(cpu - first.cpu.get(pid, 0.0) for pid, cpu in last.cpu.items() if pid not in skip)
    return 100.0 * used / wall, 100.0 * (last.steal - first.steal) / wall
