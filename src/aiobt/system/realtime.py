"""Soft real-time priority for a service's whole process: Nav2's ``use_realtime_priority``.

Nav2's controller server can run its control loop's thread under ``SCHED_FIFO`` at
priority 90, "to better ensure resources to time sensitive portions of the codebase"
(off by default; the user grants the right with an ``rtprio`` limit). Here the
option is ``--realtime-priority [N]`` on the robot, the controller, the velocity
smoother and the collision monitor (between the controller and the base), the
planner, the navigator and ``aiobt router``.

On a loaded machine a ``SCHED_FIFO`` thread that wakes runs at once, ahead of every
ordinary process, instead of waiting its turn: the control loop keeps its rate and
the simulation its pace. The whole process is raised, not the event loop's thread
alone: :func:`raise_priority` runs before the bus is opened, so Zenoh's threads (which
receive the poses, odometry and commands the loop acts on) and every thread started
later (the controller's costmap worker, the planner's searches) inherit it. Raising
the loop alone, as Nav2 raises its executor thread, was measured at 10x on 2 cores
(``bench/RESULTS.md``): the loop then outran its own transport threads, which
delivered the robot's state late, and in 11 of 16 runs a goal failed to make
progress or the robot bumped into a box it should have stopped for; with the whole
process raised, in none of 16 (nor in 17 runs without the option). The services
block between their cycles (the loop in ``epoll``, the robot between steps), so they
leave the CPU to the others; the kernel's real-time throttling
(``sched_rt_runtime_us``, 95 % by default) bounds a runaway one.

Priorities order the services when both want a core: the robot (the hardware's
stand-in: its clock is everyone's) and the controller at 90 (Nav2's), the planner
below them at 70 (a search may take tens of milliseconds; it must not hold off a
control cycle), the navigator at 60 below them all. The navigator asks for the plans
and paths: on a machine with other busy processes, plans from a raised planner still
waited for the ordinary process that asked for them (round trip p99 39-64 ms against
24-36 ms with the asker raised, ``bench/RESULTS.md``). ``aiobt router`` takes the
option too (60): with the asker raised and the router not, the router's turn came
later and the control rate fell; raised alone, the plans waited longer. Without the
right to use ``SCHED_FIFO`` the service stops with an error naming the fix, as Nav2's
does.
"""

from __future__ import annotations

import argparse
import os

PRIORITY_MIN, PRIORITY_MAX = 1, 99
# the priority ``--realtime-priority`` alone gives ``aiobt router``; each service's is in
# :mod:`aiobt.system.catalog`, beside the service (see the module's docstring)
ROUTER_PRIORITY = 60  # ``aiobt router``: the services' messages all pass through it


class RealtimePriorityError(Exception):
    """``SCHED_FIFO`` could not be set (no permission, or not Linux)."""


def priority(text: str) -> int:
    """argparse type: a ``SCHED_FIFO`` priority, an integer in 1..99."""
    try:
        value = int(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"must be an integer in 1..99, got {text!r}") from None
    if not PRIORITY_MIN <= value <= PRIORITY_MAX:
        raise argparse.ArgumentTypeError(f"must be an integer in 1..99, got {value}")
    return value


def add_realtime_argument(parser: argparse.ArgumentParser | argparse._ArgumentGroup,
                          default: int) -> None:  # fmt: skip
    """``--realtime-priority [N]`` (off unless given; given alone: ``default``)."""
    parser.add_argument(
        "--realtime-priority",
        nargs="?",
        type=priority,
        const=default,
        metavar="N",
        help="run the service (its event loop, Zenoh's threads and the threads it starts) "
        f"under SCHED_FIFO at priority N, 1..99 (Nav2's use_realtime_priority; N defaults "
        f"to {default}); needs CAP_SYS_NICE or an rtprio limit (/etc/security/limits.conf: "
        "'<user> - rtprio 99')",
    )


def raise_priority(level: int) -> None:
    """Put the calling thread, and the threads it starts from then on, under
    ``SCHED_FIFO`` at ``level``; RealtimePriorityError (naming the fix) if the system
    does not allow it."""
    setter = getattr(os, "sched_setscheduler", None)
    fifo = getattr(os, "SCHED_FIFO", None)
    if setter is None or fifo is None:
        raise RealtimePriorityError(
            f"--realtime-priority {level}: SCHED_FIFO is not available on this system "
            "(Linux only); run without it"
        )
    try:
        setter(0, fifo, os.sched_param(level))
    except PermissionError:
        raise RealtimePriorityError(
            f"--realtime-priority {level}: not permitted to use SCHED_FIFO (needs CAP_SYS_NICE "
            "or an rtprio limit: '<user> - rtprio 99' in /etc/security/limits.conf, or "
            "'cap_add: [SYS_NICE]' in docker-compose); run without it"
        ) from None
    except OSError as exc:
        raise RealtimePriorityError(f"--realtime-priority {level}: {exc}") from None


def realtime_if_asked(level: int | None) -> str:
    """:func:`raise_priority` to ``level`` unless None; the words for the service's "up"
    line ("" when not asked)."""
    if level is None:
        return ""
    raise_priority(level)
    return f", real-time priority {level} (SCHED_FIFO)"
