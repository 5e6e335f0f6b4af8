"""``python -m aiobt_services.localization``: Nav2's AMCL as a service on Zenoh.

Reads the latched ``{ns}/map``, ``{ns}/odom`` and ``{ns}/scan``; takes
``{ns}/initialpose`` (a PoseWithCovarianceStamped, or a PoseStamped / its short
form with Nav2's default covariance). Publishes ``{ns}/amcl_pose`` (latched),
the ``map`` -> ``odom`` transform on ``{ns}/tf`` (with every scan taken, as AMCL),
``{ns}/particle_cloud``
(thinned) and ``{ns}/pose``: the estimate composed with the newest odometry, at
odometry rate. Serves ``{ns}/srv/reinitialize_global_localization``,
``{ns}/srv/request_nomotion_update`` and ``{ns}/srv/localization/stats``;
holds the liveliness token ``{ns}/nodes/localization``.
"""

from __future__ import annotations

import argparse
import asyncio
import contextlib
import logging
import time
from collections.abc import Callable

import numpy as np

from aiobt.msgs import (
    Empty,
    LaserScan,
    Msg,
    OccupancyGrid,
    Odometry,
    ParticleCloud,
    PoseStamped,
    PoseWithCovarianceStamped,
    ReinitializeGlobalLocalization,
    TFMessage,
)
from aiobt.system.realtime import realtime_if_asked
from aiobt.system.service import open_bus_unless_stopped, run_service, stop_on_signals
from aiobt.transport import Bus, BusSettings, Subscription
from aiobt.transport.announce import announce
from aiobt.transport.backlog import backlog
from aiobt.transport.relay import Relay, relay

from .laser_model import ScanError
from .messages import LocalizationStats
from .node import LocalizationNode, Reply
from .options import add_arguments as add_arguments
from .options import params_from_args
from .params import AmclParams, ParamError

log = logging.getLogger("aiobt_services.localization.main")

Ack = ReinitializeGlobalLocalization.Response
PUBLISHED: dict[str, type[Msg]] = {
    "tf": TFMessage,
    "particle_cloud": ParticleCloud,
    "pose": PoseStamped,
}
MAP_WAIT_LOG = 5.0  # wall s between "waiting for the map" lines
ODOM_WAIT = 0.05  # wall s a scan waits for the odometry of its own stamp
ODOM_LOOK = 0.002  # wall s between looks at the odometry's ring while a scan waits
ODOM_KEPT = 128  # odometry messages the ring keeps between scans (the filter's buffer: 2.5 s
# at 50 Hz; a scan takes them, 5 at a time at the robot's rates)
SCAN_QUEUE = 10  # scans that wait while the filter is busy (a preempted process); then
# the oldest are dropped and counted (AMCL's scan filter queues 100)


class Outputs:
    def __init__(self, bus: Bus) -> None:
        self._pubs = {name: bus.publisher(name, model) for name, model in PUBLISHED.items()}
        self._pubs["amcl_pose"] = bus.latched_publisher("amcl_pose", PoseWithCovarianceStamped)

    def listened(self, topic: str) -> bool:
        """Whether a subscriber matches ``topic`` now (latched ones: always)."""
        return self._pubs[topic].matched

    def on_matching_change(self, topic: str, fn: Callable[[], object]) -> None:
        """``fn()`` in the event loop whenever ``topic``'s readers come or go."""
        self._pubs[topic].on_matching_change(fn)

    def send(self, messages: list[tuple[str, Msg]]) -> None:
        for topic, msg in messages:
            self._pubs[topic].put(msg)


def _ack(reply: Reply) -> Ack:
    if not reply.ok:
        log.warning("%s", reply.message)
    return Ack(ok=reply.ok, message=reply.message)


async def _follow_map(bus: Bus, node: LocalizationNode, sub: Subscription[OccupancyGrid]) -> None:
    """Every map the latched topic brings; while none has come, say so and why."""
    key = bus.keys.topic(node.params.map_topic)
    updates = aiter(sub)
    while True:
        try:
            async with asyncio.timeout(None if node.has_map else MAP_WAIT_LOG):
                grid = await anext(updates)
        except TimeoutError:
            log.warning("waiting for the map on %s (latched, from the robot or a map server): "
                        "the filter needs it to weigh scans and to check poses", key)  # fmt: skip
            continue
        reply = node.on_map(grid)
        if not reply.ok:
            log.error("%s", reply.message)


class ScanWorker:
    """Reads scans one at a time, taking the odometry up to the scan's own stamp from
    the ring (waiting briefly for it); the filter's update runs on a worker thread."""

    def __init__(self, node: LocalizationNode, outputs: Outputs) -> None:
        self.node, self.outputs = node, outputs

    async def run(self, scans: Subscription[LaserScan]) -> None:
        stats = self.node.stats
        async for scan in scans:
            began, updates = time.perf_counter(), stats.updates  # wall time: a measurement
            await self._odom_up_to(scan.header.stamp)
            try:
                job = self.node.scan_job(scan)
            except ScanError as exc:
                log.warning("scan at %.3f refused: %s", scan.header.stamp, exc)
                continue
            if job is not None:
                # off the event loop: odometry (and so {ns}/pose) flows on while it runs
                self.outputs.send(await asyncio.to_thread(self.node.update, job))
                if stats.updates > updates:
                    stats.record_latency(time.perf_counter() - began)
            self.outputs.send(self.node.correction(scan.header.stamp))  # with every scan

    async def _odom_up_to(self, stamp: float) -> None:
        """Take the odometry received; if none is stamped at or after ``stamp`` yet,
        look again every ``ODOM_LOOK`` for at most ``ODOM_WAIT`` (wall s)."""
        node = self.node
        node.take_odometry()
        with contextlib.suppress(TimeoutError):
            async with asyncio.timeout(ODOM_WAIT):
                while (newest := node.odom.newest) is None or newest[0] < stamp:
                    await asyncio.sleep(ODOM_LOOK)
                    node.take_odometry()


class PoseStream:
    """``{ns}/pose`` at odometry rate while a subscriber matches ``pose``: only then is
    each odometry message handled, composed with the correction and put on Zenoh's
    receiving thread (a :class:`~aiobt.transport.relay.Relay`, declared and closed as
    readers come and go, told by Zenoh's matching listener: no event loop wake-up per
    message); the filter takes its odometry from the ring either way."""

    def __init__(self, bus: Bus, node: LocalizationNode, outputs: Outputs) -> None:
        self._bus, self._node, self._outputs = bus, node, outputs
        self._odom: Relay[Odometry] | None = None
        self._closed = False
        outputs.on_matching_change("pose", self.follow)
        self.follow()  # after the listener: no change slips in between

    @property
    def following(self) -> bool:
        return self._odom is not None

    def follow(self) -> None:
        """Subscribe the odometry while ``pose`` has a reader; let it go when none has."""
        wanted = not self._closed and self._outputs.listened("pose")
        if wanted and self._odom is None:
            self._odom = relay(self._bus, "odom", Odometry, self._on_odom)
        elif not wanted and self._odom is not None:
            self._odom.close()
            self._odom = None

    def close(self) -> None:
        """Let the odometry go for good (before the bus undeclares ``pose``'s publisher)."""
        self._closed = True
        self.follow()

    def _on_odom(self, msg: Odometry) -> None:
        """Zenoh's thread: reads only the filter's correction (replaced whole by an update)."""
        self._outputs.send(self._node.pose_for(msg))


def _stats(node: LocalizationNode, scans: Subscription[LaserScan]) -> LocalizationStats:
    cpu = np.asarray(node.stats.update_cpu) * 1000.0
    p50, p99, top = np.percentile(cpu, [50, 99, 100]) if cpu.size else (0.0, 0.0, 0.0)
    wall = np.asarray(node.stats.update_wall) * 1000.0
    w50, w99 = np.percentile(wall, [50, 99]) if wall.size else (0.0, 0.0)
    return LocalizationStats(
        scans=node.stats.scans, dropped=scans.dropped_overflow,
        skipped_no_odom=node.stats.skipped_no_odom, updates=node.stats.updates,
        update_ms_p50=float(p50), update_ms_p99=float(p99), update_ms_max=float(top),
        latency_ms_p50=float(w50), latency_ms_p99=float(w99),
        particles=len(node.amcl.particles),
    )  # fmt: skip


def _wire(bus: Bus, node: LocalizationNode) -> Subscription[LaserScan]:
    p = node.params
    scans = bus.subscribe(p.scan_topic, LaserScan, queue_size=SCAN_QUEUE)

    def initialpose(msg: PoseWithCovarianceStamped) -> None:
        _ack(node.on_initialpose(msg))

    bus.subscribe("initialpose", PoseWithCovarianceStamped, callback=initialpose, queue_size=1)
    bus.serve("reinitialize_global_localization", Empty, Ack,
              lambda _: _ack(node.reinitialize_global_localization()))  # fmt: skip
    bus.serve("request_nomotion_update", Empty, Ack, lambda _: _ack(node.request_nomotion_update()))
    bus.serve("localization/stats", Empty, LocalizationStats, lambda _: _stats(node, scans))
    return scans


async def serve(args: argparse.Namespace, params: AmclParams) -> None:
    realtime = realtime_if_asked(args.realtime_priority)  # before the bus: its threads too
    stop = stop_on_signals()
    async with open_bus_unless_stopped(BusSettings.from_args(args), stop) as bus:
        if bus is None:
            return
        outputs = Outputs(bus)
        odometry = backlog(bus, "odom", Odometry, ODOM_KEPT)
        node = LocalizationNode(params, wanted=outputs.listened, odometry=odometry.take)
        worker = ScanWorker(node, outputs)
        stream = PoseStream(bus, node, outputs)
        maps = bus.subscribe(params.map_topic, OccupancyGrid, latched=True, queue_size=1)
        scans = _wire(bus, node)
        announce(bus, "localization", sim_time=args.sim_time)
        log.info("localization up on namespace '%s': %d..%d particles, %d beams%s%s",
                 bus.namespace, params.min_particles, params.max_particles, params.max_beams,
                 "" if params.set_initial_pose else "; waiting for initialpose",
                 realtime)  # fmt: skip
        try:
            async with asyncio.TaskGroup() as tasks:
                jobs = [
                    tasks.create_task(_follow_map(bus, node, maps)),
                    tasks.create_task(worker.run(scans)),
                ]
                await stop.wait()
                for job in jobs:
                    job.cancel()
        finally:
            stream.close()
            odometry.close()
        s = _stats(node, scans)
        log.info("localization stopped: %d scans, %d updates (CPU p50 %.2f ms, p99 %.2f ms), "
                 "%d dropped unread", s.scans, s.updates, s.update_ms_p50, s.update_ms_p99,
                 s.dropped)  # fmt: skip


def run(args: argparse.Namespace) -> int:
    try:
        params = params_from_args(args)
    except ParamError as exc:
        log.error("localization: %s", exc)
        return 2
    return run_service(serve(args, params), log, "localization")
