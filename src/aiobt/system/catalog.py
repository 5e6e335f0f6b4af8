"""The one list of services: every other list is made from it.

The ``aiobt`` command's service sub-commands, the keys of ``aiobt up``'s
``services:`` section and the order it starts them in, the ``--realtime-priority``
default of each, and the services of ``docker-compose.yml`` (checked by a test)
all come from :data:`SERVICES`. A service is named by its module path only: the
library never imports ``aiobt_services``; the launcher imports a service's module
when its command runs.
"""

from __future__ import annotations

from dataclasses import dataclass


@dataclass(frozen=True, slots=True)
class ServiceSpec:
    """One service program: ``aiobt NAME`` runs ``aiobt_services.NAME.main``."""

    name: str
    summary: str
    realtime_priority: int | None = None  # --realtime-priority given alone; None: no option
    simulation: bool = False  # it is the clock's source (takes --world and --speed, not --sim-time)
    enabled: bool = True  # run by ``aiobt up`` unless its config says otherwise
    world_flag: str | None = None  # the flag ``aiobt up`` gives its world to (not the robot's)
    host: str = "robot"  # where it runs in a deployment across hosts (docs/deployment.md)

    @property
    def module(self) -> str:
        return f"aiobt_services.{self.name}.main"


SERVICES: tuple[ServiceSpec, ...] = (
    # the robot (the hardware's stand-in: its clock is everyone's) and the controller at
    # Nav2's 90; localization (the controller's pose) just below; the planner below (a
    # search may take tens of ms); the navigator, which asks for the plans, below them all
    # (aiobt.system.realtime says why)
    ServiceSpec("robot", "the pybullet robot service", realtime_priority=90, simulation=True),
    ServiceSpec(
        "localization",
        "Nav2's AMCL: the robot's pose in map from odometry and lidar",
        realtime_priority=80,
    ),
    ServiceSpec("planner", "the planner service", realtime_priority=70, host="base"),
    ServiceSpec("controller", "the controller service", realtime_priority=90),
    ServiceSpec("behaviors", "the behavior service"),
    # the safety chain, on the controller's way to the base: at the controller's 90
    ServiceSpec(
        "velocity_smoother",
        "Nav2's velocity smoother (off with safety_chain: false)",
        realtime_priority=90,
    ),
    ServiceSpec(
        "collision_monitor",
        "Nav2's collision monitor (off with safety_chain: false)",
        realtime_priority=90,
    ),
    ServiceSpec(
        "navigator",
        "the navigator: Nav2's bt_navigator over Zenoh",
        realtime_priority=60,
        host="base",
    ),
    # Nav2's optional servers, off unless enabled (as Nav2's bringup leaves them out)
    ServiceSpec(
        "route",
        "the route server: Nav2's nav2_route (routes on a graph)",
        enabled=False,
        world_flag="--graph-filepath",
        host="base",
    ),
    ServiceSpec(
        "following",
        "the following server: Nav2's nav2_following (follow a detected object)",
        enabled=False,
    ),
    ServiceSpec(
        "docking",
        "the docking server: Nav2's opennav_docking (dock and undock)",
        enabled=False,
        world_flag="--dock-database",
    ),
)
"""In start order: the robot first (the map and the clock), the navigator last."""

SERVICE_NAMES: tuple[str, ...] = tuple(spec.name for spec in SERVICES)
HOSTS: tuple[str, ...] = ("robot", "base")
"""A deployment across hosts: the robot computer runs what closes the loop on the robot
(driver, controller, behaviors, the safety chain, localization), the base station what
plans and decides (planner, navigator, route). Each service says which (``host``)."""
SAFETY_CHAIN: tuple[str, ...] = ("velocity_smoother", "collision_monitor")
"""Between the controller/behaviors and the base: run unless ``safety_chain: false``."""
COMPOSITIONS: dict[str, tuple[str, ...]] = {"safety_chain": SAFETY_CHAIN}
"""Services that also run as one process on one bus session, Nav2's composition
(:mod:`aiobt.system.compose`): ``aiobt NAME`` runs them, in this order."""


def service(name: str) -> ServiceSpec:
    """The service called ``name``; KeyError naming the known ones otherwise."""
    for spec in SERVICES:
        if spec.name == name:
            return spec
    raise KeyError(f"no service '{name}' (known: {', '.join(SERVICE_NAMES)})")


def on_host(host: str) -> tuple[str, ...]:
    """The services ``host`` runs in a deployment across hosts, on by default or not."""
    if host not in HOSTS:
        raise KeyError(f"no host '{host}' (known: {', '.join(HOSTS)})")
    return tuple(spec.name for spec in SERVICES if spec.host == host)


def realtime_priority(name: str) -> int:
    """The ``--realtime-priority`` default of service ``name``."""
    level = service(name).realtime_priority
    if level is None:
        raise KeyError(f"service '{name}' has no --realtime-priority option")
    return level
