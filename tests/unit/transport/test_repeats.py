"""RepeatedErrors: the first error of a kind in full, repeats as one counted line."""

from __future__ import annotations

import logging
from collections.abc import Callable

import pytest

from aiobt.transport.repeats import RepeatedErrors, kind_of

log = logging.getLogger("test.repeats")


class FakeClock:
    def __init__(self) -> None:
        self.now = 0.0

    def __call__(self) -> float:
        return self.now


def fail(value: float) -> None:
    raise ValueError(f"bad value {value}")


def other_failure() -> None:
    raise KeyError("x")


def raised(fn: Callable[..., None], *args: object) -> BaseException:
    try:
        fn(*args)
    except Exception as exc:
        return exc
    raise AssertionError("did not raise")


def test_kind_is_type_and_place_not_text() -> None:
    assert kind_of(raised(fail, 1.0)) == kind_of(raised(fail, 2.0))
    assert kind_of(raised(fail, 1.0)) != kind_of(raised(other_failure))
    assert kind_of(ValueError("never raised"))[1:] == ("", 0)


def test_repeats_are_counted_in_one_line_per_interval(caplog: pytest.LogCaptureFixture) -> None:
    clock = FakeClock()
    errors = RepeatedErrors(log, "robot/cmd_vel: subscriber callback", interval=10.0, clock=clock)
    with caplog.at_level(logging.ERROR, logger="test.repeats"):
        for i in range(1000):
            clock.now = i * 0.001  # 1000 errors in 1 s
            errors.report(raised(fail, i))
        errors.report(raised(other_failure))
        clock.now = 10.5
        errors.report(raised(fail, -1.0))
        errors.report(raised(fail, -2.0))
        errors.flush()
        errors.flush()  # nothing left: says nothing
    lines = [r.getMessage() for r in caplog.records]
    tracebacks = [r for r in caplog.records if r.exc_info]
    assert len(lines) == 4, lines
    assert len(tracebacks) == 2  # the first ValueError and the first KeyError
    assert "robot/cmd_vel: subscriber callback failed" in lines[0]
    assert "bad value 0" in lines[0]
    assert "KeyError" in lines[1] or "'x'" in lines[1]
    said = "failed 1000 more times in 10 s with the same error (ValueError: bad value 0)"
    assert said in lines[2]
    assert "latest: ValueError: bad value -1.0" in lines[2]
    assert "failed 1 more time in" in lines[3]
