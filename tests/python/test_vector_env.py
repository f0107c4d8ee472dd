"""rescuesim.VectorEnv: K independent simulations stepped together, their observations one
[K, ...] numpy view per key; the same results as K separate environments, on one thread or
several; "next step" autoreset."""

import unittest

import numpy as np

import rescuesim
from support import ENV_YAML


def scenario():
    return rescuesim.parse_scenario(ENV_YAML, "small.yaml")


def actions_at(k, n):
    """Different actions for each environment and step."""
    return np.array([[0.5 * np.cos(0.3 * k + i), 0.8 * np.sin(0.2 * k + 2 * i)] for i in range(n)])


class VectorEnvTest(unittest.TestCase):
    def run_vector(self, threads, steps=12):
        v = rescuesim.VectorEnv(scenario(), 3, threads=threads)
        obs, infos = v.reset(seed=100)
        out = [{k: a.copy() for k, a in obs.items()}]
        for k in range(steps):
            obs, rewards, terminated, truncated, infos = v.step(actions_at(k, 3))
            out.append({k2: a.copy() for k2, a in obs.items()})
        return out, infos

    def test_rows_equal_separate_environments(self):
        vec, infos = self.run_vector(threads=1)
        self.assertEqual(vec[0]["laser"].shape, (3, 541))
        self.assertEqual(vec[0]["imu"].dtype, np.float64)
        self.assertEqual(list(infos["seed"]), [100, 101, 102])
        for i in range(3):
            env = rescuesim.Env(scenario())
            obs, _ = env.reset(seed=100 + i)
            rows = [{k: a.copy() for k, a in obs.items()}]
            for k in range(12):
                obs, *_ = env.step(actions_at(k, 3)[i])
                rows.append({k2: a.copy() for k2, a in obs.items()})
            for step, (single, batch) in enumerate(zip(rows, vec)):
                for key in single:
                    self.assertEqual(single[key].tobytes(), batch[key][i].tobytes(), f"env {i} step {step} {key}")

    def test_threads_do_not_change_results(self):
        one, _ = self.run_vector(threads=1)
        two, _ = self.run_vector(threads=2)
        for a, b in zip(one, two):
            for key in a:
                self.assertEqual(a[key].tobytes(), b[key].tobytes(), key)

    def test_one_block_per_key_without_copies(self):
        v = rescuesim.VectorEnv(scenario(), 2)
        obs, _ = v.reset(seed=1)
        laser = obs["laser"]
        self.assertIs(laser.base, v._core)
        self.assertFalse(laser.flags.writeable)
        self.assertTrue(laser.flags.c_contiguous)
        address = laser.__array_interface__["data"][0]
        obs2, *_ = v.step(np.zeros((2, 2)))
        self.assertEqual(obs2["laser"].__array_interface__["data"][0], address)
        # row i is environment i's buffer, right after row i - 1
        self.assertEqual(laser[1].__array_interface__["data"][0], address + 541 * 4)
        with self.assertRaisesRegex(rescuesim.Error, "shape \\(2, 2\\)"):
            v._core.step(np.zeros((3, 2)))

    def test_finished_environments_reset_on_the_next_step(self):
        v = rescuesim.VectorEnv(scenario(), 2, max_time=0.3)
        v.reset(seed=10)
        for _ in range(3):
            obs, rewards, terminated, truncated, infos = v.step(np.full((2, 2), 0.3))
        self.assertTrue(np.all(terminated | truncated))
        obs, rewards, terminated, truncated, infos = v.step(np.full((2, 2), 0.3))
        self.assertTrue(np.all(infos["_reset"]))
        self.assertTrue(np.all(rewards == 0))
        self.assertEqual(list(infos["seed"]), [12, 13])  # previous seed + K
        fresh, _ = rescuesim.Env(scenario()).reset(seed=13)
        self.assertEqual(fresh["laser"].tobytes(), obs["laser"][1].tobytes())
        obs, rewards, terminated, truncated, infos = v.step(np.full((2, 2), 0.3))
        self.assertFalse(np.any(infos["_reset"]))
        self.assertEqual(list(infos["steps"]), [1, 1])


if __name__ == "__main__":
    unittest.main()
