"""What tests of service processes share: their bus flags and a wait for them to be up."""

from __future__ import annotations

import pytest

from aiobt.testing.bus import ServiceProcess
from aiobt.transport import Bus, BusSettings

# the robot's own {ns}/pose (the truth: a perfect localization), for tests of a service
# that reads the pose without the localization service in the loop
TRUTH = ("--pose-source", "truth")


def common(settings: BusSettings) -> list[str]:
    """The flags that put a service on the test's router and namespace."""
    return ["--connect", settings.connect[0], "--namespace", settings.namespace]


async def up(bus: Bus, name: str, proc: ServiceProcess) -> None:
    """Wait (30 s at most) for ``nodes/{name}``; fail with the process's output if not."""
    if not await bus.presence(bus.keys.topic(f"nodes/{name}")).wait(30.0):
        pytest.fail(f"{name} did not come up:\n{proc.output()}")
