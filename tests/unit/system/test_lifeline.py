"""A supervised child binds itself to its supervisor, or refuses to start without one.

Run in subprocesses: the parent-death signal must not be set on pytest itself.
(tests/integration/system/test_up.py SIGKILLs a real ``aiobt up`` and checks its
children exit.)
"""

from __future__ import annotations

import os
import subprocess
import sys

from aiobt.system.lifeline import PARENT_ENV, child_env

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
