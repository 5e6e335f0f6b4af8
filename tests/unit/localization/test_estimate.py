import numpy as np

from aiobt_services.localization.estimate import cluster_labels, estimate


def test_estimate_is_the_heaviest_clusters_mean_with_the_sets_covariance() -> None:
    rng = np.random.default_rng(0)
    a = np.column_stack([rng.normal(2.0, 0.1, (600, 2)), rng.normal(0.5, 0.05, 600)])
    b = np.column_stack([rng.normal(8.0, 0.1, (400, 2)), rng.normal(-1.0, 0.05, 400)])
    particles = np.vstack([a, b])
    est = estimate(particles, np.ones(1000))
    assert est.clusters == 2
    assert abs(est.weight - 0.6) < 1e-9
    np.testing.assert_allclose(est.mean, [2.0, 2.0, 0.5], atol=0.02)
    assert est.covariance[0, 0] > 5.0  # the set's spread: both clusters, 6 m apart
    lighter = estimate(particles, np.r_[np.ones(600), np.full(400, 2.0)])
    np.testing.assert_allclose(lighter.mean[:2], [8.0, 8.0], atol=0.02)


def test_a_cluster_across_plus_minus_pi_is_one_cluster_with_heading_pi() -> None:
    rng = np.random.default_rng(1)
    yaw = np.pi + rng.normal(0.0, 0.05, 500)
    yaw = (yaw + np.pi) % (2 * np.pi) - np.pi
    particles = np.column_stack([rng.normal(1.0, 0.05, (500, 2)), yaw])
    _, count = cluster_labels(particles)
    assert count == 1
    est = estimate(particles, np.ones(500))
    assert abs(abs(est.mean[2]) - np.pi) < 0.02
    assert 0.0 < est.covariance[2, 2] < 0.01  # -2 ln R of a 0.05 rad spread
