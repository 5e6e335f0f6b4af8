"""``likelihood_field_prob`` against a direct transcription of Nav2's
``LikelihoodFieldModelProb::sensorFunction`` (one particle and one beam at a time,
in doubles), beam skipping on and off, and its all-beams fallback."""

from __future__ import annotations

import math

import numpy as np
import numpy.typing as npt

from aiobt_services.localization.laser_model import select_beams
from aiobt_services.localization.likelihood_field import OCCUPIED, LikelihoodField
from aiobt_services.localization.likelihood_field_prob import BeamSkip, LikelihoodFieldProbModel

from .maps import RES, cast, field, room

BEARINGS = -np.pi + 2 * np.pi / 360 * np.arange(360, dtype=np.float64)
CELLS = room()
FIELD = field(CELLS)
Z_HIT, Z_RAND, SIGMA, MAX_DIST, RANGE_MAX = 0.5, 0.5, 0.2, 2.0, 12.0
SKIP = BeamSkip(distance=0.5, threshold=0.3, error_threshold=0.9)
OCC = np.argwhere(CELLS == OCCUPIED)  # (row, col) of the occupied cells


def occ_dist(x: float, y: float) -> float | None:
    """``map->cells[...].occ_dist``: the distance from the point's cell to the nearest
    occupied cell, capped at ``max_occ_dist``; None off the map. The cell is the one
    the point is in (our convention; AMCL's ``MAP_GXWX`` rounds)."""
    col, row = math.floor(x / RES), math.floor(y / RES)
    if not (0 <= row < CELLS.shape[0] and 0 <= col < CELLS.shape[1]):
        return None
    d = float(np.min(np.hypot(OCC[:, 0] - row, OCC[:, 1] - col))) * RES
    return min(d, MAX_DIST)


def nav2_log_weights(
    particles: npt.NDArray[np.float64],
    ranges: npt.NDArray[np.float64],
    *,
    max_beams: int,
    skip: BeamSkip | None,
    converged: bool,
) -> npt.NDArray[np.float64]:
    """``log`` of each particle's factor, Nav2's loops transcribed. One difference,
    the documented one: in the all-beams fallback Nav2 also reads ``temp_obs_`` of
    beams the scan lacks (0 or stale); here those stay out."""
    ranges = np.where(ranges <= 0.05, RANGE_MAX, ranges)  # amcl_node: range_min -> max
    step = max(1, math.ceil(len(ranges) / max_beams))
    denom = 2 * SIGMA * SIGMA
    max_dist_prob = math.exp(-(MAX_DIST * MAX_DIST) / denom)
    do_beamskip = skip is not None and converged
    obs_count = [0] * max_beams
    temp_obs = [[math.nan] * max_beams for _ in particles]
    log_ps = []
    for j, (px, py, pyaw) in enumerate(particles):
        log_p, beam_ind = 0.0, 0
        for i in range(0, len(ranges), step):
            r, b = float(ranges[i]), float(BEARINGS[i])
            if r >= RANGE_MAX or r != r:
                beam_ind += 1
                continue
            z = occ_dist(px + r * math.cos(pyaw + b), py + r * math.sin(pyaw + b))
            if z is None:
                pz = Z_HIT * max_dist_prob
            else:
                if skip is not None and z < skip.distance:
                    obs_count[beam_ind] += 1
                pz = Z_HIT * math.exp(-(z * z) / denom)
            pz += Z_RAND / RANGE_MAX
            if not do_beamskip:
                log_p += math.log(pz)
            else:
                temp_obs[j][beam_ind] = pz
            beam_ind += 1
        log_ps.append(log_p)
    if not do_beamskip:
        return np.array(log_ps)
    assert skip is not None
    mask = [obs_count[k] / len(particles) > skip.threshold for k in range(max_beams)]
    error = mask.count(False) >= max_beams * skip.error_threshold
    return np.array(
        [
            sum(
                math.log(temp_obs[j][k])
                for k in range(max_beams)
                if (error or mask[k]) and temp_obs[j][k] == temp_obs[j][k]
            )
            for j in range(len(particles))
        ]
    )


def ours(
    particles: npt.NDArray[np.float64],
    ranges: npt.NDArray[np.float64],
    *,
    max_beams: int,
    skip: BeamSkip | None,
    converged: bool,
    grid: LikelihoodField = FIELD,
) -> npt.NDArray[np.float64]:
    beams = select_beams(ranges, BEARINGS, max_beams=max_beams, range_min=0.05,
                         range_max=RANGE_MAX, laser_model_type="likelihood_field_prob")  # fmt: skip
    model = LikelihoodFieldProbModel(grid, Z_RAND, max_beams, skip)
    factors, log_scale = model.weigh(particles, beams, converged=converged)
    return np.log(factors) + log_scale


def _scan(
    rng: np.random.Generator, truth: tuple[float, float, float], blocked: float = 0.0
) -> npt.NDArray[np.float64]:
    """The room seen from ``truth``, with noise, NaNs, max-range and too-short
    readings; ``blocked``: that share of the beams cut short (obstacles not on the map)."""
    ranges = cast(CELLS, truth, BEARINGS) + rng.normal(0.0, 0.02, len(BEARINGS))
    bad = rng.choice(len(ranges), 12, replace=False)
    ranges[bad[:4]], ranges[bad[4:8]], ranges[bad[8:]] = np.nan, 13.0, 0.01
    cut = rng.random(len(ranges)) < blocked
    ranges[cut] = rng.uniform(0.2, 0.6, int(np.count_nonzero(cut)))
    return ranges


def _cloud(rng: np.random.Generator, around: tuple[float, float, float], n: int, spread: float):
    jitter = rng.normal(0.0, 1.0, (n, 3)) * np.array([spread, spread, spread / 2])
    return np.asarray(around) + jitter


def test_without_beam_skipping_it_is_nav2s_log_sum_on_random_cases() -> None:
    for seed in range(4):
        rng = np.random.default_rng(seed)
        truth = (rng.uniform(0.5, 5.5), rng.uniform(0.5, 3.5), rng.uniform(-3, 3))
        particles = np.column_stack(
            [rng.uniform(-0.5, 6.5, 25), rng.uniform(-0.5, 4.5, 25), rng.uniform(-3, 3, 25)]
        )  # some off the map
        ranges = _scan(rng, truth)
        for max_beams in (60, 23):
            expected = nav2_log_weights(particles, ranges, max_beams=max_beams, skip=None,
                                        converged=True)  # fmt: skip
            got = ours(particles, ranges, max_beams=max_beams, skip=None, converged=True)
            np.testing.assert_allclose(got, expected, rtol=1e-5, atol=1e-4)


def _agrees(
    particles: npt.NDArray[np.float64],
    ranges: npt.NDArray[np.float64],
    skip: BeamSkip,
    *,
    converged: bool,
) -> tuple[npt.NDArray[np.float64], npt.NDArray[np.float64]]:
    """Ours against Nav2's transcription (asserted), and ours with every beam."""
    got = ours(particles, ranges, max_beams=60, skip=skip, converged=converged)
    expected = nav2_log_weights(particles, ranges, max_beams=60, skip=skip, converged=converged)
    np.testing.assert_allclose(got, expected, rtol=1e-5, atol=1e-4)
    return got, ours(particles, ranges, max_beams=60, skip=None, converged=True)


def test_beam_skipping_leaves_out_the_beams_most_particles_disagree_with() -> None:
    rng = np.random.default_rng(11)
    truth = (2.5, 1.5, 0.4)
    particles, ranges = _cloud(rng, truth, 40, 0.05), _scan(rng, truth, blocked=0.3)
    got, all_beams = _agrees(particles, ranges, SKIP, converged=True)
    assert np.all(got > all_beams + 5.0)  # the blocked beams' low pz left out


def test_beam_skipping_waits_for_the_filter_to_converge() -> None:
    rng = np.random.default_rng(12)
    truth = (2.5, 1.5, 0.4)
    particles, ranges = _cloud(rng, truth, 30, 0.05), _scan(rng, truth, blocked=0.3)
    got, all_beams = _agrees(particles, ranges, SKIP, converged=False)
    np.testing.assert_allclose(got, all_beams)


def test_too_many_skipped_beams_fall_back_to_all_of_them() -> None:
    rng = np.random.default_rng(13)
    particles = _cloud(rng, (4.5, 2.8, -2.0), 30, 0.05)  # converged, on a wrong pose
    strict = BeamSkip(distance=0.1, threshold=0.9, error_threshold=0.5)
    got, all_beams = _agrees(particles, _scan(rng, (2.5, 1.5, 0.4)), strict, converged=True)
    np.testing.assert_allclose(got, all_beams)  # the fallback: every beam


def test_the_product_does_not_underflow_where_nav2s_would() -> None:
    """1,440 beams: each beam's ``pz`` is at most 0.54, so ``exp(sum log pz)`` is below
    1e-300 for every particle (AMCL's total 0: uniform weights)."""
    rng = np.random.default_rng(14)
    truth = (2.5, 1.5, 0.4)
    particles = np.vstack([truth, _cloud(rng, truth, 20, 0.1)])
    bearings = np.linspace(-np.pi, np.pi, 1440, endpoint=False)
    ranges = cast(CELLS, truth, bearings)
    beams = select_beams(ranges, bearings, max_beams=1440, range_min=0.05, range_max=RANGE_MAX,
                         laser_model_type="likelihood_field_prob")  # fmt: skip
    model = LikelihoodFieldProbModel(FIELD, Z_RAND, 1440)
    factors, log_scale = model.weigh(particles, beams, converged=False)
    assert math.exp(log_scale) == 0.0  # the best particle's exp(sum log pz) itself
    assert factors[0] == 1.0  # the truth weighs most
    assert np.all(factors[1:] < 1.0)


def test_the_prob_models_stride_is_ceil_n_over_max_beams() -> None:
    ranges = np.full(361, 3.0)
    bearings = np.linspace(-np.pi, np.pi, 361)
    prob = select_beams(ranges, bearings, max_beams=60, range_min=0.05, range_max=12.0,
                        laser_model_type="likelihood_field_prob")  # fmt: skip
    plain = select_beams(ranges, bearings, max_beams=60, range_min=0.05, range_max=12.0)
    assert (len(prob.ranges), len(plain.ranges)) == (52, 61)  # steps 7 and 6


def test_beams_the_scan_lacks_count_as_skipped_against_max_beams() -> None:
    """50 of ``max_beams`` 60 beams in the scan: with 41 or 42 agreeing, 19 or 18 are
    skipped, at or above 0.3 x 60, so all beams are used (Nav2 counts the missing
    ones as skipped); with 43, 17 skipped: the 43 alone. A beam agreeing for exactly
    ``beam_skip_threshold`` of the particles is skipped (``>``)."""
    model = LikelihoodFieldProbModel(FIELD, Z_RAND, max_beams=60)
    skip = BeamSkip(distance=0.5, threshold=0.3, error_threshold=0.3)

    def used(agreeing: int) -> npt.NDArray[np.bool_]:
        dist = np.full((10, 50), np.inf, dtype=np.float32)
        dist[:, :agreeing] = 0.1
        dist[:3, agreeing:] = 0.1  # 3 of 10 particles: exactly the threshold, not above
        return model.used_beams(dist, skip)

    assert used(41).all()
    assert used(42).all()
    assert used(43).sum() == 43
    assert used(43)[:43].all()
