#!/usr/bin/env python3
"""Compare the built-in controllers over a batch of seeded mazes, in parallel, from Python.

    PYTHONPATH=build/python python3 examples/python/batch_eval.py --trials 20 --jobs 2

Each controller's trials go into their own batch folder (results.jsonl + summaries, the same
format as `rescuesim batch`, so rerunning resumes and `rescuesim batch merge` works). Trials run
in worker processes through rescuesim.run_trial; the parent appends each record as it arrives.
"""

import argparse
import os
import time
from concurrent.futures import ProcessPoolExecutor, as_completed

import rescuesim
from rescuesim import _rescuesim
from rescuesim.batch import Batch


def one_trial(text, file, trial, seed, options, fingerprint):
    """Runs in a worker process: one trial, its results.jsonl line back."""
    scenario = rescuesim.parse_scenario(text, file)
    opts = rescuesim.trial_options(**options)
    return _rescuesim.run_trial(scenario, trial, seed, opts, fingerprint)


def evaluate(scenario, controller, trials, jobs, out, duration):
    options = dict(duration=duration, controller=controller)
    with Batch(scenario, out, trials, options=rescuesim.trial_options(**options)) as b:
        t0 = time.monotonic()
        with ProcessPoolExecutor(jobs) as pool:
            futures = [pool.submit(one_trial, b.scenario.text, b.scenario.file, t, b.seed_of(t), options, b.fingerprint)
                       for t in b.todo]
            for f in as_completed(futures):
                b.record(f.result())
        return b.finish(jobs, len(b.todo), time.monotonic() - t0)


def main():
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--scenario", help="scenario YAML (default: a 4 x 4 maze with three victims)")
    p.add_argument("--trials", type=int, default=10)
    p.add_argument("--jobs", type=int, default=os.cpu_count() or 1)
    p.add_argument("--duration", type=float, default=60.0, help="time limit per trial (s of sim time)")
    p.add_argument("--out", default="batches/eval")
    a = p.parse_args()
    scenario = rescuesim.load_scenario(a.scenario) if a.scenario else rescuesim.maze_scenario(4, 4, victims=3, rubble=4)
    print(f"{'controller':<14} {'success':>8} {'victims':>8} {'coverage':>9} {'collisions':>10} {'trials/h':>9}")
    for controller in ("explorer", "wall_follower"):
        s = evaluate(scenario, controller, a.trials, a.jobs, os.path.join(a.out, controller), a.duration)
        rate = s.get("run", {}).get("trials_per_hour", 0)
        print(f"{controller:<14} {100 * s['success_rate']:>7.0f}% {100 * s['victim_find_rate']:>7.0f}% "
              f"{100 * s['coverage']['mean']:>8.0f}% {s['collisions']['mean']:>10.1f} {rate:>9.0f}")
    print(f"details: {a.out}/<controller>/summary.json, summary.csv, summary.png")


if __name__ == "__main__":
    main()
