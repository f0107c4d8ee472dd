"""Batches from Python write the same results.jsonl as `rescuesim batch`: the same records for
the same trials, resumable and mergeable across the two, and the folder lock is shared."""

import json
import os
import unittest

import rescuesim
from rescuesim import _rescuesim
from support import cli, temp_dir, write_tiny


def lines_of(folder):
    with open(os.path.join(folder, "results.jsonl")) as f:
        return [l for l in f.read().splitlines() if l.strip()]


def by_trial(folder):
    return {json.loads(l)["trial"]: l for l in lines_of(folder)}


class PythonBatches(unittest.TestCase):
    def setUp(self):
        self.dir = temp_dir("py-batch-" + self._testMethodName)
        self.scenario = write_tiny(self.dir)

    def assert_same(self, a, b):
        self.assertEqual(sorted(a), sorted(b))
        for trial in a:
            self.assertTrue(_rescuesim.same_outcome(a[trial], b[trial]), f"trial {trial}:\n{a[trial]}\n{b[trial]}")

    def test_python_and_cli_batches_agree_and_resume_each_other(self):
        cli_dir, py_dir = os.path.join(self.dir, "cli"), os.path.join(self.dir, "py")
        r = cli("batch", self.scenario, "--trials", "8", "--jobs", "2", "-q", "--out", cli_dir)
        options = rescuesim.trial_options()
        self.assertIn(rescuesim.fingerprint(self.scenario, options), r.stdout)
        # half the batch from the CLI (one shard), the rest from Python in the same folder
        cli("batch", self.scenario, "--trials", "8", "--shard", "0/2", "-q", "--out", py_dir)
        summary = rescuesim.run_batch(self.scenario, py_dir, 8, progress=False)
        self.assertEqual(summary["trials"], 8)
        self.assertEqual(summary["run"]["trials"], 4)
        self.assertEqual(len(lines_of(py_dir)), 8)
        self.assert_same(by_trial(cli_dir), by_trial(py_dir))
        for f in ("summary.json", "summary.csv", "summary.png"):
            self.assertTrue(os.path.exists(os.path.join(py_dir, f)), f)
        # and nothing is left to do
        self.assertEqual(rescuesim.run_batch(self.scenario, py_dir, 8, progress=False)["trials"], 8)
        records = rescuesim.load_results(py_dir)
        self.assertEqual(records[3]["seed"], 14)

    def test_run_trial_returns_the_record(self):
        record = rescuesim.run_trial(self.scenario, 2, base_seed=100, options=rescuesim.trial_options(duration=2))
        self.assertEqual((record["trial"], record["seed"], record["status"]), (2, 102, "ok"))
        self.assertLessEqual(record["sim_time_s"], 2.0)
        self.assertEqual(record["host"], os.uname().nodename)

    def test_a_folder_is_locked_while_a_python_batch_holds_it(self):
        folder = os.path.join(self.dir, "locked")
        with rescuesim.batch.Batch(self.scenario, folder, 2) as b:
            self.assertEqual(b.todo, [0, 1])
            r = cli("batch", self.scenario, "--trials", "2", "--out", folder, check=False)
            self.assertEqual(r.returncode, 2)
            self.assertIn("another batch is writing this folder", r.stderr)
            with self.assertRaisesRegex(rescuesim.Error, "already has this batch folder open"):
                rescuesim.batch.Batch(self.scenario, folder, 2)
        cli("batch", self.scenario, "--trials", "2", "-q", "--out", folder)

    def test_merge_and_refusals(self):
        a, b, out = (os.path.join(self.dir, n) for n in ("a", "b", "out"))
        rescuesim.run_batch(self.scenario, a, 4, shard="0/2", progress=False)
        rescuesim.run_batch(self.scenario, b, 4, shard="1/2", progress=False)
        self.assertEqual(rescuesim.merge([a, b], out), [])
        self.assertEqual(sorted(by_trial(out)), [0, 1, 2, 3])
        with self.assertRaisesRegex(rescuesim.Error, "ran with seed"):
            rescuesim.run_batch(self.scenario, a, 4, seed=500, progress=False)
        with self.assertRaisesRegex(rescuesim.Error, "corrupt|not valid JSON"):
            _rescuesim.check_trial_line("{not json")


if __name__ == "__main__":
    unittest.main()
