"""rescuesim.Env's simulation control, the operations ROS 2's Simulation Interfaces offer, on the
same RunControl as the ROS 2, ROS 1 and Foxglove services: entities and their categories, a
teleport that moves the robot where asked while its odometry does not notice, and the errors of
bad requests (docs/python.md)."""

import math
import unittest

import rescuesim


class Control(unittest.TestCase):
    def setUp(self):
        self.env = rescuesim.Env(None, control_period=0.1, max_time=30)
        self.env.reset(seed=1)

    def tearDown(self):
        self.env.close()

    def test_entities_by_category_and_name(self):
        names = self.env.entities()
        self.assertEqual(names[0], "robot")
        self.assertEqual(self.env.entities(categories=[1]), ["robot"])
        self.assertEqual(self.env.entities(filter="^rob"), ["robot"])
        humans = self.env.entities(categories=[2])
        self.assertGreater(len(humans), 0)
        self.assertEqual(self.env._core.entity_category(humans[0]), 2)

    def test_teleport_moves_the_robot_and_not_its_odometry(self):
        x, y, z = self.env.entity_state("robot")["position"]  # where it starts
        for _ in range(5):
            self.env.step((0.3, 0.0))
        self.assertGreater(self.env.entity_state("robot")["position"][0], x + 0.05)
        # a quarter turn about z: (0, 0, sin 45°, cos 45°)
        s = math.sqrt(0.5)
        # back to the start (free floor: it just drove over it), turned a quarter left
        self.env.set_entity_state("robot", position=(x, y, z), orientation=(0, 0, s, s),
                                  linear=(0, 0, 0), angular=(0, 0, 0))
        after = self.env.entity_state("robot")
        self.assertAlmostEqual(after["position"][0], x, places=9)
        self.assertAlmostEqual(after["position"][1], y, places=9)
        self.assertAlmostEqual(after["orientation"][2], s, places=9)
        # standing still, it stays within 5 cm over 0.5 s
        for _ in range(5):
            self.env.step((0.0, 0.0))
        there = self.env.entity_state("robot")["position"]
        self.assertLess(math.hypot(there[0] - x, there[1] - y), 0.05)

    def test_bad_requests_name_the_problem(self):
        with self.assertRaisesRegex(rescuesim.Error, "no entity named 'ghost'"):
            self.env.entity_state("ghost")
        with self.assertRaisesRegex(rescuesim.Error, "not a unit quaternion"):
            self.env.set_entity_state("robot", orientation=(0, 0, 0.5, 0.5))
        with self.assertRaisesRegex(rescuesim.Error, "not finite"):
            self.env.set_entity_state("robot", position=(float("nan"), 0, 0))
        with self.assertRaisesRegex(rescuesim.Error, "no such file /nowhere.urdf.*result 104"):
            self.env.spawn("p3at", "file:///nowhere.urdf")
        with self.assertRaisesRegex(rescuesim.Error, "comes from the scenario"):
            self.env.delete("robot")

    def test_a_spawned_box_falls_and_is_deleted(self):
        x, y, _ = self.env.entity_state("robot")["position"]
        # 2.5 m above the robot: 0.3 s of free fall takes it down g 0.3^2 / 2 = 0.44 m
        name = self.env.spawn("crate", "box", position=(x, y, 2.5))
        self.assertEqual(name, "crate")
        self.assertIn("crate", self.env.entities(categories=[4]))
        for _ in range(3):  # 3 agent steps of 0.1 s
            self.env.step((0.0, 0.0))
        z = self.env.entity_state("crate")["position"][2]
        self.assertAlmostEqual(z, 2.5 - 0.5 * 9.81 * 0.3 ** 2, delta=0.02)
        self.env.delete("crate")
        self.assertNotIn("crate", self.env.entities())

    def test_features_and_state_hash(self):
        f = self.env.simulator_features()
        self.assertIn(11, f["features"])  # ENTITY_STATE_SETTING
        h = self.env.state_hash()
        self.assertEqual(h, self.env.state_hash())
        self.env.step((0.2, 0.0))
        self.assertNotEqual(h, self.env.state_hash())


if __name__ == "__main__":
    unittest.main()
