"""A supervised child binds itself to its supervisor, or refuses to start without one;
a child of :func:`popen_bound` is bound between fork and exec, forked on a lasting thread.

Run in subprocesses: the parent-death signal must not be set on pytest itself.
(tests/integration/system/test_up.py SIGKILLs a real ``aiobt up`` and checks its
children exit.)
"""

from __future__ import annotations

import os
import signal
import subprocess
import sys
import threading

import pytest

from aiobt.system.lifeline import PARENT_ENV, child_env, on_lasting_thread, popen_bound

BIND = (
    "import os; from aiobt.system.lifeline import die_with_supervisor as d; d();"
    f"print({PARENT_ENV!r} in os.environ)"
)


def _child(value: str) -> subprocess.CompletedProcess[str]:
    env = {**os.environ, PARENT_ENV: value}
    command = [sys.executable, "-c", BIND]
    return subprocess.run(command, env=env, capture_output=True, text=True, timeout=60)


def test_child_env_names_this_process() -> None:
    assert child_env() == {PARENT_ENV: str(os.getpid())}


def test_a_child_of_its_supervisor_starts_and_does_not_pass_the_binding_on() -> None:
    done = _child(str(os.getpid()))
    assert (done.returncode, done.stdout.strip()) == (0, "False"), done.stderr


def test_a_child_whose_supervisor_is_gone_refuses_to_start() -> None:
    done = _child("999999999")
    assert done.returncode == 1
    assert done.stderr.strip() == "aiobt: the supervisor (pid 999999999) is gone: not starting"


def test_a_bad_pid_is_named_and_ignored() -> None:
    done = _child("x1")
    assert done.returncode == 0
    assert f"{PARENT_ENV}='x1' is not a process id" in done.stderr


DEATH_SIGNAL = (  # PR_GET_PDEATHSIG (2): the signal this process gets when its parent dies
    "import ctypes; s = ctypes.c_int(); ctypes.CDLL(None).prctl(2, ctypes.byref(s), 0, 0, 0);"
    "print(s.value)"
)


@pytest.mark.skipif(not sys.platform.startswith("linux"), reason="prctl is Linux's")
def test_a_bound_child_gets_sigterm_when_its_parent_dies_and_a_plain_one_nothing() -> None:
    command = [sys.executable, "-c", DEATH_SIGNAL]
    with popen_bound(command, stdout=subprocess.PIPE, text=True) as bound:
        assert bound.communicate(timeout=60)[0].strip() == str(int(signal.SIGTERM))
    plain = subprocess.run(command, capture_output=True, text=True, timeout=60, check=True)
    assert plain.stdout.strip() == "0"


def test_the_main_thread_forks_itself() -> None:
    assert on_lasting_thread(threading.current_thread) is threading.main_thread()


def test_another_thread_hands_its_fork_to_one_kept_thread_and_gets_its_errors() -> None:
    seen: list[threading.Thread] = []
    errors: list[BaseException] = []

    def fork_twice() -> None:
        seen.extend(on_lasting_thread(threading.current_thread) for _ in range(2))
        try:
            on_lasting_thread(lambda: 1 / 0)
        except ZeroDivisionError as exc:
            errors.append(exc)

    for _ in range(2):  # two short-lived threads, one kept thread
        caller = threading.Thread(target=fork_twice)
        caller.start()
        caller.join(30)
    assert len(errors) == 2
    assert len(set(seen)) == 1
    [kept] = set(seen)
    assert kept.name == "aiobt-forker"
    assert kept.is_alive()
