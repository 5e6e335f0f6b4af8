"""``aiobt robot``: the pybullet robot service on Zenoh.

Publishes ``{ns}/odom``, ``{ns}/pose`` (unless ``--pose-source none``), ``{ns}/scan``,
``{ns}/battery``, ``{ns}/clock``, ``{ns}/bumper``, ``{ns}/joint_states`` (the wheels),
``{ns}/detected_dock_pose`` (the
dock's marker as the robot's camera sees it) and the latched ``{ns}/map``; listens on
``{ns}/cmd_vel`` and ``{ns}/initialpose``; serves
``{ns}/srv/reinitialize_global_localization`` and ``{ns}/srv/dock_detector/toggle``
(the dock detector off and on, as a real detector may); holds the liveliness token
``{ns}/nodes/robot``. The simulation's own keys are in its namespace ``{ns}/sim``
(``aiobt.transport.keys.sim_namespace``): the truth on ``{ns}/sim/pose``, and the
services ``{ns}/sim/srv/obstacles/{spawn,move,remove,list}``,
``{ns}/sim/srv/reset_pose`` (the teleport), ``{ns}/sim/srv/snapshot`` and, with
``--stepped``, ``{ns}/sim/srv/step``. See README.md next to this file for the
message shapes. With ``target_service``: the followed box
(``{ns}/sim/srv/follow_target/{start,hide,stop}``, its detections on
``{ns}/dynamic_pose``, its truth on ``{ns}/sim/target``).
"""

from __future__ import annotations

import argparse
import asyncio
import logging
import math
import os
from pathlib import Path

from aiobt.msgs import (
    BatteryState,
    Empty,
    JointState,
    LaserScan,
    Msg,
    OccupancyGrid,
    Odometry,
    PoseStamped,
    PoseWithCovarianceStamped,
    Trigger,
    Twist,
)
from aiobt.msgs import Clock as ClockMsg
from aiobt.msgs import sim as messages
from aiobt.system.heap import settle
from aiobt.system.realtime import realtime_if_asked
from aiobt.system.service import open_bus_unless_stopped, run_service, stop_on_signals
from aiobt.transport import Bus, BusSettings, add_bus_arguments
from aiobt.transport.announce import announce
from aiobt.transport.keys import SIM_POSE, sim_namespace

from . import convert
from .dock_detector import SERVICE as DETECTOR_SERVICE
from .mapfile import MapError, load_map
from .options import add_robot_arguments, sim_config
from .pacing import speed_label
from .runner import DOCK_DETECTION, JOINT_STATES, Rates, SimRunner
from .service import RobotService
from .sim import Simulation
from .snapshot import render_png
from .target_service import add_target_arguments, wire_target
from .worlds import world_path

log = logging.getLogger("aiobt_services.robot.main")

PUBLISHED: dict[str, type[Msg]] = {
    "odom": Odometry,
    "pose": PoseStamped,
    SIM_POSE: PoseStamped,
    "scan": LaserScan,
    "battery": BatteryState,
    "clock": ClockMsg,
    "bumper": messages.BumperEvent,
    DOCK_DETECTION: PoseStamped,
    JOINT_STATES: JointState,
}


def add_arguments(parser: argparse.ArgumentParser) -> None:
    add_bus_arguments(parser)
    parser.add_argument(
        "--sim-time",
        action="store_true",
        help="accepted as every service takes it: the robot is the simulation, it always "
        "publishes {ns}/clock",
    )
    add_robot_arguments(parser)
    add_target_arguments(parser)


class BusOutputs:
    """The runner's sink: one publisher per topic (``pose`` only as the localization's
    stand-in: a base publishes no pose in map, nor declares one)."""

    def __init__(self, bus: Bus, *, pose: bool = True) -> None:
        topics = {name: model for name, model in PUBLISHED.items() if pose or name != "pose"}
        self._pubs = {name: bus.publisher(name, model) for name, model in topics.items()}

    def publish(self, topic: str, msg: Msg) -> None:
        self._pubs[topic].put(msg)

    def listened(self, topic: str) -> bool:
        """Whether a subscriber matches ``topic`` now (the runner's ``wanted``)."""
        return self._pubs[topic].matched


def _wire(bus: Bus, service: RobotService, *, localization_stand_in: bool) -> None:
    # commands: only the newest counts, so a burst is applied once, not message by message
    bus.subscribe("cmd_vel", Twist, callback=service.on_cmd_vel, queue_size=1)
    m = messages
    if localization_stand_in:  # --pose-source truth: else the localization service's
        # one model per key: initialpose carries a pose with covariance (or a PoseStamped)
        bus.subscribe("initialpose", PoseWithCovarianceStamped, queue_size=1,
                      callback=lambda m: service.on_initialpose(m.as_pose_stamped()))  # fmt: skip
        bus.serve(
            "reinitialize_global_localization", Empty, m.Ack, service.reinitialize_localization
        )
    sim_ns = sim_namespace(bus.namespace)  # the simulation's own services
    bus.serve("obstacles/spawn", m.SpawnObstacle, m.Ack, service.spawn, namespace=sim_ns)
    bus.serve("obstacles/move", m.MoveObstacle, m.Ack, service.move, namespace=sim_ns)
    bus.serve("obstacles/remove", m.RemoveObstacle, m.Ack, service.remove, namespace=sim_ns)
    bus.serve("obstacles/list", Empty, m.ObstacleList, service.list_obstacles, namespace=sim_ns)
    bus.serve("reset_pose", PoseStamped, m.Ack, service.reset_pose, namespace=sim_ns)
    bus.serve("snapshot", m.SnapshotRequest, m.Snapshot, service.snapshot, namespace=sim_ns)


def _serve_steps(bus: Bus, runner: SimRunner) -> None:
    """``--stepped``: sim time moves only when ``sim/srv/step`` asks (one request at a
    time)."""
    lock = asyncio.Lock()

    async def step(req: messages.StepRequest) -> messages.StepReply:
        async with lock:
            steps = await runner.advance(req.seconds)
        return messages.StepReply(time=runner.sim.time, steps=steps)

    sim_ns = sim_namespace(bus.namespace)
    bus.serve("step", messages.StepRequest, messages.StepReply, step, namespace=sim_ns)


async def serve(args: argparse.Namespace, sim: Simulation) -> None:
    realtime = realtime_if_asked(args.realtime_priority)  # before the bus: its threads too
    stop = stop_on_signals()
    async with open_bus_unless_stopped(BusSettings.from_args(args), stop) as bus:
        if bus is None:
            return
        service = RobotService(sim, initialpose=args.initialpose)
        bus.latched_publisher("map", OccupancyGrid).put(convert.occupancy_grid(sim.world))
        targets = wire_target(bus, sim, args)  # the followed box (sim/srv/follow_target/*)
        outputs = BusOutputs(bus, pose=args.pose_source == "truth")
        runner = SimRunner(
            sim,
            targets.tap(outputs),
            speed=args.speed,
            rates=Rates(
                scan=args.scan_hz, odom=args.odom_hz, pose=args.odom_hz, clock=args.clock_hz
            ),
            command_wait=args.command_wait,
            max_lag=args.max_lag,
            publish_pose=args.pose_source == "truth",
            wanted=outputs.listened,  # the truth and the wheels only for a reader
        )
        _wire(bus, service, localization_stand_in=args.pose_source == "truth")
        bus.serve(DETECTOR_SERVICE, Trigger.Request, Trigger.Response, runner.dock_detector.toggle)
        settle()  # start-up's objects (the world's too) out of the collector's full passes
        announce(bus, "robot", sim_time=True)  # it is the simulation: its time is sim time
        log.info(
            "robot up on namespace '%s': world %s, %s, dt %g s%s",
            bus.namespace,
            sim.world.source,
            "stepped by sim/srv/step" if args.stepped else f"speed {speed_label(args.speed)}",
            sim.config.dt,
            realtime,
        )
        if args.stepped:
            _serve_steps(bus, runner)
            await stop.wait()
        else:
            await runner.run(stop)
    log.info("robot stopped at sim time %.2f s after %d steps", sim.time, sim.steps)


def run(args: argparse.Namespace) -> int:
    if args.gui and not (os.environ.get("DISPLAY") or os.environ.get("WAYLAND_DISPLAY")):
        log.error("robot: --gui needs a display (DISPLAY is not set); run headless without it")
        return 2
    if args.realtime_priority is not None and math.isinf(args.speed):
        log.error(
            "robot: --realtime-priority with --speed max: at max the sim never sleeps, and "
            "under SCHED_FIFO it would hold a core from every other process; give a speed"
        )
        return 2
    try:
        world = load_map(world_path(args.world))
        config = sim_config(args)
        if args.start is not None:
            x, y, yaw = args.start
            world.start = (x, y, yaw)
        sim = Simulation(world, config)
    except (MapError, ValueError) as exc:
        log.error("robot: %s", exc)
        return 2
    with sim:
        if run_service(serve(args, sim), log, "robot") != 0:
            return 1
        if args.snapshot_on_exit:
            Path(args.snapshot_on_exit).write_bytes(render_png(sim))
            log.info("snapshot written to %s", args.snapshot_on_exit)
    return 0
