"""Bad parameters are refused at start, naming the parameter (Nav2's testInvalidParams*)."""

from __future__ import annotations

import pytest

from aiobt_services.velocity_smoother import SmootherConfigError, SmootherParams
from aiobt_services.velocity_smoother.__main__ import main


def test_nav2_defaults() -> None:
    p = SmootherParams()
    assert (p.smoothing_frequency, p.feedback, p.scale_velocities) == (20.0, "OPEN_LOOP", False)
    assert p.max_velocity == (0.5, 0.0, 2.5)
    assert p.min_velocity == (-0.5, 0.0, -2.5)
    assert p.max_accel == (2.5, 0.0, 3.2)
    assert p.max_decel == (-2.5, 0.0, -3.2)
    assert (p.velocity_timeout, p.odom_duration, p.deadband_velocity) == (1.0, 0.1, (0.0,) * 3)


@pytest.mark.parametrize(
    ("fields", "named"),
    [
        ({"max_velocity": (0.0, 0.0)}, "max_velocity has 2 values"),
        ({"feedback": "LAWLS"}, "feedback 'LAWLS'"),
        ({"max_accel": (-10.0, -10.0, -10.0)}, "max_accel is -10 on axis x"),
        ({"max_decel": (10.0, 10.0, 10.0)}, "max_decel is 10 on axis x"),
        ({"min_velocity": (10.0, 10.0, 10.0)}, "min_velocity is 10 on axis x"),
        ({"max_velocity": (-10.0, -10.0, -10.0)}, "max_velocity is -10 on axis x"),
        ({"max_velocity": (0.5, 0.5, 0.5, 2.5)}, "max_velocity has 4 values"),
        ({"smoothing_frequency": 0.0}, "smoothing_frequency 0.0"),
        ({"velocity_timeout": -1.0}, "velocity_timeout -1.0"),
        ({"max_velocity": (float("nan"), 0.0, 1.0)}, "max_velocity [nan, 0.0, 1.0]"),
    ],
)
def test_a_bad_parameter_is_refused_by_name(fields: dict[str, object], named: str) -> None:
    with pytest.raises(SmootherConfigError, match=named.replace("[", r"\[")):
        SmootherParams(**fields)  # type: ignore[arg-type]


def test_the_service_refuses_a_bad_parameter_before_opening_the_bus(
    caplog: pytest.LogCaptureFixture,
) -> None:
    code = main(["--max-decel", "1", "0", "-3", "--connect", "tcp/127.0.0.1:1"])
    assert code == 2
    assert "max_decel is 1 on axis x" in caplog.text
