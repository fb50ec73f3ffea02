"""wingman/Formation-v0 is a Gymnasium environment: registered on `import wingman`, it
passes gymnasium's env_checker (spaces, seeding: the same seed gives the same episode,
render), and a random policy runs 1,000 steps through episodes that end and restart
without error; holding the slot earns more than flying away from it."""

import gymnasium
import numpy as np
from gymnasium.utils.env_checker import check_env

import wingman  # noqa: F401  (registers the environments)


def test_registered_and_passes_env_checker():
    env = gymnasium.make("wingman/Formation-v0")
    check_env(env.unwrapped, skip_render_check=False)
    obs, _ = env.reset(seed=5)
    assert obs.shape == (48, 64, 3) and obs.dtype == np.uint8
    env.close()


def test_measurement_observation_passes_env_checker():
    env = gymnasium.make("wingman/Formation-v0", measurement=True, episode_s=2.0)
    check_env(env.unwrapped)
    obs, _ = env.reset(seed=2)
    for _ in range(40):
        obs, *_ = env.step(np.zeros(3, dtype=np.float32))
    assert obs["measurement"][3] == 1.0, "the target is measured on the slot"


def test_same_seed_same_episode():
    env = gymnasium.make("wingman/Formation-v0", episode_s=1.0)
    runs = []
    for _ in range(2):
        env.reset(seed=11)
        rewards = [env.step(np.full(3, 0.3, dtype=np.float32))[1] for _ in range(10)]
        runs.append(rewards)
    assert runs[0] == runs[1]


def test_random_policy_thousand_steps():
    env = gymnasium.make("wingman/Formation-v0", episode_s=3.0)
    env.action_space.seed(0)
    env.reset(seed=0)
    episodes = 0
    for _ in range(1000):
        obs, reward, terminated, truncated, info = env.step(env.action_space.sample())
        assert env.observation_space.contains(obs)
        assert np.isfinite(reward) or info["status"] == "diverged"
        if terminated or truncated:
            episodes += 1
            env.reset()
    assert episodes >= 10
    assert env.render().shape == (48, 64, 3)


def test_holding_the_slot_earns_more_than_flying_away():
    env = gymnasium.make("wingman/Formation-v0", episode_s=4.0)
    totals = []
    for action in (np.zeros(3), np.array([0.0, 1.0, 0.0])):
        env.reset(seed=1)
        total, done = 0.0, False
        while not done:
            _, reward, terminated, truncated, _ = env.step(action.astype(np.float32))
            total += reward
            done = terminated or truncated
        totals.append(total)
    assert totals[0] > totals[1], totals
