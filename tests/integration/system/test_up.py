"""``aiobt up`` as a user runs it: the system comes up, stops fast, and bad input is named."""

from __future__ import annotations

import signal
import socket
from collections.abc import Iterator
from pathlib import Path

import pytest

from aiobt.testing.bus import free_endpoint, port_of

from .helpers import SystemProcess, kill_mentioning, processes_mentioning, wait_gone

pytestmark = [pytest.mark.integration, pytest.mark.timeout(180)]


@pytest.fixture
def endpoint() -> Iterator[str]:
    """A free loopback endpoint; every process still mentioning it is killed at the end."""
    chosen = free_endpoint()
    yield chosen
    kill_mentioning(chosen)


def test_up_brings_every_service_up_and_stops_everything_in_under_3_s(
    endpoint: str, tmp_path: Path
) -> None:
    config = tmp_path / "system.yaml"
    config.write_text(f"world: small\nspeed: 2\nrouter: {{listen: '{endpoint}'}}\n")
    with SystemProcess(["up", "--config", str(config), "--namespace", "upt"]) as up:
        ready = up.wait_line("     up * ")
        assert "robot, localization, planner, controller, behaviors" in ready
        assert "up on namespace 'upt' (sim time x2)" in ready
        for name in ("router", "robot", "localization", "planner", "controller", "behaviors"):
            up.wait_line(f"{name:>10} * up", timeout=1.0)
        assert len(processes_mentioning(endpoint)) >= 5
        code, seconds = up.stop(signal.SIGTERM)
    assert code == 0
    assert seconds < 3.0
    assert processes_mentioning(endpoint) == []


def test_a_sigkilled_up_leaves_no_process_behind(endpoint: str) -> None:
    """Its children die with it (parent-death signal): no orphan services or router."""
    with SystemProcess(["up", "--listen", endpoint, "--world", "small"]) as up:
        up.wait_line("     up * ")
        children = [int(line.split(":", 1)[0]) for line in processes_mentioning(endpoint)]
        assert len(children) >= 7  # router, robot, localization, planner, controller, ...
        up.proc.kill()
        assert up.proc.wait(10) == -signal.SIGKILL
        left = wait_gone(children, timeout=30.0)
    assert left == [], processes_mentioning(endpoint)


def test_a_service_that_cannot_start_is_named_in_one_line_and_nothing_is_left(
    endpoint: str, tmp_path: Path
) -> None:
    world = str(tmp_path / "nowhere.yaml")
    with SystemProcess(["up", "--listen", endpoint, "--world", world]) as up:
        code, err = up.finish()
    assert code == 1
    [line] = err.strip().splitlines()
    assert line.startswith("aiobt up: robot failed to start (exited with code 2: ")
    assert "nowhere.yaml" in line
    assert processes_mentioning(endpoint) == []


def test_a_taken_router_port_is_named(endpoint: str) -> None:
    with socket.socket() as taken:
        taken.bind(("127.0.0.1", port_of(endpoint)))
        taken.listen()
        with SystemProcess(["up", "--listen", endpoint]) as up:
            code, err = up.finish()
    assert code == 1
    assert err.strip() == (
        f"aiobt up: router.listen {endpoint}: the port is already in use (another router? "
        "set router.start: false to use it, or choose another port)"
    )
    assert processes_mentioning(endpoint) == []


def test_no_router_to_use_is_named(endpoint: str, tmp_path: Path) -> None:
    config = tmp_path / "system.yaml"
    config.write_text(f"router: {{listen: '{endpoint}', start: false}}\n")
    with SystemProcess(["up", "--config", str(config)]) as up:
        code, err = up.finish()
    assert code == 1
    assert err.strip().splitlines()[-1].startswith(f"aiobt up: no Zenoh router at {endpoint}: ")
    assert processes_mentioning(endpoint) == []


def test_a_bad_config_key_is_named_and_nothing_starts(endpoint: str, tmp_path: Path) -> None:
    config = tmp_path / "system.yaml"
    config.write_text(f"router: {{listen: '{endpoint}'}}\nservices: {{robot: {{args: 3}}}}\n")
    with SystemProcess(["up", "--config", str(config)]) as up:
        code, err = up.finish()
    assert code == 2
    assert err.strip() == f"aiobt up: {config}: services.robot.args must be a list of strings"
