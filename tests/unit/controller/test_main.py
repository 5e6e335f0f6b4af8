"""Command-line options of the controller and behavior services."""

from __future__ import annotations

import argparse

import pytest

from aiobt_services.behaviors.main import add_arguments as add_behavior_arguments
from aiobt_services.controller.main import add_arguments, config_from, costmap_from


def _parser(add) -> argparse.ArgumentParser:
    parser = argparse.ArgumentParser()
    add(parser)
    return parser


def test_options_configure_rate_speed_tolerances_and_costmap():
    args = _parser(add_arguments).parse_args(
        ["--rate", "10", "--max-speed", "0.3", "--failure-tolerance", "0", "--robot-radius", "0.3"]
    )
    config = config_from(args)
    assert config.control_period == pytest.approx(0.1)
    assert config.failure_tolerance == 0.0
    assert config.controllers["FollowPath"]().params.desired_linear_vel == 0.3  # type: ignore[attr-defined]
    assert config.controllers["DWB"]().params.max_vel_x == 0.3  # type: ignore[attr-defined]
    assert costmap_from(args).costmap.inflation.inscribed_radius == 0.3


@pytest.mark.parametrize("add", [add_arguments, add_behavior_arguments])
@pytest.mark.parametrize("bad", [["--rate", "0"], ["--rate", "nan"], ["--pose-timeout", "-1"]])
def test_bad_option_values_are_refused_naming_the_flag(add, bad, capsys):
    with pytest.raises(SystemExit):
        _parser(add).parse_args(bad)
    assert bad[0] in capsys.readouterr().err
