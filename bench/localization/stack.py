"""The navigation stack with localization in the loop: the robot publishing no pose
in map (``--pose-source none``) and the localization service giving ``{ns}/pose``.

Until the localization service is in ``aiobt.system.catalog`` (and so an ``aiobt``
command), it starts as ``python -m aiobt_services.localization``.
"""

from __future__ import annotations

from dataclasses import dataclass, field

from aiobt.testing.stack import StackConfig

NAVIGATION = ("localization", "planner", "controller", "behaviors", "navigator")
SERVICES = ("robot", *NAVIGATION)
START = (2.0, 9.75, 0.0)  # the office world's start


@dataclass(slots=True)
class LocalizedStackConfig(StackConfig):
    """A :class:`StackConfig` whose stack includes the localization service."""

    services: tuple[str, ...] = SERVICES
    localization: list[str] = field(default_factory=list)  # its flags

    def command(self, service: str, endpoint: str, namespace: str) -> list[str]:
        if service == "robot":
            return [
                *StackConfig.command(self, service, endpoint, namespace),
                "--pose-source",
                "none",
            ]
        if service != "localization":
            return StackConfig.command(self, service, endpoint, namespace)
        x, y, yaw = START
        return ["-m", "aiobt_services.localization", "--connect", endpoint,
                "--namespace", namespace, "--lease-ms", str(self.lease_ms),
                "--set", "set_initial_pose=true",
                "--set", f"initial_pose={{x: {x}, y: {y}, yaw: {yaw}}}",
                *self.localization]  # fmt: skip
