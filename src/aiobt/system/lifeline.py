"""Children die with the process that started them, even one killed with SIGKILL.

Two bindings, both Linux's parent-death signal (``prctl(PR_SET_PDEATHSIG)``),
SIGTERM, so a child still closes its session and files:

- :func:`popen_bound` (the test and benchmark spawner, ``aiobt.testing.bus``):
  the child asks for it between fork and exec, whatever program it then runs;
  the signal fires when the *thread* that forked it ends, so the fork is done on
  the main thread, or on one that lives as long as the process.
- ``aiobt up``'s supervisor puts its pid in the child's environment
  (:func:`child_env`); the child, as it starts (``aiobt``'s ``main``), binds
  itself (:func:`die_with_supervisor`): bound to the thread that runs the
  supervisor's loop, the main thread of ``aiobt up`` and ``aiobt demo``. The
  variable is taken out of the environment: the child's own children are not bound.

Both exit at once if the parent is already gone. Off Linux neither binds, and
nothing is bound unless the spawner asks: a service in its own container
(docker-compose) has no parent to die with.
"""

from __future__ import annotations

import ctypes
import functools
import logging
import os
import queue
import signal
import subprocess
import sys
import threading
from collections.abc import Callable, Sequence
from concurrent.futures import Future
from typing import Any, TypeVar

log = logging.getLogger("aiobt.system.lifeline")
PARENT_ENV = "AIOBT_SUPERVISOR_PID"
_PR_SET_PDEATHSIG = 1  # linux/prctl.h
_LINUX = sys.platform.startswith("linux")
T = TypeVar("T")


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
    if not _LINUX:
        log.debug(
            "no parent-death signal on %s: an orphan outlives a killed supervisor", sys.platform
        )
        return
    if _prctl()(_PR_SET_PDEATHSIG, int(sig), 0, 0, 0) != 0:
        log.warning("prctl(PR_SET_PDEATHSIG) failed: %s", os.strerror(ctypes.get_errno()))
        return
    if os.getppid() != int(value):  # the supervisor died before the prctl
        raise SystemExit(f"aiobt: the supervisor (pid {value}) is gone: not starting")


def popen_bound(argv: Sequence[str], **options: Any) -> subprocess.Popen[Any]:
    """``subprocess.Popen(argv, **options)``, the child bound to this process: SIGTERM
    when this process ends, however (off Linux: a plain ``Popen``)."""
    if not _LINUX:
        return subprocess.Popen(argv, **options)
    bind = functools.partial(_bind_to, os.getpid(), _prctl())
    return on_lasting_thread(functools.partial(subprocess.Popen, argv, preexec_fn=bind, **options))


def _bind_to(parent: int, prctl: Callable[..., int]) -> None:
    """In the child, between fork and exec (``preexec_fn``): nothing here may log."""
    prctl(_PR_SET_PDEATHSIG, int(signal.SIGTERM), 0, 0, 0)
    if os.getppid() != parent:  # the parent died before the prctl
        os._exit(128 + signal.SIGTERM)


@functools.cache
def _prctl() -> Callable[..., int]:
    """libc's ``prctl``, looked up in the parent (not after a fork)."""
    function: Callable[..., int] = ctypes.CDLL(None, use_errno=True).prctl
    return function


def on_lasting_thread(start: Callable[[], T]) -> T:
    """``start()`` on a thread that lives as long as the process: this one if it is
    the main thread, else one kept for the purpose (a parent-death signal fires
    when the thread that forked the child ends, not the process)."""
    if threading.current_thread() is threading.main_thread():
        return start()
    done: Future[T] = Future()
    _forker().put((start, done))
    return done.result()


_Request = tuple[Callable[[], Any], "Future[Any]"]
_requests: queue.SimpleQueue[_Request] | None = None
_forker_lock = threading.Lock()


def _forker() -> queue.SimpleQueue[_Request]:
    """The kept thread's queue (the thread started on first use; a daemon, blocked
    in ``get`` until the process ends)."""
    global _requests
    with _forker_lock:
        if _requests is None:
            _requests = queue.SimpleQueue()
            threading.Thread(
                target=_serve, args=(_requests,), name="aiobt-forker", daemon=True
            ).start()
        return _requests


def _serve(requests: queue.SimpleQueue[_Request]) -> None:
    while True:
        start, done = requests.get()
        try:
            done.set_result(start())
        except BaseException as exc:  # handed to the caller's thread
            done.set_exception(exc)
