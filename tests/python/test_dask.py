"""A batch on a real Dask cluster (a scheduler and two workers on loopback, started here with
Debian's python3-distributed) records the same trials as the local `rescuesim batch`, in the
same results.jsonl, and resumes like it."""

import json
import os
import subprocess
import sys
import time
import unittest

from rescuesim import _rescuesim
from support import cli, temp_dir, write_tiny

try:
    import distributed  # noqa: F401
    HAVE_DASK = True
except ImportError:
    HAVE_DASK = False


def by_trial(folder):
    with open(os.path.join(folder, "results.jsonl")) as f:
        return {json.loads(l)["trial"]: l for l in f.read().splitlines() if l.strip()}


@unittest.skipUnless(HAVE_DASK, "python3-distributed is not installed")
class DaskBatch(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.dir = temp_dir("py-dask")
        cls.procs = []
        sched_file = os.path.join(cls.dir, "scheduler.json")
        common = ["--no-dashboard", "--host", "127.0.0.1"]
        cls.start([sys.executable, "-m", "distributed.cli.dask_scheduler", "--port", "0", "--dashboard-address", "127.0.0.1:0",
                   "--scheduler-file", sched_file, "--idle-timeout", "300", *common], "scheduler")
        deadline = time.monotonic() + 90
        while not os.path.exists(sched_file) and time.monotonic() < deadline:
            time.sleep(0.1)
        with open(sched_file) as f:
            cls.address = json.load(f)["address"]
        for name in ("w1", "w2"):
            cls.start([sys.executable, "-m", "distributed.cli.dask_worker", cls.address, "--name", name, "--nthreads", "1",
                       "--no-nanny", "--memory-limit", "0", "--local-directory", os.path.join(cls.dir, name), *common], name)
        from distributed import Client
        with Client(cls.address, timeout=60) as c:
            c.wait_for_workers(2, timeout=90)

    @classmethod
    def start(cls, cmd, name):
        log = open(os.path.join(cls.dir, name + ".log"), "w")
        cls.procs.append((subprocess.Popen(cmd, stdout=log, stderr=subprocess.STDOUT), log))

    @classmethod
    def tearDownClass(cls):
        for p, log in reversed(cls.procs):
            p.terminate()
        for p, log in cls.procs:
            try:
                p.wait(timeout=20)
            except subprocess.TimeoutExpired:
                p.kill()
                p.wait()
            log.close()

    def dask_batch(self, *args):
        return subprocess.run([sys.executable, "-m", "rescuesim.dask_batch", "--scheduler", self.address, *args],
                              capture_output=True, text=True, timeout=300)

    def test_a_dask_batch_equals_the_local_batch_and_resumes(self):
        scenario = write_tiny(self.dir)
        local, remote = os.path.join(self.dir, "local"), os.path.join(self.dir, "dask")
        cli("batch", scenario, "--trials", "8", "--jobs", "2", "-q", "--out", local)

        r = self.dask_batch(scenario, "--trials", "6", "--out", remote)
        self.assertEqual(r.returncode, 0, r.stderr)
        self.assertIn("6 to run on Dask", r.stderr)
        self.assertEqual(sorted(by_trial(remote)), list(range(6)))
        # two more trials: only those run
        r = self.dask_batch(scenario, "--trials", "8", "--out", remote)
        self.assertEqual(r.returncode, 0, r.stderr)
        self.assertIn("6 already recorded", r.stderr)
        a, b = by_trial(local), by_trial(remote)
        self.assertEqual(sorted(a), sorted(b))
        for trial in a:
            self.assertTrue(_rescuesim.same_outcome(a[trial], b[trial]), f"trial {trial}:\n{a[trial]}\n{b[trial]}")
        with open(os.path.join(remote, "summary.json")) as f:
            self.assertEqual(json.load(f)["trials"], 8)
        # the CLI resumes and merges the Dask folder like its own
        again = cli("batch", scenario, "--trials", "8", "--out", remote)
        self.assertIn("8 already recorded", again.stdout)

    def test_bad_input_is_reported(self):
        r = self.dask_batch(os.path.join(self.dir, "missing.yaml"), "--trials", "2", "--out", os.path.join(self.dir, "x"))
        self.assertEqual(r.returncode, 2)
        self.assertIn("missing.yaml", r.stderr)


if __name__ == "__main__":
    unittest.main()
