"""rescuesim.Env in a mission: victim reports judged by the referee, datagrams, relays and the
radio status, on a 10 m x 10 m floor with one victim at a known place (docs/missions.md)."""

import os
import unittest

import rescuesim
from support import temp_dir

# 100 units = 1 m; SVG y grows downwards, the world's y upwards: (700, 500) is (7, 5) m. A wall
# at x = 4.5 m hides the victim from the robot, so the episode does not end at once.
SVG = """<svg xmlns="http://www.w3.org/2000/svg" width="10m" height="10m" viewBox="0 0 1000 1000">
  <line x1="450" y1="100" x2="450" y2="900" stroke="#000" stroke-width="10"/>
  <circle id="victim-a" cx="700" cy="500" r="25" fill="blue" data-posture="sitting"/>
  <circle id="robot" cx="200" cy="500" r="30" fill="#2ca02c"/>
  <line x1="200" y1="500" x2="270" y2="500" stroke="#2ca02c" stroke-width="6"/>
</svg>
"""

YAML = """name: mission
seed: 3
duration: 60
world: {svg: floor.svg}
robots:
  - {name: r, controller: none}
mission:
  radio: {model: wss}
"""


def scenario(text=YAML):
    folder = temp_dir("mission")
    with open(os.path.join(folder, "floor.svg"), "w") as f:
        f.write(SVG)
    return rescuesim.parse_scenario(text, os.path.join(folder, "mission.yaml"))


class Reports(unittest.TestCase):
    def setUp(self):
        self.env = rescuesim.Env(scenario(), control_period=0.1)
        self.env.reset(seed=3)

    def wait(self, seconds):
        for _ in range(round(seconds / 0.1)):
            self.env.step((0.0, 0.0))

    def test_a_report_near_the_victim_scores_and_a_wrong_one_costs(self):
        wrong = self.env.report(2.0, 9.0)  # 5 m from the victim
        self.assertEqual(wrong["outcome"], "false")
        self.assertEqual(wrong["score_change"], -0.5)
        self.assertIsNone(wrong["victim"])
        self.wait(0.6)  # two reports per second per robot (reset may leave the clock a step past 0)
        right = self.env.report(7.0, 5.3)
        self.assertEqual(right["outcome"], "accepted", right["message"])
        self.assertEqual(right["victim"], "victim-a")
        self.assertLess(right["distance"], 1.5)
        self.assertEqual(right["score"], 0.5)
        self.wait(0.6)
        again = self.env.report(6.8, 5.0)
        self.assertEqual(again["outcome"], "duplicate")
        score = self.env.mission_score()
        self.assertEqual(score["score"], 0.5)
        self.assertEqual(score["victims_found"], 1)
        self.assertEqual(score["victims"], 1)
        self.assertEqual(score["false_reports"], 1)
        self.assertEqual(score["reports"], 3)

    def test_a_report_takes_a_picture_as_a_numpy_array(self):
        import numpy as np

        picture = np.zeros((4, 6, 3), dtype=np.uint8)
        picture[:, :, 0] = 255
        right = self.env.report(7.0, 5.3, image=picture)
        self.assertEqual(right["outcome"], "accepted", right["message"])
        self.assertIn("with its picture", right["message"])
        self.wait(0.6)
        # an array that is no picture is a usage error, raised before anything is judged
        with self.assertRaisesRegex(rescuesim.Error, "H x W x 3"):
            self.env.report(6.8, 5.0, image=np.zeros((4, 6, 2), dtype=np.uint8))
        self.assertEqual(self.env.mission_score()["reports"], 1)
        # a picture the referee cannot keep (over 4096 pixels a side): judged, the picture left out
        again = self.env.report(6.8, 5.0, image=np.zeros((1, 4097), dtype=np.uint8))
        self.assertEqual(again["outcome"], "duplicate")
        self.assertIn("its picture was not kept: a picture of 4097 x 1 pixels", again["message"])

    def test_a_flood_and_nan_are_answered_not_scored(self):
        outcomes = [self.env.report(9.0, 9.0)["outcome"] for _ in range(50)]
        self.assertEqual(outcomes[0], "false")
        self.assertEqual(set(outcomes[1:]), {"rate_limited"})
        self.wait(0.6)
        self.assertEqual(self.env.report(float("nan"), 1.0)["outcome"], "invalid")
        self.assertEqual(self.env.mission_score()["score"], -0.5)

    def test_radio_status_datagrams_and_a_relay(self):
        status = self.env.comms_status()
        self.assertTrue(status["in_contact"])
        self.assertEqual(status["hops_to_base"], 1)
        self.assertEqual([n[0] for n in status["neighbours"]], ["base"])
        self.assertEqual(status["relays_left"], 12)
        self.assertEqual(self.env.send("base", b"victim at 7 5"), (True, ""))
        accepted, reason = self.env.send("nobody", b"x")
        self.assertFalse(accepted)
        self.assertIn("nobody", reason)
        self.assertEqual(self.env.drop_relay(), (True, "r/relay_1"))
        self.wait(0.2)
        self.assertEqual(self.env.comms_status()["relays_left"], 11)
        self.assertEqual(self.env.comms_status()["bytes_sent"], len(b"victim at 7 5"))
        self.assertEqual(self.env.inbox(), [])  # nobody wrote to the robot


class WithoutAMission(unittest.TestCase):
    def test_the_calls_say_there_is_no_mission(self):
        env = rescuesim.Env(scenario(YAML.replace("mission:\n  radio: {model: wss}\n", "")))
        env.reset(seed=3)
        self.assertIsNone(env.mission_score())
        with self.assertRaises(ValueError) as e:
            env.report(1.0, 1.0)
        self.assertIn("no mission", str(e.exception))


if __name__ == "__main__":
    unittest.main()
