"""rescuesim.Env: reset/step like Gymnasium, reproducible resets, observations as numpy views of
the simulation's buffers (shapes, dtypes, aliasing), the task's rewards, independent
simulations in one process, and the Gymnasium registration."""

import sys
import types
import unittest

import numpy as np

import rescuesim
import rescuesim.env
from support import ENV_YAML, TINY_YAML, temp_dir, write_tiny


def tiny():
    return rescuesim.parse_scenario(ENV_YAML, "small.yaml")


def snapshot(obs):
    return {k: v.copy() for k, v in obs.items()}


def same(a, b):
    """Bitwise equality of two observation dicts (NaN and inf included)."""
    return a.keys() == b.keys() and all(a[k].dtype == b[k].dtype and a[k].tobytes() == b[k].tobytes() for k in a)


def pointer(a):
    return a.__array_interface__["data"][0]


ACTIONS = [(0.4, 0.0)] * 5 + [(0.2, 0.8)] * 5 + [(0.5, -0.3)] * 5


class ResetAndStep(unittest.TestCase):
    def test_reset_with_a_seed_twice_gives_identical_observations(self):
        env = rescuesim.Env(tiny())
        first, info1 = env.reset(seed=7)
        first = snapshot(first)
        after = []
        for a in ACTIONS:
            obs, *_ = env.step(a)
            after.append(snapshot(obs))
        second, info2 = env.reset(seed=7)
        self.assertTrue(same(first, second))
        self.assertEqual(info1, info2)
        for a, expected in zip(ACTIONS, after):
            obs, *_ = env.step(a)
            self.assertTrue(same(expected, obs))
        # a second environment with the same seed agrees; another seed does not
        other = rescuesim.Env(tiny())
        obs, _ = other.reset(seed=7)
        self.assertTrue(same(first, obs))
        obs, _ = other.reset(seed=8)
        self.assertFalse(same(first, obs))

    def test_reset_with_the_same_seed_restores_the_start_instead_of_rebuilding(self):
        env = rescuesim.Env(tiny())
        episodes = []
        builds = []
        for _ in range(3):
            obs, info = env.reset(seed=5)
            builds.append(env._core.builds)
            run = [snapshot(obs)]
            for a in ACTIONS:
                obs, reward, *_ = env.step(a)
                run.append(snapshot(obs))
                run.append(reward)
            episodes.append((run, env._core.info()))
        # the first reset builds for seed 5 (construction built the scenario's seed 11); the next
        # two restore, and replay bitwise the first (observations, rewards, final info)
        self.assertEqual(builds, [2, 2, 2])
        for run, info in episodes[1:]:
            self.assertEqual(info, episodes[0][1])
            for x, y in zip(run, episodes[0][0]):
                self.assertTrue(same(x, y) if isinstance(x, dict) else x == y)
        # another seed builds anew
        env.reset(seed=6)
        self.assertEqual(env._core.builds, 3)

    def test_reset_without_a_seed_continues_from_the_last(self):
        env = rescuesim.Env(tiny())
        self.assertEqual(env.reset()[1]["seed"], 11)  # the scenario's
        self.assertEqual(env.reset()[1]["seed"], 12)
        self.assertEqual(env.reset(seed=40)[1]["seed"], 40)
        self.assertEqual(env.reset()[1]["seed"], 41)

    def test_shapes_dtypes_and_plausible_values(self):
        env = rescuesim.Env(tiny())
        self.assertEqual(env.observation_fields, {
            "laser": (np.dtype("float32"), (541,)),
            "imu": (np.dtype("float64"), (10,)),
            "odometry": (np.dtype("float64"), (5,)),
            "sonar": (np.dtype("float32"), (4,)),
        })
        obs, info = env.reset(seed=3)
        for key, (dtype, shape) in env.observation_fields.items():
            self.assertEqual(obs[key].dtype, dtype, key)
            self.assertEqual(obs[key].shape, shape, key)
        # the laser sees the walls of a 7.5 m maze: every return is within it or none (REP-117)
        finite = obs["laser"][np.isfinite(obs["laser"])]
        self.assertGreater(len(finite), 400)
        self.assertTrue(np.all((finite > 0.05) & (finite < 10.7)))
        # standing still: the IMU feels gravity, its quaternion is a unit one
        self.assertAlmostEqual(float(np.linalg.norm(obs["imu"][:4])), 1.0, places=6)
        self.assertAlmostEqual(float(obs["imu"][9]), 9.81, delta=0.2)
        np.testing.assert_allclose(obs["odometry"], 0.0, atol=1e-6)
        self.assertEqual(info["pose"], (0.75, 0.75, info["pose"][2]))  # the start cell's centre
        for _ in range(10):
            obs, *_ = env.step((0.5, 0.0))
        self.assertGreater(obs["odometry"][3], 0.3)  # driving forward

    def test_actions_as_arrays_or_dicts(self):
        env = rescuesim.Env(tiny())
        env.reset(seed=3)
        env.step(np.array([0.3, 0.1], dtype=np.float32))
        env.step({"linear": 0.3, "angular": 0.1})
        with self.assertRaises(rescuesim.Error):
            env.step((float("nan"), 0.0))


class ObservationMemory(unittest.TestCase):
    def test_observations_are_read_only_views_of_the_simulation_buffers(self):
        env = rescuesim.Env(tiny())
        obs, _ = env.reset(seed=5)
        laser = obs["laser"]
        # the array owns no memory: its base is the C++ environment, which keeps the buffer alive
        self.assertIs(laser.base, env._core)
        self.assertFalse(laser.flags.owndata)
        self.assertFalse(laser.flags.writeable)
        with self.assertRaises(ValueError):
            laser[0] = 1.0
        before = laser.copy()
        addresses = {k: pointer(v) for k, v in obs.items()}
        obs2, *_ = env.step((0.5, 0.5))
        obs3, *_ = env.step((0.5, 0.5))
        # the same memory, overwritten in place by each step (and by reset)
        for k, v in obs3.items():
            self.assertEqual(pointer(v), addresses[k], k)
            self.assertIs(v, obs[k])
        self.assertFalse(np.array_equal(before, laser, equal_nan=True))
        obs4, _ = env.reset(seed=6)
        self.assertEqual(pointer(obs4["laser"]), addresses["laser"])

    def test_copy_observations_gives_arrays_of_their_own(self):
        env = rescuesim.Env(tiny(), copy_observations=True)
        obs, _ = env.reset(seed=5)
        obs2, *_ = env.step((0.5, 0.5))
        self.assertTrue(obs["laser"].flags.owndata)
        self.assertNotEqual(pointer(obs["laser"]), pointer(obs2["laser"]))
        self.assertTrue(same(obs2, env.observations))

    def test_choosing_observations(self):
        env = rescuesim.Env(tiny(), observations=["laser"])
        obs, _ = env.reset(seed=1)
        self.assertEqual(list(obs), ["laser"])
        with self.assertRaisesRegex(rescuesim.Error, "no observation 'camera'.*available: laser, imu, odometry, sonar"):
            rescuesim.Env(tiny(), observations=["camera"])


class Task(unittest.TestCase):
    def test_rewards_follow_victims_collisions_and_time(self):
        env = rescuesim.Env(tiny(), time_penalty=0.5, collision_penalty=2.0, victim_reward=10.0)
        _, info = env.reset(seed=11)
        collisions = info["collisions"]
        saw_collision = False
        # drive at the walls and turn, long enough to hit something
        for k in range(60):
            _, reward, terminated, truncated, info = env.step((0.8, 0.0) if k % 20 < 14 else (0.0, 1.5))
            hits = info["collisions"] - collisions
            saw_collision |= hits > 0
            collisions = info["collisions"]
            self.assertAlmostEqual(reward, 10.0 * len(info["new_victims"]) - 2.0 * hits - 0.5 * 0.1, places=9)
            if terminated or truncated:
                break
        self.assertTrue(saw_collision, "the robot never touched a wall")

    def test_an_episode_ends_at_max_time_and_must_then_be_reset(self):
        env = rescuesim.Env(tiny(), max_time=1.0)
        with self.assertRaisesRegex(rescuesim.Error, "call reset"):
            env.step((0, 0))
        env.reset(seed=2)
        for k in range(10):
            _, _, terminated, truncated, info = env.step((0.0, 0.0))
        self.assertTrue(truncated or terminated)
        self.assertAlmostEqual(info["sim_time"], 1.0)
        self.assertEqual(info["steps"], 10)
        with self.assertRaisesRegex(rescuesim.Error, "episode is over"):
            env.step((0, 0))
        env.reset()
        env.step((0, 0))

    def test_finding_every_victim_terminates(self):
        # the built-in explorer drives (the actions are ignored) until every victim is found
        env = rescuesim.Env(rescuesim.parse_scenario(TINY_YAML, "tiny.yaml"), controller="explorer", max_time=30)
        for seed in range(11, 16):
            env.reset(seed=seed)
            while True:
                _, _, terminated, truncated, info = env.step((0, 0))
                if terminated or truncated:
                    break
            self.assertEqual(terminated, info["victims_found"] == info["victims_total"], info)
            if terminated:
                return
        self.fail("the explorer found every victim in none of five mazes")


class IndependentSimulations(unittest.TestCase):
    def test_environments_in_one_process_do_not_affect_each_other(self):
        def alone(seed):
            env = rescuesim.Env(tiny())
            out = [snapshot(env.reset(seed=seed)[0])]
            for a in ACTIONS:
                out.append(snapshot(env.step(a)[0]))
            return out

        a_alone, b_alone = alone(21), alone(22)
        a, b = rescuesim.Env(tiny()), rescuesim.Env(tiny())
        a_obs = [snapshot(a.reset(seed=21)[0])]
        b_obs = [snapshot(b.reset(seed=22)[0])]
        for act in ACTIONS:
            b_obs.append(snapshot(b.step((-act[0], act[1]))[0]))  # b does something else meanwhile
            a_obs.append(snapshot(a.step(act)[0]))
        self.assertTrue(all(same(x, y) for x, y in zip(a_alone, a_obs)))
        self.assertTrue(same(b_alone[0], b_obs[0]))
        self.assertFalse(same(b_alone[-1], b_obs[-1]))


class Scenarios(unittest.TestCase):
    def test_scenarios_from_files_text_mazes_and_the_default(self):
        path = write_tiny(temp_dir("py-scenarios"))
        s = rescuesim.load_scenario(path)
        self.assertEqual((s.name, s.seed, s.duration, s.is_maze), ("tiny", 11, 5.0, True))
        self.assertEqual(s.file, path)
        self.assertEqual(rescuesim.default_scenario().name, "default")
        m = rescuesim.maze_scenario(cols=5, rows=4, victims=3, seed=9, duration=30)
        self.assertEqual((m.seed, m.duration, m.robots), (9, 30.0, ["robot"]))
        env = rescuesim.Env(path)
        self.assertEqual(env.scenario.name, "tiny")
        with self.assertRaisesRegex(rescuesim.Error, "cols"):
            rescuesim.maze_scenario(cols=0)
        with self.assertRaisesRegex(rescuesim.Error, "nope.yaml"):
            rescuesim.load_scenario("/nonexistent/nope.yaml")
        self.assertTrue(issubclass(rescuesim.Error, ValueError))


# the OpenGL libraries a process has mapped, by file name (EGL, GLX, libGL, Mesa's drivers)
GL_MAPS = """
import sys, rescuesim
def gl():
    names = set()
    for line in open("/proc/self/maps"):
        name = line.split()[-1].rsplit("/", 1)[-1]
        if name.startswith(("libEGL", "libGLX", "libGL.", "libgbm")) or name.endswith("_dri.so"):
            names.add(name)
    return sorted(names)
env = rescuesim.Env(rescuesim.parse_scenario(sys.argv[1], "small.yaml"))
env.reset(seed=3)
for _ in range(5):
    env.step((0.3, 0.0))
print("without:", " ".join(gl()))
try:
    env = rescuesim.Env(rescuesim.parse_scenario(sys.argv[2], "cams.yaml"), cameras=True)
    env.reset(seed=3)
    env.step((0.0, 0.0))
    print("with:", " ".join(gl()))
except rescuesim.Error as e:
    print("with: error", e)
"""


class NoOpenGLWithoutCameras(unittest.TestCase):
    def test_opengl_is_loaded_only_when_cameras_are_asked_for(self):
        # a fresh interpreter, so that no other test has loaded a renderer into it: stepping an
        # environment without cameras maps no EGL or GL library (the module links libepoxy,
        # which opens them on first use), so it runs where there is no OpenGL at all; with
        # cameras they are loaded (the control: the check sees them when they are there)
        import subprocess
        cams = ENV_YAML + ("robots:\n  - name: robot\n    sensors:\n"
                           "      color_camera: {width: 32, height: 24}\n")
        out = subprocess.run([sys.executable, "-c", GL_MAPS, ENV_YAML, cams], capture_output=True, text=True, timeout=240)
        self.assertEqual(out.returncode, 0, out.stderr)
        lines = dict(line.split(":", 1) for line in out.stdout.splitlines() if ":" in line)
        self.assertEqual(lines["without"].strip(), "", out.stdout)
        self.assertIn("libEGL", lines["with"], out.stdout)


class Cameras(unittest.TestCase):
    def test_camera_images_as_arrays(self):
        text = ENV_YAML + ("robots:\n  - name: robot\n    sensors:\n"
                            "      color_camera: {width: 64, height: 48}\n"
                            "      depth_camera: {width: 40, height: 30}\n"
                            "      thermal_camera: {width: 32, height: 24}\n")
        try:
            env = rescuesim.Env(rescuesim.parse_scenario(text, "cams.yaml"), cameras=True)
        except rescuesim.Error as e:
            self.skipTest(f"no renderer here: {e}")
        self.assertEqual(env.observation_fields["color_camera"], (np.dtype("uint8"), (48, 64, 3)))
        self.assertEqual(env.observation_fields["depth_camera"], (np.dtype("float32"), (30, 40)))
        self.assertEqual(env.observation_fields["thermal_camera"], (np.dtype("uint16"), (24, 32)))
        obs, _ = env.reset(seed=4)
        for _ in range(3):
            obs, *_ = env.step((0.0, 0.0))
        self.assertGreater(int(obs["color_camera"].max()), 0)
        self.assertTrue(np.isfinite(obs["depth_camera"]).any())
        # thermal counts are 0.01 K: the scene sits around room temperature (about 29 315)
        self.assertTrue(27000 < float(np.median(obs["thermal_camera"])) < 32000)
        self.assertIs(obs["color_camera"].base, env._core)


class Gymnasium(unittest.TestCase):
    def test_registered_and_wrapped_when_gymnasium_is_installed(self):
        # a stand-in for gymnasium (it is not a dependency), recording what rescuesim does with it
        fake = types.ModuleType("gymnasium")
        spaces = types.ModuleType("gymnasium.spaces")
        registry = {}

        class Box:
            def __init__(self, low, high, shape=None, dtype=None):
                self.low, self.high, self.dtype = low, high, np.dtype(dtype)
                self.shape = tuple(shape) if shape is not None else np.shape(low)

        class Dict(dict):
            pass

        class Env:
            def reset(self, *, seed=None, options=None):
                self.seeded = seed

        spaces.Box, spaces.Dict = Box, Dict
        fake.spaces, fake.Env = spaces, Env
        fake.register = lambda id, entry_point: registry.update({id: entry_point})
        sys.modules["gymnasium"], sys.modules["gymnasium.spaces"] = fake, spaces
        try:
            rescuesim.env._registered = False
            rescuesim.env.__dict__.pop("GymEnv", None)
            self.assertTrue(rescuesim.env.register_with_gymnasium())
            self.assertEqual(registry, {"rescuesim/Rescue-v0": "rescuesim.env:GymEnv"})
            env = rescuesim.env.GymEnv(tiny(), max_time=1.0)
            self.assertEqual(env.observation_space["laser"].shape, (541,))
            self.assertEqual(env.action_space.shape, (2,))
            obs, info = env.reset(seed=3)
            self.assertEqual(env.seeded, 3)
            self.assertTrue(obs["laser"].flags.owndata)  # copies, for replay buffers
            obs, reward, terminated, truncated, info = env.step(np.array([0.2, 0.0], dtype=np.float32))
            self.assertEqual(info["steps"], 1)
        finally:
            del sys.modules["gymnasium"], sys.modules["gymnasium.spaces"]
            rescuesim.env.__dict__.pop("GymEnv", None)
            rescuesim.env._registered = False


if __name__ == "__main__":
    unittest.main()
