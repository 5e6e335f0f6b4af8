"""KLD-adaptive sample count (Fox 2003, AMCL's ``pf_resample_limit``) and the
histogram it counts bins in (AMCL's kd-tree: 0.5 m x 0.5 m x 10 degrees)."""

from __future__ import annotations

import numpy as np
import numpy.typing as npt

from .se2 import FloatArray

BIN_SIZE = np.array([0.5, 0.5, np.deg2rad(10.0)])
IntArray = npt.NDArray[np.int64]


def bin_keys(particles: FloatArray) -> IntArray:
    """The histogram bin (integer x, y, yaw index) of each particle."""
    keys: IntArray = np.floor(particles / BIN_SIZE).astype(np.int64)
    return keys


def bin_codes(particles: FloatArray) -> IntArray:
    """One integer per histogram bin (the three indices packed, 21 bits each: bins
    of a map up to 500 km a side), so bins are told apart by a 1-D sort."""
    keys = bin_keys(particles) + (1 << 20)
    codes: IntArray = (keys[:, 0] << 42) | (keys[:, 1] << 21) | keys[:, 2]
    return codes


def resample_limit(
    k: IntArray, *, min_particles: int, max_particles: int, pf_err: float, pf_z: float
) -> IntArray:
    """Samples needed when ``k`` bins are occupied (each element of ``k``): the
    chi-square bound with error ``pf_err`` at quantile ``pf_z``, clamped to the
    particle limits; ``max_particles`` for ``k <= 1``, as AMCL."""
    k = np.asarray(k, dtype=np.float64)
    km1 = np.maximum(k - 1.0, 1.0)
    b = 2.0 / (9.0 * km1)
    x = 1.0 - b + np.sqrt(b) * pf_z
    n = np.ceil((k - 1.0) / (2.0 * pf_err) * x * x * x)
    limit = np.clip(n, min_particles, max_particles).astype(np.int64)
    return np.where(k <= 1.0, max_particles, limit)


def kld_count(
    candidates: FloatArray, *, min_particles: int, max_particles: int, pf_err: float, pf_z: float
) -> int:
    """How many of ``candidates`` (in draw order) AMCL keeps: it adds samples one by
    one and stops after the first count that exceeds the limit for the bins occupied
    so far. Vectorised: the occupied-bin count of every prefix, then the first stop."""
    n = len(candidates)
    if n == 0:
        return 0
    _, first = np.unique(bin_codes(candidates), return_index=True)
    new_bin = np.zeros(n, dtype=np.int64)
    new_bin[first] = 1
    occupied = np.cumsum(new_bin)
    counts = np.arange(1, n + 1)
    limits = resample_limit(
        occupied, min_particles=min_particles, max_particles=max_particles, pf_err=pf_err, pf_z=pf_z
    )
    stop = np.flatnonzero(counts > limits)
    return int(stop[0] + 1) if stop.size else n
