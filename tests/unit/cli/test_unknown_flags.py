"""A misspelled flag gets the closest known one, as a misspelled node ID does."""

from __future__ import annotations

import pytest

from aiobt.cli.main import _full_parser, main


def test_a_misspelled_service_flag_gets_did_you_mean(capsys: pytest.CaptureFixture[str]) -> None:
    with pytest.raises(SystemExit) as exit_:
        main(["controller", "--max-sped", "0.4"])
    assert exit_.value.code == 2
    last = capsys.readouterr().err.splitlines()[-1]
    assert last == (
        "aiobt controller: error: unrecognized arguments: "
        "--max-sped (did you mean --max-speed?) 0.4"
    )


def test_a_flag_like_none_is_named_without_a_guess(capsys: pytest.CaptureFixture[str]) -> None:
    with pytest.raises(SystemExit):
        main(["navigate", "1", "1", "--zzz"])
    assert capsys.readouterr().err.splitlines()[-1].endswith("unrecognized arguments: --zzz")


def test_a_through_pose_with_a_negative_x_is_a_pose_not_a_flag() -> None:
    argv = ["navigate", "--through", "-1.5,1.9", "1,-2,0.5", "-3,-4"]
    args = _full_parser(argv).parse_args(argv)
    assert args.through == [(-1.5, 1.9), (1.0, -2.0, 0.5), (-3.0, -4.0)]
    argv = ["navigate", "-1.5", "-0.5"]  # and plain negative numbers still are numbers
    assert _full_parser(argv).parse_args(argv).pose == [-1.5, -0.5]
