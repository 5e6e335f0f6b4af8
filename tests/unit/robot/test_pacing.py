"""Pacing of the sim loop on a fake wall clock: step timing, commands between steps,
the command timeout in sim time, lag reports, and ``--speed max``."""

from __future__ import annotations

import argparse
import asyncio
import itertools
import logging
import math
from collections.abc import Iterator

import pytest

from aiobt.msgs import Clock as ClockMsg
from aiobt.msgs import Msg
from aiobt_services.robot.bumper import ContactEvent
from aiobt_services.robot.drive import DriveController
from aiobt_services.robot.mapfile import load_map
from aiobt_services.robot.options import add_robot_arguments
from aiobt_services.robot.pacing import Pacer, parse_speed
from aiobt_services.robot.runner import LATE_WALL, MAX_LAG, MIN_SLEEP, SimRunner
from aiobt_services.robot.sim import Simulation
from aiobt_services.robot.worlds import SMALL

DT = 0.01


class FakeWall:
    """Virtual wall time: ``sleep`` moves it on; each physics step can cost ``step_cost``."""

    def __init__(self) -> None:
        self.time = 0.0
        self.sleeps = 0
        self.end = math.inf
        self.stop = asyncio.Event()

    def now(self) -> float:
        return self.time

    def pass_time(self, seconds: float) -> None:
        self.time += seconds
        if self.time >= self.end:
            self.stop.set()

    async def sleep(self, seconds: float) -> None:
        self.sleeps += 1
        self.pass_time(max(0.0, seconds))
        await asyncio.sleep(0)


class CostlySink:
    """The runner's outputs, the clock stamps kept; each physics step of ``sim`` costs
    ``step_cost`` of wall time (a slow step)."""

    def __init__(self, sim: Simulation, wall: FakeWall, step_cost: float) -> None:
        self.clock: list[tuple[float, float]] = []  # (wall, stamp) of each clock message
        self.wall = wall
        step = sim.step

        def costly_step(count: int = 1) -> list[ContactEvent]:
            events = step(count)
            wall.pass_time(step_cost * count)
            return events

        sim.step = costly_step  # type: ignore[method-assign]

    def publish(self, topic: str, msg: Msg) -> None:
        if isinstance(msg, ClockMsg):
            self.clock.append((self.wall.time, msg.clock))


@pytest.fixture
def sim() -> Iterator[Simulation]:
    with Simulation(load_map(SMALL)) as simulation:
        yield simulation


async def run_until(runner: SimRunner, wall: FakeWall, wall_end: float) -> None:
    wall.end = wall_end
    await asyncio.wait_for(runner.run(wall.stop), 30.0)


# -- Pacer (pure) ---------------------------------------------------------------------------


def test_pacer_waits_until_each_step_is_due() -> None:
    pacer = Pacer(10.0, DT)
    pacer.start(100.0, 0.0)
    assert pacer.delay(100.0, 0.0) == pytest.approx(0.001)  # one 10 ms step at 10x: 1 ms
    assert pacer.delay(100.001, 0.0) == 0.0
    assert pacer.delay(100.0, 0.05) == pytest.approx(0.006)  # ahead: wait for it


def test_pacer_gives_up_lag_instead_of_catching_up_and_counts_it() -> None:
    pacer = Pacer(10.0, DT, max_lag=0.25, report_every=5.0)
    pacer.start(0.0, 0.0)
    assert pacer.delay(0.2, 1.5) == 0.0  # 0.5 s of sim behind: within 0.25 s of wall
    assert pacer.report(0.2, 1.5) is None
    assert pacer.delay(1.0, 2.0) == 0.0  # 8 s behind: the target moves to now
    assert pacer.delay(1.0, 2.0) == pytest.approx(0.001)  # and is not caught up in a burst
    assert pacer.delay(2.0, 3.0) == 0.0  # behind again: 9 s
    assert pacer.report(4.9, 3.0) is None  # not before report_every
    line = pacer.report(5.0, 4.0)
    assert line is not None
    assert "achieved x0.8" in line
    assert "2 time(s)" in line
    assert "17.00 s of sim time given up" in line
    assert pacer.fell_short
    assert pacer.report(10.0, 54.0) is None  # a period without lag says nothing


def test_pacer_reports_lag_made_up_as_the_speed_met() -> None:
    pacer = Pacer(2.0, DT, max_lag=0.008, report_every=5.0)
    pacer.start(0.0, 0.0)
    assert pacer.delay(1.0, 1.9) == 0.0  # 0.05 s of wall behind: the target moves to now
    line = pacer.report(5.0, 10.0)
    assert line is not None
    assert line.startswith("simulation at --speed 2: achieved x2.0 over the last 5.0 s; ")
    assert not pacer.fell_short  # the runner logs it as INFO, not as a warning


def test_pacer_counts_waits_for_late_commands_apart_from_lag() -> None:
    pacer = Pacer(10.0, DT, report_every=5.0)
    pacer.start(0.0, 0.0)
    pacer.held(1.0, 5.0, 0.5)  # waited 0.5 s: the target restarts, no lag counted
    assert pacer.delay(1.0, 5.0) == pytest.approx(0.001)
    line = pacer.report(5.0, 45.0)
    assert line == (
        "simulation at --speed 10: achieved x9.0 over the last 5.0 s; "
        "waited 1 time(s), 0.50 s in all, for a late cmd_vel"
    )


def test_pacer_max_never_waits_and_reports_the_speed_achieved() -> None:
    pacer = Pacer(math.inf, DT, report_every=2.0)
    pacer.start(0.0, 0.0)
    assert pacer.unpaced
    assert pacer.delay(0.0, 1000.0) == 0.0
    line = pacer.report(2.0, 60.0)
    assert line == "running as fast as possible: x30.0 over the last 2.0 s"


@pytest.mark.parametrize(
    ("text", "value"), [("max", math.inf), ("MAX", math.inf), ("10", 10.0), ("0.5", 0.5)]
)
def test_parse_speed(text: str, value: float) -> None:
    assert parse_speed(text) == value


@pytest.mark.parametrize("text", ["0", "-1", "inf", "nan", "fast"])
def test_parse_speed_refuses_bad_values(text: str) -> None:
    with pytest.raises(ValueError, match="speed"):
        parse_speed(text)


def test_speed_flag_takes_max_and_names_bad_values(capsys: pytest.CaptureFixture[str]) -> None:
    parser = argparse.ArgumentParser()
    add_robot_arguments(parser)
    assert parser.parse_args(["--speed", "max"]).speed == math.inf
    with pytest.raises(SystemExit):
        parser.parse_args(["--speed", "fast"])
    err = capsys.readouterr().err
    assert "--speed" in err
    assert "'max'" in err


def test_max_lag_flag_defaults_to_two_shortest_sleeps_and_names_bad_values(
    capsys: pytest.CaptureFixture[str],
) -> None:
    parser = argparse.ArgumentParser()
    add_robot_arguments(parser)
    assert parser.parse_args([]).max_lag == MAX_LAG == 2 * MIN_SLEEP
    assert parser.parse_args(["--max-lag", "0.25"]).max_lag == 0.25
    with pytest.raises(SystemExit):
        parser.parse_args(["--max-lag", "0"])
    assert "--max-lag" in capsys.readouterr().err


def test_pacer_refuses_bad_parameters() -> None:
    with pytest.raises(ValueError, match="speed"):
        Pacer(0.0, DT)
    with pytest.raises(ValueError, match="dt"):
        Pacer(1.0, 0.0)


# -- SimRunner.run on the fake clock ---------------------------------------------------------


async def test_run_paces_sim_time_at_the_speed_up(sim: Simulation) -> None:
    wall = FakeWall()
    runner = SimRunner(sim, CostlySink(sim, wall, 0.0), speed=10.0, wall=wall)
    await run_until(runner, wall, 2.0)
    assert sim.time == pytest.approx(20.0, abs=MIN_SLEEP * 10.0 + 0.02)  # a batch behind
    # one wake-up per MIN_SLEEP (4 steps at 10x), not one per step (2000)
    assert 2.0 / MIN_SLEEP * 0.9 <= wall.sleeps <= 2.0 / MIN_SLEEP + 1


class StallingWall(FakeWall):
    """A fake wall on which the ``at``-th sleep lasts ``stall`` wall seconds longer (this
    process preempted on a loaded machine); the sim time reached at each wake-up."""

    def __init__(self, sim: Simulation, at: int, stall: float) -> None:
        super().__init__()
        self.sim, self.at, self.stall = sim, at, stall
        self.woke_at: list[float] = []

    async def sleep(self, seconds: float) -> None:
        self.woke_at.append(self.sim.time)
        await super().sleep(seconds + (self.stall if self.sleeps == self.at else 0.0))


@pytest.mark.parametrize("max_lag", [MAX_LAG, 0.25])
async def test_a_stall_is_given_up_not_caught_up_in_a_burst(
    sim: Simulation, max_lag: float
) -> None:
    """A 30 ms stall at 10x: by default (8 ms) the 0.34 s of sim time due at the wake-up
    is given up, so no wake-up runs more than 8 ms' worth (80 ms of sim time) of steps
    back to back; with a 0.25 s lag allowed the whole 0.34 s runs at once."""
    wall = StallingWall(sim, at=50, stall=0.03)
    runner = SimRunner(sim, CostlySink(sim, wall, 0.0), speed=10.0, wall=wall, max_lag=max_lag)
    await run_until(runner, wall, 0.5)
    longest = max(b - a for a, b in itertools.pairwise(wall.woke_at))
    given_up = 0.5 * 10.0 - sim.time
    if max_lag == MAX_LAG:
        assert longest <= MAX_LAG * 10.0
        assert given_up == pytest.approx(0.34, abs=0.05)
    else:
        assert longest == pytest.approx(0.34, abs=DT / 2)
        assert given_up == pytest.approx(0.0, abs=0.05)


async def test_at_10x_the_clock_goes_out_once_per_wake_up_with_the_batch_end_time(
    sim: Simulation,
) -> None:
    """Four steps per wake-up at 10x: one stamp at the batch's end (250 a wall second,
    not 1,000), stamped with the sim time the followers then wake on, before the sleep."""
    wall = StallingWall(sim, at=-1, stall=0.0)  # records the sim time at each sleep
    sink = CostlySink(sim, wall, 0.0)
    runner = SimRunner(sim, sink, speed=10.0, wall=wall)
    await run_until(runner, wall, 1.0)
    stamps = [stamp for _, stamp in sink.clock]
    assert 1.0 / MIN_SLEEP * 0.9 <= len(stamps) <= 1.0 / MIN_SLEEP + 2
    slept_at = {round(s, 9) for s in wall.woke_at if s > 0.0}
    assert slept_at <= {round(s, 9) for s in stamps}  # each sleep's time is out before it
    gaps = [b - a for a, b in itertools.pairwise(stamps)]
    assert min(gaps) > 0.0
    assert max(gaps) <= 0.05 + 1e-9  # a wake-up's batch (4-5 steps), never more
    assert stamps[-1] == pytest.approx(sim.time)  # the last batch's too, at the end


@pytest.mark.parametrize(("speed", "step_cost"), [(1.0, 0.0), (math.inf, 0.001)])
async def test_at_1x_and_unpaced_every_clock_stamp_due_goes_out(
    sim: Simulation, speed: float, step_cost: float
) -> None:
    wall = FakeWall()
    sink = CostlySink(sim, wall, step_cost)
    runner = SimRunner(sim, sink, speed=speed, wall=wall)
    await run_until(runner, wall, 0.5)
    stamps = [stamp for _, stamp in sink.clock]
    assert len(stamps) >= sim.steps - 1  # one per step (100 Hz of sim time, dt 10 ms)
    assert all(b - a == pytest.approx(DT) for a, b in itertools.pairwise(stamps))


async def test_behind_and_never_sleeping_the_clock_still_goes_out_every_batch(
    sim: Simulation,
) -> None:
    """5 ms of wall per 10 ms step at 10x: the sim never sleeps, yet a stamp goes out
    at least every four steps (a wake-up's batch), never held back longer."""
    wall = FakeWall()
    sink = CostlySink(sim, wall, 0.005)
    runner = SimRunner(sim, sink, speed=10.0, wall=wall)
    await run_until(runner, wall, 1.0)
    stamps = [stamp for _, stamp in sink.clock]
    assert sim.steps >= 150
    assert max(b - a for a, b in itertools.pairwise(stamps)) == pytest.approx(4 * DT)


async def test_stepped_mode_sends_every_clock_stamp_due(sim: Simulation) -> None:
    wall = FakeWall()
    sink = CostlySink(sim, wall, 0.0)
    runner = SimRunner(sim, sink, speed=10.0, wall=wall)
    await runner.advance(0.1)
    assert [stamp for _, stamp in sink.clock] == pytest.approx([DT * k for k in range(1, 11)])


async def test_every_step_lets_the_loop_in_whatever_the_lag(sim: Simulation) -> None:
    """A slow machine (5 ms per 10 ms step at 10x): far behind, yet one step per loop pass."""
    wall = FakeWall()
    runner = SimRunner(sim, CostlySink(sim, wall, 0.005), speed=10.0, wall=wall)
    seen: list[int] = []

    async def watcher() -> None:
        while wall.time < 1.0:
            seen.append(sim.steps)
            await asyncio.sleep(0)

    await asyncio.gather(run_until(runner, wall, 1.0), watcher())
    gaps = [b - a for a, b in itertools.pairwise(seen)]
    assert sim.steps >= 150
    assert max(gaps) == 1


async def test_command_timeout_is_sim_time_even_when_behind(sim: Simulation) -> None:
    """A client commanding every 0.1 s of sim time keeps the base moving though the sim
    lags far behind its 20x target (the old loop stepped 5 s of sim time in one batch)."""
    wall = FakeWall()
    runner = SimRunner(sim, CostlySink(sim, wall, 0.002), speed=20.0, wall=wall)
    stopped_at: list[float] = []
    last = -math.inf

    async def client() -> None:
        nonlocal last
        while wall.time < 1.0:
            if sim.time - last >= 0.1:
                sim.command(0.3, 0.0)
                last = sim.time
            if sim.time > 0.5 and sim.drive.linear == 0.0:
                stopped_at.append(sim.time)
            await asyncio.sleep(0)

    await asyncio.gather(run_until(runner, wall, 1.0), client())
    assert sim.time > 3.0
    assert stopped_at == []
    assert sim.drive.linear == pytest.approx(0.3)


async def test_command_timeout_stops_after_its_sim_time(sim: Simulation) -> None:
    wall = FakeWall()
    runner = SimRunner(sim, CostlySink(sim, wall, 0.0), speed=10.0, wall=wall)
    moving: list[tuple[float, float]] = []
    sim.command(0.3, 0.0)

    async def watcher() -> None:
        while wall.time < 0.2:
            moving.append((sim.time, sim.drive.linear))
            await asyncio.sleep(0)

    await asyncio.gather(run_until(runner, wall, 0.2), watcher())
    last_moving = max(t for t, v in moving if v > 0.0)
    assert 0.5 <= last_moving <= 0.5 + 0.3 / 2.5 + 2 * DT  # timeout, then the deceleration ramp


async def test_lag_is_reported_periodically(
    sim: Simulation, caplog: pytest.LogCaptureFixture
) -> None:
    wall = FakeWall()
    runner = SimRunner(sim, CostlySink(sim, wall, 0.004), speed=10.0, wall=wall, report_every=0.5)
    with caplog.at_level(logging.WARNING, logger="aiobt_services.robot.runner"):
        await run_until(runner, wall, 1.6)
    lines = [r.getMessage() for r in caplog.records if "behind --speed 10" in r.getMessage()]
    assert len(lines) == 3
    assert all("achieved x2.5" in line for line in lines)


async def test_speed_max_never_sleeps_and_reports_the_speed_up(
    sim: Simulation, caplog: pytest.LogCaptureFixture
) -> None:
    wall = FakeWall()
    runner = SimRunner(
        sim, CostlySink(sim, wall, 0.001), speed=math.inf, wall=wall, report_every=0.5
    )
    with caplog.at_level(logging.INFO, logger="aiobt_services.robot.runner"):
        await run_until(runner, wall, 1.0)
    assert wall.sleeps == 0
    assert sim.time == pytest.approx(10.0, abs=0.02)
    assert "running as fast as possible: x10.0" in caplog.text


class StreamingClient:
    """Commands every ``period`` s of sim time, as a controller does; from sim time
    ``pause_at`` it sends nothing for ``pause`` s of wall time (its process descheduled;
    inf: gone). It runs in the loop pass between two steps, as a Zenoh callback would."""

    def __init__(self, sim: Simulation, pause_at: float, pause: float) -> None:
        self.sim = sim
        self.pause_at = pause_at
        self.pause = pause
        self.last = -math.inf
        self.paused: tuple[float, float] | None = None  # (wall, sim) when the pause began
        self.resumed_sim: float | None = None

    async def run(self, wall: FakeWall) -> None:
        while not wall.stop.is_set():
            if self.paused is None and self.sim.time >= self.pause_at:
                self.paused = (wall.time, self.sim.time)
            paused = self.paused
            if paused and self.resumed_sim is None and wall.time - paused[0] >= self.pause:
                self.resumed_sim = self.sim.time
            sending = self.paused is None or self.resumed_sim is not None
            if sending and self.sim.time - self.last >= 0.05 - 1e-9:
                self.sim.command(0.3, 0.0)
                self.last = self.sim.time
            await asyncio.sleep(0)


async def test_the_sim_waits_for_a_stalled_command_stream(sim: Simulation) -> None:
    wall = FakeWall()
    runner = SimRunner(sim, CostlySink(sim, wall, 0.0), speed=10.0, wall=wall)
    client = StreamingClient(sim, pause_at=1.0, pause=0.3)
    await asyncio.gather(run_until(runner, wall, 1.0), client.run(wall))
    assert client.paused is not None
    assert client.resumed_sim is not None
    # late by LATE_WALL of wall time (0.2 s of sim time at 10x, 4 periods): it waited
    assert client.resumed_sim - client.paused[1] <= LATE_WALL * 10.0 + 0.02
    assert sim.drive.linear == pytest.approx(0.3)  # never timed out
    assert sim.time > 5.0


async def test_a_command_late_by_less_than_a_scheduler_slot_is_not_waited_for(
    sim: Simulation, caplog: pytest.LogCaptureFixture
) -> None:
    wall = FakeWall()
    runner = SimRunner(sim, CostlySink(sim, wall, 0.0), speed=10.0, wall=wall, report_every=0.5)
    client = StreamingClient(sim, pause_at=1.0, pause=0.015)  # 3 periods late, under LATE_WALL
    with caplog.at_level(logging.INFO, logger="aiobt_services.robot.runner"):
        await asyncio.gather(run_until(runner, wall, 1.0), client.run(wall))
    assert client.resumed_sim is not None
    assert "late cmd_vel" not in caplog.text
    assert sim.time == pytest.approx(10.0, abs=0.05)  # not held
    assert sim.drive.linear == pytest.approx(0.3)


def test_overdue_counts_from_the_larger_of_two_periods_and_the_patience() -> None:
    drive = DriveController()
    for step in range(5):
        drive.command(0.3, 0.0, 0.05 * step)  # a 20 Hz stream, last at 0.2
    assert not drive.overdue(0.2 + 0.09)
    assert drive.overdue(0.2 + 0.11)
    assert not drive.overdue(0.2 + 0.11, patience=0.2)
    assert drive.overdue(0.2 + 0.21, patience=0.2)
    assert not drive.overdue(0.2 + 0.51, patience=0.2)  # timed out: nothing to wait for


async def test_a_client_gone_is_waited_for_once_then_the_command_timeout_stops_the_base(
    sim: Simulation, caplog: pytest.LogCaptureFixture
) -> None:
    wall = FakeWall()
    runner = SimRunner(sim, CostlySink(sim, wall, 0.0), speed=10.0, wall=wall, report_every=0.5)
    client = StreamingClient(sim, pause_at=1.0, pause=math.inf)
    with caplog.at_level(logging.WARNING, logger="aiobt_services.robot.runner"):
        await asyncio.gather(run_until(runner, wall, 1.5), client.run(wall))
    assert sim.drive.linear == 0.0  # stopped by the command timeout
    assert sim.time > 5.0  # one wait of 0.5 s, not one per step
    assert "waited 1 time(s), 0.50 s in all, for a late cmd_vel" in caplog.text


async def test_command_wait_zero_never_waits(sim: Simulation) -> None:
    wall = FakeWall()
    runner = SimRunner(sim, CostlySink(sim, wall, 0.0), speed=10.0, wall=wall, command_wait=0.0)
    client = StreamingClient(sim, pause_at=1.0, pause=math.inf)
    await asyncio.gather(run_until(runner, wall, 1.0), client.run(wall))
    assert sim.time == pytest.approx(10.0, abs=0.05)
    assert sim.drive.linear == 0.0
