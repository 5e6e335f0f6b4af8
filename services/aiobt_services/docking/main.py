"""``aiobt docking``: Nav2's docking server (``opennav_docking``) on Zenoh.

Loads a dock database (``--dock-database``, Nav2's YAML; a shipped world's name picks
its database) and the dock plugins (``--dock-plugins``, Nav2's SimpleChargingDock);
reads ``{ns}/pose``, ``{ns}/odom``, ``{ns}/battery`` and the dock's detections on
``{ns}/detected_dock_pose``; serves the actions ``dock_robot`` and ``undock_robot``
(navigating to a staging pose through the navigator's ``navigate_to_pose``) and the
service ``srv/docking_server/reload_database``; publishes ``{ns}/cmd_vel`` while it
drives, ``{ns}/dock_pose``, ``{ns}/filtered_dock_pose``, ``{ns}/staging_pose``, and
latched ``{ns}/docks`` and ``{ns}/docking_state``; holds ``{ns}/nodes/docking``. A
database that does not load is logged and every DockRobot by id fails DOCK_NOT_IN_DB.
See README.md.
"""

from __future__ import annotations

import argparse
import logging

from aiobt.core.clock import Clock
from aiobt.system.robot_flags import add_command_argument
from aiobt.system.service import (
    add_clock_arguments,
    open_bus_unless_stopped,
    open_clock,
    run_service,
    stop_on_signals,
)
from aiobt.transport import Bus, BusSettings, add_bus_arguments

from .controller import DockController
from .database import DockInstance, load_database
from .errors import DockDatabaseError
from .motion import Motion
from .navigator import StagingNavigator
from .options import (
    add_docking_arguments,
    check_scopes,
    controller_params,
    docking_params,
    make_plugins,
)
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


def database_or_explain(args: argparse.Namespace) -> tuple[dict[str, DockInstance], str]:
    """The docks, and why there are none when the database does not load (logged)."""
    if args.dock_database is None:
        log.warning(
            "Dock database filepath nor dock parameters set. Docking actions can "
            "only be executed specifying the dock pose via the action request."
        )
        return {}, ""
    try:
        docks = load_database(args.dock_database)
    except DockDatabaseError as exc:
        log.error("%s", exc)
        return {}, str(exc)
    log.info("Loaded %d dock(s) from %s", len(docks), args.dock_database)
    return docks, ""


def build(args: argparse.Namespace, bus: Bus, clock: Clock) -> tuple[DockingBus, DockingServer]:
    """The server's parts; ValueError naming a bad parameter."""
    check_scopes(args)
    params, controller = docking_params(args), DockController(controller_params(args))
    wires = DockingBus(bus, clock, args.cmd_vel_topic)
    wiring = DockWiring(wires.frames, clock, wires.detection, wires.battery, wires.show)
    plugins = make_plugins(args, wiring)
    motion = Motion(params, controller, wires.frames, clock, wires.drive, wires.turn_rate)
    navigate = StagingNavigator(bus, clock, params.navigator_bt_xml)
    docks, problem = database_or_explain(args)
    server = DockingServer(motion, navigate, plugins, docks)
    server.database_error = problem
    log.info("Docking Server has %d dock types and %d dock instances available.",
             len(plugins), len(server.docks))  # fmt: skip
    return wires, server


async def serve(args: argparse.Namespace) -> None:
    stop = stop_on_signals()
    async with open_bus_unless_stopped(BusSettings.from_args(args), stop) as bus:
        if bus is None:
            return
        clock = await open_clock(bus, args.sim_time, stop)
        if clock is None:
            return
        try:
            wires, server = build(args, bus, clock)
        except ValueError as exc:
            log.error("docking: %s", exc)
            raise SystemExit(2) from None
        wires.serve(server, args.sim_time)
        log.info("docking server up on namespace '%s'", bus.namespace)
        await stop.wait()


def run(args: argparse.Namespace) -> int:
    return run_service(serve(args), log, "docking")
