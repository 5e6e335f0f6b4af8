"""The page's messages, the options, and the warning for a view open to other machines."""

from __future__ import annotations

import logging

import pytest

from aiobt.cli.main import _full_parser
from aiobt.cli.web import web_options
from aiobt.hosts import is_loopback
from aiobt.web import WebOptions
from aiobt.web.server import parse_goal, warn_if_open


def test_a_goal_message_gives_its_pose():
    assert parse_goal('{"goal": {"x": 1, "y": -2.5, "yaw": 0.5}}') == ((1.0, -2.5, 0.5), "")


@pytest.mark.parametrize(
    ("text", "named"),
    [
        ("not json", "expected"),
        ('{"goal": {"x": 1, "y": 2}}', "yaw"),
        ('{"other": 1}', "goal"),
        ('{"goal": {"x": "1", "y": 2, "yaw": 0}}', "must be numbers"),
        ('{"goal": {"x": true, "y": 2, "yaw": 0}}', "must be numbers"),
        ('{"goal": [1, 2, 3]}', "expected"),
    ],
)
def test_a_bad_page_message_is_refused_with_what_was_wrong(text, named):
    goal, problem = parse_goal(text)
    assert goal is None
    assert named in problem


def test_loopback_hosts():
    assert is_loopback("127.0.0.1")
    assert is_loopback("::1")
    assert is_loopback("localhost")
    assert not is_loopback("0.0.0.0")
    assert not is_loopback("192.168.1.5")
    assert not is_loopback("my-host")


def test_an_open_host_is_warned_about_and_loopback_is_not(caplog):
    with caplog.at_level(logging.WARNING, logger="aiobt.web.server"):
        warn_if_open("127.0.0.1", 8080)
        assert not caplog.records
        warn_if_open("0.0.0.0", 8080)
    assert "0.0.0.0:8080" in caplog.text
    assert "other machines" in caplog.text


def test_bad_options_are_refused_with_the_value():
    with pytest.raises(ValueError, match="70000"):
        WebOptions(port=70000)
    with pytest.raises(ValueError, match=r"0\.5"):
        WebOptions(rate=0.5)


def test_cli_flags_make_the_options():
    argv = ["web", "--port", "9000", "--robot-radius", "0.3", "--inflation-radius", "0.1"]
    options = web_options(_full_parser(argv).parse_args(argv))
    assert options.host == "127.0.0.1"  # loopback unless asked
    assert options.port == 9000
    assert options.inflation.inscribed_radius == 0.3
    assert options.inflation.inflation_radius == 0.3  # never inside the robot
