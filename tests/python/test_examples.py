"""The Python examples run (briefly) and say what they did."""

import os
import subprocess
import sys
import unittest

from support import SOURCE_DIR, temp_dir

EXAMPLES = os.path.join(SOURCE_DIR, "examples", "python")


def run(script, *args):
    r = subprocess.run([sys.executable, os.path.join(EXAMPLES, script), *args], capture_output=True, text=True, timeout=300)
    if r.returncode != 0:
        raise AssertionError(f"{script} exited {r.returncode}:\n{r.stdout}\n{r.stderr}")
    return r.stdout


class Examples(unittest.TestCase):
    def test_random_agent(self):
        out = run("random_agent.py", "--episodes", "2", "--max-time", "3")
        self.assertIn("episode 1 (seed 2)", out)
        out = run("random_agent.py", "--episodes", "2", "--max-time", "1", "--envs", "2")
        self.assertEqual(out.count("env "), 2, out)

    def test_batch_eval(self):
        out_dir = temp_dir("py-example-eval")
        out = run("batch_eval.py", "--trials", "2", "--jobs", "2", "--duration", "5", "--out", out_dir)
        self.assertIn("explorer", out)
        self.assertIn("wall_follower", out)
        for c in ("explorer", "wall_follower"):
            self.assertTrue(os.path.exists(os.path.join(out_dir, c, "summary.png")), c)

    def test_mission_team(self):
        out = run("mission_team.py", "--max-time", "12")
        self.assertIn("r1: in contact True", out)
        self.assertIn("team score ", out)
        self.assertIn("/6 victims reported", out)


if __name__ == "__main__":
    unittest.main()
