import numpy as np

from aiobt_services.localization.motion_model import DifferentialMotionModel
from aiobt_services.localization.se2 import angle_diff


def _moved(
    model: DifferentialMotionModel, start: np.ndarray, delta: np.ndarray, n: int = 20000
) -> np.ndarray:
    particles = np.tile(start, (n, 1))
    odom_pose = np.array([5.0, 5.0, 0.0]) + delta  # where in odom does not matter
    return model.odometry_update(particles, odom_pose, delta, np.random.default_rng(1))


def test_noise_free_model_applies_the_odometry_step_in_each_particles_frame() -> None:
    model = DifferentialMotionModel(0.0, 0.0, 0.0, 0.0)
    # 1 m straight ahead of the odometry's heading: a particle facing pi/2 goes up 1 m
    delta = np.array([1.0, 0.0, 0.1])
    out = _moved(model, np.array([0.0, 0.0, np.pi / 2]), delta, n=3)
    np.testing.assert_allclose(out[0], [0.0, 1.0, np.pi / 2 + 0.1], atol=1e-12)


def test_translation_noise_grows_with_alpha3_and_rotation_noise_with_alpha1() -> None:
    delta = np.array([1.0, 0.0, 0.0])
    still = _moved(DifferentialMotionModel(0.0, 0.0, 0.0, 0.0), np.zeros(3), delta)
    noisy = _moved(DifferentialMotionModel(0.0, 0.0, 0.04, 0.0), np.zeros(3), delta)
    assert np.std(still[:, 0]) < 1e-12
    assert abs(np.std(noisy[:, 0]) - 0.2) < 0.01  # sqrt(alpha3) * 1 m
    turn = np.array([0.0, 0.0, 1.0])
    spun = _moved(DifferentialMotionModel(0.01, 0.0, 0.0, 0.0), np.zeros(3), turn)
    assert abs(np.std(angle_diff(spun[:, 2], 1.0)) - 0.1) < 0.01  # sqrt(alpha1) * 1 rad
    assert np.allclose(spun[:, :2], 0.0)  # a turn in place: no translation (alpha4 = 0)


def test_backward_motion_is_as_noisy_as_forward() -> None:
    model = DifferentialMotionModel(0.2, 0.2, 0.2, 0.2)
    fwd = _moved(model, np.zeros(3), np.array([0.5, 0.0, 0.0]))
    back = _moved(model, np.zeros(3), np.array([-0.5, 0.0, 0.0]))
    assert abs(np.mean(fwd[:, 0]) - 0.5) < 0.02
    assert abs(np.mean(back[:, 0]) + 0.5) < 0.02
    assert abs(np.std(fwd[:, 0]) - np.std(back[:, 0])) < 0.01
