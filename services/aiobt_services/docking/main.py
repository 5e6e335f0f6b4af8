"""``aiobt docking``: Nav2's docking server (``opennav_docking``) on Zenoh.

Loads a dock database (``--dock-database``, Nav2's YAML; a shipped world's name picks
its database; or Nav2's ``docks`` parameter, ``--docks``) and the dock plugins
(``--dock-plugins``, Nav2's SimpleChargingDock); reads ``{ns}/pose``, ``{ns}/odom``,
``{ns}/battery``, ``{ns}/scan`` (its approach's collision check, with ``--footprint``),
latched ``{ns}/tf_static`` (frames beyond map, odom and base_link), the dock's detections
on ``{ns}/detected_dock_pose`` and, with stall detection, ``{ns}/joint_states``; calls
a plugin's ``detector_service_name`` (``{ns}/srv/...``, std_srvs/Trigger) to start and
stop the detector; serves the actions ``dock_robot`` and ``undock_robot``
(navigating to a staging pose through the navigator's ``navigate_to_pose``) and the
service ``srv/docking_server/reload_database``; publishes ``{ns}/cmd_vel`` while it
drives, ``{ns}/dock_pose``, ``{ns}/filtered_dock_pose``, ``{ns}/staging_pose``, and
latched ``{ns}/docks`` and ``{ns}/docking_state``; holds ``{ns}/nodes/docking``. A
database that does not load is logged and every DockRobot by id fails DOCK_NOT_IN_DB.
See README.md.
"""

from __future__ import annotations

import argparse
import functools
import logging

from aiobt.core.clock import Clock
from aiobt.costmap import footprint_from_radius, parse_footprint
from aiobt.geometry import FloatArray
from aiobt.system.robot_flags import (
    add_command_argument,
    add_local_costmap_arguments,
    local_costmap_from,
)
from aiobt.system.service import add_clock_arguments, run_service, serve_on_clock
from aiobt.transport import Bus, add_bus_arguments

from .collisions import ScanCollisions
from .controller import DockController
from .database import DockInstance, load_database
from .errors import DockDatabaseError
from .motion import Motion
from .navigator import StagingNavigator
from .options import Settings, add_docking_arguments, make_plugins, settings_from
from .plugins import DockWiring
from .server import DockingServer
from .service import DockingBus

log = logging.getLogger("aiobt_services.docking.main")


def add_arguments(parser: argparse.ArgumentParser) -> None:
    add_bus_arguments(parser)
    add_clock_arguments(parser)
    group = parser.add_argument_group("docking server", description=__doc__.split("\n\n")[1])
    add_docking_arguments(group)
    add_command_argument(group)
    costmap = parser.add_argument_group("local costmap (the approach's check)")
    add_local_costmap_arguments(costmap)
    costmap.add_argument("--footprint", type=footprint_flag, default=None, metavar="POINTS",
                         help="the robot's outline, Nav2's costmap footprint "
                         "'[[x, y], [x, y], [x, y], ...]' in m (default: a circle of "
                         "--robot-radius)")  # fmt: skip


def footprint_flag(text: str) -> FloatArray | None:
    """Nav2's ``footprint`` string; empty or ``[]`` (Nav2's default): none."""
    if text.strip() in ("", "[]"):
        return None
    try:
        return parse_footprint(text)
    except ValueError as exc:
        raise argparse.ArgumentTypeError(str(exc)) from None


def footprint_of(args: argparse.Namespace) -> FloatArray:
    """The polygon checked: ``--footprint``, else Nav2's 16 points of ``--robot-radius``."""
    given: FloatArray | None = args.footprint
    return footprint_from_radius(args.robot_radius) if given is None else given


def database_or_explain(
    args: argparse.Namespace, from_params: dict[str, DockInstance] | None
) -> tuple[dict[str, DockInstance], str]:
    """The docks (Nav2's order: the ``dock_database`` file, else the ``docks``
    parameter), and why there are none when the database does not load (logged)."""
    if args.dock_database is None and from_params is not None:
        log.info("Loading docks from parameter file.")
        return from_params, ""
    if args.dock_database is None:
        log.warning(
            "Dock database filepath nor dock parameters set. Docking actions can "
            "only be executed specifying the dock pose via the action request."
        )
        return {}, ""
    if from_params is not None:
        log.warning("docks: ignored, dock_database %s is given (Nav2 reads the file "
                    "first; --dock-database '' uses the docks)", args.dock_database)  # fmt: skip
    try:
        docks = load_database(args.dock_database)
    except DockDatabaseError as exc:
        log.error("%s", exc)
        return {}, str(exc)
    log.info("Loaded %d dock(s) from %s", len(docks), args.dock_database)
    return docks, ""


def start(settings: Settings, args: argparse.Namespace, bus: Bus, clock: Clock) -> None:
    """The server's parts on ``bus``, its actions and services served."""
    wires = DockingBus(bus, clock, args.cmd_vel_topic)
    wiring = DockWiring(wires.frames, clock, wires.detection, wires.battery, wires.show,
                        wires.subscribe, wires.trigger, wires.joint_states)  # fmt: skip
    plugins = make_plugins(settings.plugins, wiring)
    costmap = ScanCollisions(local_costmap_from(args), footprint_of(args), wires.scan,
                             wires.frames, clock)  # fmt: skip
    controller = DockController(settings.controller, costmap.collides)
    motion = Motion(settings.docking, controller, wires.frames, clock, wires.drive,
                    wires.turn_rate, costmap.refresh)  # fmt: skip
    navigate = StagingNavigator(bus, clock, settings.docking.navigator_bt_xml)
    docks, problem = database_or_explain(args, settings.docks)
    server = DockingServer(motion, navigate, plugins, docks)
    server.database_error = problem
    log.info("Docking Server has %d dock types and %d dock instances available.",
             len(plugins), len(server.docks))  # fmt: skip
    wires.serve(server)


def run(args: argparse.Namespace) -> int:
    try:
        settings = settings_from(args)
    except ValueError as exc:
        log.error("docking: %s", exc)
        return 2
    up = functools.partial(start, settings, args)
    return run_service(serve_on_clock(args, "docking", up), log, "docking")
