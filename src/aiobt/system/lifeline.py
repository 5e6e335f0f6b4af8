"""A supervised child dies with its supervisor, even one killed with SIGKILL (no orphans).

The supervisor puts its pid in the child's environment (:func:`child_env`); the
child, as it starts (``aiobt``'s ``main``), asks Linux for a signal when its
parent dies (``prctl(PR_SET_PDEATHSIG)``) and exits at once if the parent is
already gone. SIGTERM, so a service still closes its session and files. The
variable is taken out of the environment: the child's own children are not bound.
"""

from __future__ import annotations

import ctypes
import logging
import os
import signal
import sys

log = logging.getLogger("aiobt.system.lifeline")
PARENT_ENV = "AIOBT_SUPERVISOR_PID"
_PR_SET_PDEATHSIG = 1  # linux/prctl.h


def child_env() -> dict[str, str]:
    """The environment entry that binds a child started now to this process."""
    return {PARENT_ENV: str(os.getpid())}


def die_with_supervisor(sig: signal.Signals = signal.SIGTERM) -> None:
    """In a child started by the supervisor: ``sig`` when the supervisor dies; exit
    now if it died already. Does nothing outside a supervisor or off Linux."""
    value = os.environ.pop(PARENT_ENV, None)
    if value is None:
        return
    if not value.isdigit():
        log.warning("%s=%r is not a process id: not bound to the supervisor", PARENT_ENV, value)
        return
    if not sys.platform.startswith("linux"):
        log.debug(
            "no parent-death signal on %s: an orphan outlives a killed supervisor", sys.platform
        )
        return
    libc = ctypes.CDLL(None, use_errno=True)
    if libc.prctl(_PR_SET_PDEATHSIG, int(sig), 0, 0, 0) != 0:
        log.warning("prctl(PR_SET_PDEATHSIG) failed: %s", os.strerror(ctypes.get_errno()))
        return
    if os.getppid() != int(value):  # the supervisor died before the prctl
        raise SystemExit(f"aiobt: the supervisor (pid {value}) is gone: not starting")
