"""bench.system.report's rows (planner, controller, pacing, the rest of the machine), options."""

from __future__ import annotations

import argparse
import math
import os
import time

import pytest

from aiobt_services.controller.cycle_stats import CycleStats
from bench.system.procstat import (
    TICKS,
    Machine,
    cpu_seconds,
    machine,
    others_percent,
    stolen_seconds,
)
from bench.system.report import (
    CYCLES,
    Figures,
    controller_rows,
    main,
    others_row,
    pacing_row,
    planner_rows,
    pooled_rate,
    priorities,
    spin,
    stack_config,
    summed_row,
)


def test_the_first_trip_is_shown_against_the_slowest_of_the_others() -> None:
    figures = Figures(round_trips=[0.080, 0.012, 0.045, 0.010])
    spread, first, _ = planner_rows(figures)
    assert spread.startswith("| planner round trip ms p50 / p99 / max (n=4, failed 0) |")
    assert "| 80.0 / 45.0 |" in first


def test_the_planners_own_time_is_shown_beside_the_round_trip() -> None:
    figures = Figures(round_trips=[0.030, 0.060], planning_times=[0.004, 0.020, 0.010])
    *_, inside = planner_rows(figures)
    assert "| of which in the planner (planning_time) ms p50 / p99 / max | 10.0 / " in inside
    assert inside.endswith(" / 20.0 |  |")
    assert "| n/a |" in planner_rows(Figures(round_trips=[0.03]))[2]


def test_with_one_trip_there_is_nothing_to_set_it_against() -> None:
    _, first, _ = planner_rows(Figures(round_trips=[0.02]))
    assert "| n/a |" in first


def test_the_controller_rows_come_from_its_goal_lines_with_the_slots_served() -> None:
    stats = CycleStats(0.05)
    for began in (0.0, 0.05, 0.10, 0.25, 0.30):  # two slots lost before 0.25
        stats.record(began, 0.001)
    line = f"follow_path: goal abc: {stats.summary()}"
    goals = [
        (int(m[0]), float(m[1]), float(m[2]), float(m[4]), float(m[5]), int(m[6]))
        for m in CYCLES.findall(f"noise\n{line}\n")
    ]
    assert goals == [(5, 13.33, 20.0, 1.0, 1.0, 2)]
    rate, served, p99 = controller_rows(goals)
    assert "| 66.6%, 66.6%; 66.7% |" in rate  # 4 periods in 0.3 s: 13.33 Hz (logged) of 20
    assert "| 71.4%, 71.4% |" in served  # 5 cycles of 7 slots
    assert "| 1.00, 1.00; 1.00 |" in p99


def test_the_pooled_rate_weighs_each_goal_by_its_robot_time() -> None:
    # 1001 cycles at 20 Hz (50 s) and a 2-cycle goal whose one interval came 20 ms late
    goals = [(1001, 20.0, 20.0, 1.0, 1.0, 0), (2, 1 / 0.07, 20.0, 1.0, 1.0, 0)]
    assert pooled_rate(goals) == pytest.approx(1001 / 50.07 / 20.0)  # 99.98 %
    rate = controller_rows(goals)[0]
    assert "| 85.7%, 71.4%; 100.0% |" in rate  # the short goal's 71 % is the min
    assert math.isnan(pooled_rate([(1, math.nan, 20.0, 1.0, 1.0, 0)]))  # no interval at all


def test_the_pacing_row_sums_the_robots_reports() -> None:
    log = (
        "W simulation behind --speed 10: achieved x9.1 over the last 5.0 s; fell more than "
        "0.008 s behind 3 time(s), 0.42 s of sim time given up; waited 2 time(s), 0.05 s in "
        "all, for a late cmd_vel\n"
        "W simulation at --speed 10: achieved x9.9 over the last 5.0 s; waited 1 time(s), "
        "0.02 s in all, for a late cmd_vel\n"
        "W simulation behind --speed 10: achieved x8.0 over the last 5.0 s; fell more than "
        "0.008 s behind 5 time(s), 1.10 s of sim time given up\n"
    )
    assert "| 1.52 s in 8 / 3, 0.07 wall s |" in pacing_row(log)
    assert "| 0.00 s in 0 / 0, 0.00 wall s |" in pacing_row("robot up\n")


def test_the_rest_of_the_machine_is_every_other_process_and_the_time_stolen() -> None:
    first = Machine(10.0, {1: 5.0, 20: 1.0, 30: 2.0, 40: 9.0}, steal=3.0)
    # 2 s later: the stack (20, 30) used 1.2 s; pid 1 used 0.5 s, pid 50 started and used
    # 1.0 s, pid 40 ended (missed); 0.2 s stolen
    last = Machine(12.0, {1: 5.5, 20: 2.0, 30: 2.2, 50: 1.0}, steal=3.2)
    others, stolen = others_percent(first, last, [20, 30])
    assert others == pytest.approx(75.0)  # 1.5 s in 2 s
    assert stolen == pytest.approx(10.0)
    assert "| 2.0 / 75.0; stolen 0.0 / 10.0 |" in others_row([(2.0, 0.0), (75.0, 10.0)])
    assert "| n/a |" in others_row([])


def test_the_stolen_time_comes_from_the_all_cores_line() -> None:
    assert stolen_seconds(f"cpu  100 0 20 900 5 0 0 {3 * TICKS} 0 0\n") == pytest.approx(3.0)
    with pytest.raises(ValueError, match="all-cores line: 'cpu0 1 2 3 4 5 6 7 8'"):
        stolen_seconds("cpu0 1 2 3 4 5 6 7 8")
    with pytest.raises(ValueError, match="in order"):
        others_percent(Machine(2.0, {}, 0.0), Machine(1.0, {}, 0.0), [])


def test_a_live_sample_holds_this_process_and_its_cpu() -> None:
    sample = machine()
    assert sample.cpu[os.getpid()] > 0.0
    assert sample.steal >= 0.0


def test_the_stack_is_summed_without_the_bench_client() -> None:
    figures = Figures(
        cpu_idle={"router": 1.0, "robot": 8.0, "planner": 0.5, "bench client": 3.0},
        cpu_driving={"router": 2.0, "robot": 9.0, "planner": 1.5, "bench client": 6.0},
        speed_idle=0.95,
        speed_driving=0.5,
    )
    line = summed_row(figures, 1.0, 1.0)
    assert line.startswith("| CPU the stack summed % of a core: idle / driving (3 processes, ")
    assert "a plan every 1 s); the same per sim time at x1 | 9.5 / 12.5; 10.0 / 25.0 |" in line


def test_the_probe_period_must_be_positive(capsys: pytest.CaptureFixture[str]) -> None:
    with pytest.raises(SystemExit):
        main(["--probe-period", "0"])
    assert "--probe-period must be > 0 s, got 0.0" in capsys.readouterr().err


def test_busy_must_not_be_negative(capsys: pytest.CaptureFixture[str]) -> None:
    with pytest.raises(SystemExit) as exited:
        main(["--busy", "-1"])
    assert exited.value.code == 2
    assert "--busy must be 0 or more processes, got -1" in capsys.readouterr().err


def test_a_priority_names_a_raised_service_and_a_fifo_level() -> None:
    assert priorities(["planner=90", "robot=80"]) == {"planner": 90, "robot": 80}
    with pytest.raises(
        ValueError, match="'router=80': NAME must be one of robot, localization, controller"
    ):
        priorities(["router=80"])
    with pytest.raises(ValueError, match="'planner=100': N must be a SCHED_FIFO level"):
        priorities(["planner=100"])
    with pytest.raises(ValueError, match="'planner': N must be"):
        priorities(["planner"])


def options(**given: object) -> argparse.Namespace:
    """The options :func:`stack_config` reads (1x, wall clock, all in), ``given`` replaced."""
    values = {"speed": 1.0, "seed": 1, "realtime": False, "clock_hz": None}
    values |= {"localization": True, "safety_chain": True, "sim_time": False}
    return argparse.Namespace(**{**values, **given})


def test_without_localization_the_robot_gives_its_stand_in_pose() -> None:
    config = stack_config(options(localization=False, realtime=True, clock_hz=50.0), {})
    assert "localization" not in config.services
    assert {"robot", "planner", "controller", "navigator", "collision_monitor"} <= {
        *config.services
    }
    robot = config.command("robot", "tcp/127.0.0.1:7447", "ns")
    assert robot[-5:] == ["--realtime-priority", "--clock-hz", "50.0", "--pose-source", "truth"]
    assert "localization" not in config.extra
    with_it = stack_config(options(), {})
    assert "localization" in with_it.services
    assert "--pose-source" not in with_it.command("robot", "tcp/127.0.0.1:7447", "ns")


def test_a_priority_needs_realtime(capsys: pytest.CaptureFixture[str]) -> None:
    with pytest.raises(SystemExit):
        main(["--priority", "planner=90"])
    assert "--priority needs --realtime" in capsys.readouterr().err


@pytest.mark.timeout(30)
def test_a_busy_process_spins_until_killed() -> None:
    spinner = spin()
    try:
        deadline = time.monotonic() + 20.0
        while cpu_seconds(spinner.pid) < 0.2 and time.monotonic() < deadline:
            time.sleep(0.05)
        assert cpu_seconds(spinner.pid) >= 0.2  # it works, not sleeps
        assert spinner.poll() is None
    finally:
        spinner.kill()
        spinner.wait(timeout=10.0)
    assert spinner.returncode == -9
