"""Command-line options -> simulation config, and bad values named."""

from __future__ import annotations

import argparse

import pytest

from aiobt_services.robot.options import add_robot_arguments, sim_config


def parse(*argv: str) -> argparse.Namespace:
    parser = argparse.ArgumentParser()
    add_robot_arguments(parser)
    return parser.parse_args(list(argv))


def test_defaults_and_overrides() -> None:
    cfg = sim_config(parse())
    assert cfg.dt == 0.01
    assert cfg.lidar.rays == 360
    assert cfg.lidar.angle_increment == pytest.approx(2 * 3.141592653589793 / 360)
    cfg = sim_config(parse("--max-linear", "0.4", "--lidar-rays", "90", "--slip", "0.1"))
    assert cfg.limits.max_linear == 0.4
    assert cfg.lidar.angle_increment == pytest.approx(2 * 3.141592653589793 / 90)
    assert cfg.noise.slip == 0.1


@pytest.mark.parametrize("flag", ["--speed", "--dt", "--max-linear"])
def test_non_positive_numbers_refused(flag: str, capsys: pytest.CaptureFixture[str]) -> None:
    with pytest.raises(SystemExit):
        parse(flag, "0")
    assert flag in capsys.readouterr().err


def test_bad_noise_named() -> None:
    with pytest.raises(ValueError, match="slip"):
        sim_config(parse("--slip", "1.5"))
    with pytest.raises(ValueError, match="rays"):
        sim_config(parse("--lidar-rays", "0"))


def test_clock_rate_defaults_to_100_hz() -> None:
    assert parse().clock_hz == 100.0
    assert parse("--clock-hz", "50").clock_hz == 50.0
