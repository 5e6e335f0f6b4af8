"""Processes started by the test spawner die with their parent, however it ends.

The parent is a real process (lifeline_parent.py) that starts a real router and a
service with ``aiobt.testing.bus``; the test signals it and waits, on pidfds, for
its children. (test_up.py checks the same of ``aiobt up``'s children.)
"""

from __future__ import annotations

import contextlib
import os
import signal
import subprocess
import sys
from collections.abc import Iterator
from pathlib import Path
from typing import Any

import pytest

from tests.integration.system.helpers import wait_gone

pytestmark = [pytest.mark.integration, pytest.mark.timeout(120)]
PARENT = "tests.integration.system.lifeline_parent"
ROOT = Path(__file__).resolve().parents[3]


@contextlib.contextmanager
def started(
    command: list[str], **options: Any
) -> Iterator[tuple[subprocess.Popen[str], list[int]]]:
    """``command`` started, with the pids its output names on a line ``pids ...``
    (once its children serve); after: it and any of them left killed by PID."""
    pids: list[int] = []
    with subprocess.Popen(command, stdout=subprocess.PIPE, text=True, **options) as proc:
        try:  # its pipes closed on the way out
            assert proc.stdout is not None
            lines = [""]
            for line in proc.stdout:  # bounded by its own waits (and the test's timeout)
                lines.append(line)
                if line.startswith("pids "):
                    break
            assert lines[-1].startswith("pids "), "".join(lines)
            pids = [int(word) for word in lines[-1].split()[1:]]
            yield proc, pids
        finally:
            if proc.poll() is None:
                proc.kill()
            proc.wait(10)
            for pid in wait_gone(pids, 0.0):
                os.kill(pid, signal.SIGKILL)


def parent(
    *flags: str,
) -> contextlib.AbstractContextManager[tuple[subprocess.Popen[str], list[int]]]:
    return started([sys.executable, "-m", PARENT, *flags], stdin=subprocess.PIPE)


@pytest.mark.parametrize("sig", [signal.SIGTERM, signal.SIGKILL])
def test_the_children_of_a_killed_parent_exit(sig: signal.Signals) -> None:
    with parent() as (proc, children):
        proc.send_signal(sig)
        assert proc.wait(10) == -sig  # its finally did not run: the children are on their own
        assert wait_gone(children, 20.0) == []


def test_children_started_on_a_thread_outlive_it_and_die_with_the_process() -> None:
    with parent("--from-thread") as (proc, children):  # they served after the thread ended
        proc.kill()
        assert wait_gone(children, 20.0) == []


def test_a_parent_that_ends_normally_stops_its_children_gracefully() -> None:
    with parent() as (proc, children):
        assert proc.stdin is not None
        assert proc.stdout is not None
        proc.stdin.close()
        assert proc.stdout.read().split() == ["stopped", "0", "0"]
        assert proc.wait(30) == 0
        assert wait_gone(children, 0.0) == []


def test_exit_on_sigterm_stops_the_children_as_the_normal_path_does() -> None:
    with parent("--exit-on-sigterm") as (proc, children):
        assert proc.stdout is not None
        proc.send_signal(signal.SIGTERM)
        assert proc.stdout.read().split() == ["stopped", "0", "0"]
        assert proc.wait(30) == 128 + signal.SIGTERM
        assert wait_gone(children, 0.0) == []


INNER_TEST = """
import time
import pytest
from aiobt.testing.bus import start_router

@pytest.fixture
def router():
    proc, _ = start_router()
    assert proc.wait_for_output("listening on", 30.0)  # its SIGTERM handler is set
    yield proc
    print("stopped", proc.stop(), flush=True)

def test_serves(router):
    print("pids", router.pid, flush=True)
    time.sleep(100)  # what the SIGTERM interrupts
"""


def test_a_sigterm_to_pytest_tears_its_fixtures_down(tmp_path: Path) -> None:
    """tests/conftest.py turns SIGTERM into Ctrl-C: the router fixture stops its router."""
    (tmp_path / "test_inner.py").write_text(INNER_TEST)
    (tmp_path / "pytest.ini").write_text("[pytest]\n")
    conftest = ["-p", "tests.conftest", "-p", "no:cacheprovider", "-p", "no:randomly"]
    command = [sys.executable, "-m", "pytest", "-s", "-q", *conftest, "-c", "pytest.ini"]
    env = {**os.environ, "PYTHONPATH": str(ROOT)}
    with started(command, cwd=tmp_path, env=env) as (pytest_run, pids):
        assert pytest_run.stdout is not None
        pytest_run.send_signal(signal.SIGTERM)
        output = pytest_run.stdout.read()
        assert pytest_run.wait(30) == pytest.ExitCode.INTERRUPTED, output
        assert "stopped 0" in output
        assert wait_gone(pids, 0.0) == []
