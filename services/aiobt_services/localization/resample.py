"""Low-variance (systematic) resampling with KLD-adaptive size and AMCL's random
recovery particles.

AMCL itself draws with a naive multinomial sampler because, its comment says,
the low-variance sampler does not combine easily with KLD sampling. Here it
does: a systematic draw of ``max_particles`` in a random order is a fair
sample at every prefix, so the KLD bound (:func:`.kld.kld_count`) cuts the
prefix where AMCL's incremental loop would have stopped.
"""

from __future__ import annotations

import numpy as np
import numpy.typing as npt

from .kld import kld_count
from .likelihood_field import LikelihoodField
from .params import AmclParams
from .se2 import FloatArray


def low_variance_indices(
    weights: FloatArray, count: int, rng: np.random.Generator
) -> npt.NDArray[np.intp]:
    """``count`` indices drawn in proportion to ``weights`` with one random offset
    (Probabilistic Robotics p. 110): a particle of weight ``w`` is drawn
    ``floor(count * w)`` or one more times."""
    cumulative = np.cumsum(weights)
    cumulative /= cumulative[-1]
    points = (rng.uniform(0.0, 1.0) + np.arange(count)) / count
    return np.minimum(np.searchsorted(cumulative, points, side="right"), len(weights) - 1)


def resample(
    particles: FloatArray,
    weights: FloatArray,
    *,
    params: AmclParams,
    w_diff: float,
    field: LikelihoodField,
    rng: np.random.Generator,
) -> FloatArray:
    """The new particle set (equal weights implied): drawn by weight, each replaced
    with probability ``w_diff`` by a random pose in free space, sized by KLD."""
    drawn = particles[low_variance_indices(weights, params.max_particles, rng)]
    drawn = drawn[rng.permutation(len(drawn))]
    if w_diff > 0.0:
        replace = rng.uniform(0.0, 1.0, len(drawn)) < w_diff
        drawn[replace] = field.random_free_poses(int(replace.sum()), rng)
    count = kld_count(
        drawn,
        min_particles=params.min_particles,
        max_particles=params.max_particles,
        pf_err=params.pf_err,
        pf_z=params.pf_z,
    )
    return np.ascontiguousarray(drawn[:count])
