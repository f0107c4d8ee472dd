"""A batch on a Dask cluster: each trial runs in-process on a worker through the Python API,
and its record streams back into the same results.jsonl as ``rescuesim batch`` writes, so
resume and ``rescuesim batch merge`` work the same.

    python3 -m rescuesim.dask_batch --scheduler tcp://HOST:8786 SCENARIO.yaml --trials 1000 --out DIR

Workers need ``import rescuesim`` to work (the same build on every machine, e.g. on
PYTHONPATH) and, for SVG worlds, the SVG at the same path. Start them with one thread each
(``dask worker tcp://HOST:8786 --nthreads 1 --nworkers N``): a trial already fills a core.
A trial whose worker dies (a crash) is recorded as failed once Dask gives up on it. See
docs/batch.md.
"""

import argparse
import json
import sys
import time

from . import _rescuesim
from .batch import Batch, describe, trial_options

_worker_ready = False


def run_on_worker(text, file, trial, seed, fingerprint, duration, controller, cameras, stop_when_all_found):
    """The task: runs one trial in the worker's process and returns its results.jsonl line."""
    global _worker_ready
    if not _worker_ready:
        # one trial per worker thread: ray casting stays on the trial's own thread
        _rescuesim.set_ray_threads(1)
        _worker_ready = True
    scenario = _rescuesim.parse_scenario(text, file)
    options = trial_options(duration, controller, cameras, stop_when_all_found)
    return _rescuesim.run_trial(scenario, trial, seed, options, fingerprint)


def run(client, scenario, out, trials, *, seed=None, shard="", options=None, retry_failed=False, log=sys.stderr):
    """Runs the batch's missing trials on the cluster behind ``client`` and returns summary.json
    as a dict. Records are appended as trials finish, in finishing order."""
    from distributed import as_completed

    with Batch(scenario, out, trials, seed=seed, shard=shard, options=options, retry_failed=retry_failed, log=log) as b:
        o = b.options
        print(f"batch {b.scenario.name} ({b.fingerprint}): {len(b.mine)} trials, "
              f"{len(b.mine) - len(b.todo)} already recorded in {b.out}/results.jsonl, {len(b.todo)} to run on Dask", file=log)
        t0 = time.monotonic()
        futures = {}
        for trial in b.todo:
            f = client.submit(run_on_worker, b.scenario.text, b.scenario.file, trial, b.seed_of(trial), b.fingerprint,
                              o.duration, o.controller, o.cameras, o.stop_when_all_found,
                              key=f"rescuesim-{b.fingerprint}-trial-{trial}-{b.seed_of(trial)}", pure=False)
            futures[f] = trial
        done = failed = 0
        try:
            for f in as_completed(list(futures)):
                trial = futures[f]
                try:
                    line = f.result()
                except Exception as e:  # the worker died (KilledWorker) or the task could not run
                    line = b.record_failure(trial, f"the Dask task failed: {type(e).__name__}: {e}")
                else:
                    b.record(line)
                record = json.loads(line)
                done += 1
                failed += record["status"] != "ok"
                print(describe(record, done, len(b.todo)), file=log)
                f.release()
        except KeyboardInterrupt:
            client.cancel(list(futures))
            print(f"interrupted: {len(b.todo) - done} trials not recorded; run the same command again to finish", file=log)
            raise
        summary = b.finish(0, done, time.monotonic() - t0)
        print(f"{summary['trials']} trials recorded: {summary['successes']} found every victim, "
              f"{summary['trials_failed']} failed; this run {done} trials in {time.monotonic() - t0:.1f} s", file=log)
        return summary


def main(argv=None):
    p = argparse.ArgumentParser(prog="python3 -m rescuesim.dask_batch",
                                description="Run a rescuesim batch on a Dask cluster (see docs/batch.md).")
    p.add_argument("scenario", nargs="?", default=None, help="scenario YAML file (default: built-in)")
    p.add_argument("--scheduler", required=True, help="Dask scheduler address, e.g. tcp://HOST:8786")
    p.add_argument("--trials", "-n", type=int, required=True, help="number of trials in the batch")
    p.add_argument("--seed", type=int, default=None, help="base seed S: trial i uses S+i (default: the scenario's)")
    p.add_argument("--out", "-o", default=None, help="batch folder (default batches/<scenario name>)")
    p.add_argument("--shard", default="", help="run only trials i with i %% M == K, given as K/M")
    p.add_argument("--duration", type=float, default=None, help="time limit per trial (s of sim time)")
    p.add_argument("--controller", default="", choices=["", "explorer", "wall_follower"], help="controller of every robot")
    p.add_argument("--cameras", action="store_true", help="render the cameras (workers need OpenGL)")
    p.add_argument("--full-duration", action="store_true", help="run every trial to its time limit")
    p.add_argument("--retry-failed", action="store_true", help="run the trials recorded as failed again")
    a = p.parse_args(argv)
    if a.trials < 1:
        p.error("--trials must be at least 1")
    try:
        from distributed import Client
    except ImportError:
        print("rescuesim.dask_batch: needs Dask's distributed package (Debian: python3-distributed)", file=sys.stderr)
        return 2
    try:
        scenario = _rescuesim.load_scenario(a.scenario)
        out = a.out or f"batches/{scenario.name}"
        options = trial_options(a.duration, a.controller, a.cameras, not a.full_duration)
        with Client(a.scheduler) as client:
            summary = run(client, scenario, out, a.trials, seed=a.seed, shard=a.shard, options=options,
                          retry_failed=a.retry_failed)
    except _rescuesim.Error as e:
        print(f"rescuesim.dask_batch: error: {e}", file=sys.stderr)
        return 2
    except KeyboardInterrupt:
        return 1
    return 1 if summary["trials_failed"] else 0


if __name__ == "__main__":
    sys.exit(main())
