"""The deployment across hosts (tests/netlab/deployment.py), shared by a module's tests."""

from __future__ import annotations

from collections.abc import Iterator

import pytest

from tests.netlab.deployment import UP_TIMEOUT, Deployment, deployment


@pytest.fixture(scope="module")
def deployed(tmp_path_factory: pytest.TempPathFactory) -> Iterator[Deployment]:
    with deployment(tmp_path_factory.mktemp("deployment")) as lab:
        for host, up in lab.ups.items():
            if not up.wait_for_output("up on namespace 'robot'", UP_TIMEOUT):
                pytest.fail(f"the {host} host's share did not come up:\n{lab.logs()}")
        # the base host has the map and the robot's pose (its planner plans from them)
        ready = lab.scenario("base", "web", ["map", "--pose", "--timeout", "60"])
        if not ready.wait_for_output('"event": "map"', 70.0):
            pytest.fail(f"the robot's map and pose did not reach the base host:\n{lab.logs()}")
        yield lab
