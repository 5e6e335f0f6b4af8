"""A misspelled flag gets the closest known one, as a misspelled node ID does."""

from __future__ import annotations

import pytest

from aiobt.cli.main import main


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
