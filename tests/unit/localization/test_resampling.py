from typing import Any

import numpy as np

from aiobt_services.localization.kld import kld_count, resample_limit
from aiobt_services.localization.params import AmclParams
from aiobt_services.localization.recovery import RecoveryAverages
from aiobt_services.localization.resample import low_variance_indices, resample

from .maps import field

LIMITS: dict[str, Any] = {"min_particles": 500, "max_particles": 2000, "pf_err": 0.05, "pf_z": 0.99}


def _amcl_limit(k: int) -> int:
    """pf_resample_limit, transcribed from pf.c."""
    if k <= 1:
        return 2000
    b = 2 / (9 * (k - 1))
    x = 1 - b + np.sqrt(b) * 0.99
    return int(min(2000, max(500, np.ceil((k - 1) / (2 * 0.05) * x**3))))


def test_resample_limit_is_amcls_formula() -> None:
    ks = np.array([1, 2, 5, 20, 60, 200, 1000])
    assert resample_limit(ks, **LIMITS).tolist() == [_amcl_limit(int(k)) for k in ks]


def test_kld_keeps_few_particles_when_they_agree_and_many_when_they_spread() -> None:
    rng = np.random.default_rng(0)
    tight = np.column_stack([rng.normal(3, 0.05, (2000, 2)), rng.normal(0, 0.02, 2000)])
    spread = np.column_stack([rng.uniform(0, 20, (2000, 2)), rng.uniform(-np.pi, np.pi, 2000)])
    assert kld_count(tight, **LIMITS) == 501  # AMCL stops once count exceeds the minimum
    assert kld_count(spread, **LIMITS) == 2000


def test_low_variance_draws_each_particle_in_proportion_to_its_weight() -> None:
    weights = np.array([0.5, 0.25, 0.125, 0.125])
    idx = low_variance_indices(weights, 800, np.random.default_rng(3))
    assert np.bincount(idx, minlength=4).tolist() == [400, 200, 100, 100]  # exactly, not about


def test_resample_takes_the_heavy_particles_and_random_ones_in_free_space_at_w_diff() -> None:
    rng = np.random.default_rng(1)
    f = field()
    particles = np.array([[1.0, 1.0, 0.0], [4.0, 3.0, 1.0]])
    params = AmclParams()
    kept = resample(particles, np.array([1.0, 0.0]), params=params, w_diff=0.0, field=f, rng=rng)
    assert np.all(kept == particles[0])
    mixed = resample(particles, np.array([1.0, 0.0]), params=params, w_diff=0.5, field=f, rng=rng)
    share = np.mean(np.any(mixed != particles[0], axis=1))
    assert 0.4 < share < 0.6
    assert len(mixed) == 2000


def test_recovery_share_appears_when_the_fast_average_drops_below_the_slow() -> None:
    rec = RecoveryAverages(alpha_slow=0.001, alpha_fast=0.1)
    for _ in range(50):
        rec.update(1.0)
    assert rec.w_diff == 0.0
    for _ in range(20):
        rec.update(0.1)  # the measurements stop fitting
    assert rec.w_diff > 0.5
    rec.reset()
    assert rec.w_diff == 0.0
    off = RecoveryAverages(0.0, 0.0)
    off.update(1.0)
    off.update(0.01)
    assert off.w_diff == 0.0  # Nav2's default: recovery off
