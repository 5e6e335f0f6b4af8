"""The transport benchmarks' summary of repeated runs (pure formatting and counting)."""

from __future__ import annotations

from bench.transport.summary import summarize


def rows(text: str) -> dict[str, list[str]]:
    table = [line for line in text.splitlines() if line.startswith("| ") and "---" not in line]
    return {
        cells[0]: cells[1:]
        for cells in ([c.strip() for c in line.strip("|").split("|")] for line in table[1:])
    }


def test_counts_runs_within_the_target_strictly_and_reports_median_and_range() -> None:
    text = summarize(
        {"raw_typed": [1.17, 1.2004, 1.19, 1.25], "reference": [1.13, 1.11, 1.14, 1.12]},
        {"raw_typed": 1.2},
        ["0.50", "0.60", "0.70", "0.80"],
    )
    assert text.startswith("4 runs, load average after each: 0.50 0.60 0.70 0.80")
    target, median, spread, within, every = rows(text)["raw_typed"]
    assert (target, median, spread) == ("1.2x", "1.20x", "1.17x-1.25x")
    assert within == "2 of 4"  # 1.2004 prints as 1.20 but is over the target
    assert every == "1.170 1.200 1.190 1.250"
    assert rows(text)["reference"][0] == "-"
    assert rows(text)["reference"][3] == "-"
