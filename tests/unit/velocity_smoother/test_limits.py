"""Nav2's testfindEtaConstraint and testapplyConstraints* cases (test_velocity_smoother.cpp)."""

from __future__ import annotations

import pytest

from aiobt_services.velocity_smoother import apply_constraints, find_eta_constraint

F = 20.0  # Nav2's default smoothing_frequency
ACCEL, DECEL = 0.1, -1.0  # dv 0.005 and 0.05 per period


def eta(v_curr: float, v_cmd: float) -> float:
    return float(find_eta_constraint(v_curr, v_cmd, ACCEL, DECEL, F))


def step(v_curr: float, v_cmd: float, accel: float = ACCEL, decel: float = DECEL,
         eta_: float = 1.0) -> float:  # fmt: skip
    return float(apply_constraints(v_curr, v_cmd, accel, decel, eta_, F))


@pytest.mark.parametrize(
    ("v_curr", "v_cmd"),
    [(1.0, 1.0), (-1.0, -1.0), (0.5, 0.504), (0.5, 0.46), (0.0, 0.004), (0.04, 0.0),
     (-0.5, -0.504), (-0.5, -0.46), (0.0, -0.004), (-0.04, 0.0), (-0.02, 0.02),
     (0.02, -0.02)],
)  # fmt: skip
def test_a_change_within_the_limits_needs_no_eta(v_curr: float, v_cmd: float) -> None:
    assert eta(v_curr, v_cmd) == -1.0


@pytest.mark.parametrize(
    ("v_curr", "v_cmd", "expected"),
    [(0.5, 1.5, 0.005), (1.5, 0.5, 0.05), (0.0, 1.0, 0.005), (1.0, 0.0, 0.05),
     (-0.5, -1.5, 0.005), (-1.5, -0.5, 0.05), (0.0, -1.0, 0.005), (-1.0, 0.0, 0.05),
     (-0.2, 0.8, 0.05), (0.2, -0.8, 0.05)],
)  # fmt: skip
def test_a_change_beyond_the_limits_is_scaled_by_eta(
    v_curr: float, v_cmd: float, expected: float
) -> None:
    assert eta(v_curr, v_cmd) == pytest.approx(expected)


def test_apply_constraints_cases_of_nav2() -> None:
    assert step(1.0, 1.0, 1.5, -2.0) == 1.0
    assert step(0.5, 0.55, 1.5, -2.0) == pytest.approx(0.55)
    assert step(0.5, 0.45, 1.5, -2.0) == pytest.approx(0.45)
    assert step(1.0, 2.0, 1.5, -2.0) == pytest.approx(1.075, abs=0.01)
    assert step(1.0, 2.0, 1.5, -2.0, 0.075) == pytest.approx(1.075, abs=0.01)
    assert step(0.5, 0.55, 1.5, -2.0, 0.075) == pytest.approx(0.503, abs=0.01)


def ramp(init: float, target: float) -> list[float]:
    values, v = [], init
    for _ in range(2000):
        v = step(v, target)
        values.append(v)
        if abs(v - target) < 1e-9:
            break
    return values


@pytest.mark.parametrize(("init", "target"), [(1.0, 2.0), (0.0, 2.0), (-1.0, -2.0), (0.0, -2.0)])
def test_speeding_up_moves_by_max_accel_per_period(init: float, target: float) -> None:
    values = ramp(init, target)
    sign = 1.0 if target > init else -1.0
    for i, v in enumerate(values[:-1], start=1):
        assert v == pytest.approx(init + sign * i * ACCEL / F, abs=1e-3)
    assert values[-1] == pytest.approx(target)
    assert step(values[-1], target) == pytest.approx(target)


@pytest.mark.parametrize(("init", "target"), [(2.0, 1.0), (2.0, 0.0), (-2.0, -1.0), (-2.0, 0.0)])
def test_slowing_down_moves_by_max_decel_per_period(init: float, target: float) -> None:
    values = ramp(init, target)
    sign = 1.0 if target > init else -1.0
    for i, v in enumerate(values, start=1):
        assert v == pytest.approx(init + sign * i * -DECEL / F, abs=1e-3)
    assert values[-1] == pytest.approx(target)


@pytest.mark.parametrize(("init", "target"), [(-1.0, 2.0), (1.0, -2.0)])
def test_through_zero_decelerates_then_accelerates(init: float, target: float) -> None:
    values = ramp(init, target)
    sign = 1.0 if target > 0 else -1.0
    to_zero = round(abs(init) / (-DECEL / F))
    for i, v in enumerate(values, start=1):
        if i <= to_zero:
            assert v == pytest.approx(init + sign * i * -DECEL / F, abs=1e-3)
        else:
            assert v == pytest.approx(sign * (i - to_zero) * ACCEL / F, abs=1e-3)
    assert values[-1] == pytest.approx(target)
