"""A robot host and a base host, a router each, joined router to router (through a
link proxy), with mutual TLS and access control; a laptop host sends goals."""

from __future__ import annotations

import math

import pytest

from tests.netlab.deployment import Deployment, event

pytestmark = [pytest.mark.e2e, pytest.mark.integration]
START = (2.0, 9.75)
CORRIDOR = (6.0, 9.75, 0.0)  # 4 m east along the corridor


@pytest.mark.timeout(120)
def test_the_map_reaches_the_base_host(deployed: Deployment) -> None:
    watcher = deployed.scenario("base", "web", ["map", "--timeout", "60"])
    assert watcher.wait_for_output('"event": "map"', 70.0), deployed.logs()
    found = event(watcher, "map")
    assert found is not None
    assert found["width"] > 0
    assert found["height"] > 0


@pytest.mark.timeout(200)
def test_a_goal_from_the_laptop_is_reached(deployed: Deployment) -> None:
    nav = deployed.scenario(
        "laptop", "laptop", ["navigate", *map(str, CORRIDOR), "--timeout", "120"]
    )
    assert nav.wait_for_output('"event": "result"', 170.0), deployed.logs()
    result = event(nav, "result")
    assert result is not None
    assert result["state"] == "SUCCEEDED", (result, deployed.logs())
    assert math.dist((result["x"], result["y"]), CORRIDOR[:2]) < 0.5, result


@pytest.mark.timeout(200)
def test_a_goal_from_the_zenoh_command_line_on_the_laptop_is_reached(deployed: Deployment) -> None:
    x, y = START
    watcher = deployed.scenario("laptop", "laptop", ["reach", str(x), str(y), "--timeout", "150"])
    assert watcher.wait_for_output('"event": "watching"', 60.0), deployed.logs()
    put = deployed.zenoh_cli(
        "laptop", ["put", "-k", "robot/goal_pose", "-v", f'{{"x": {x}, "y": {y}, "yaw": 0.0}}']
    )
    assert put.popen.wait(30.0) == 0, put.output()
    assert watcher.wait_for_output('"event": "reached"', 160.0), deployed.logs()


def test_no_service_was_denied_anything(deployed: Deployment) -> None:
    """The rules let a working deployment work: neither router denied its services."""
    for host, up in deployed.ups.items():
        denied = [
            line for line in up.output().splitlines() if "denied" in line or "refused" in line
        ]
        assert not denied, (host, denied[:20])
