"""Batches of seeded trials from Python, in the same results.jsonl format as ``rescuesim batch``.

Trial i of a batch with base seed S runs the scenario with seed S + i. Every trial's record is
one JSON line (docs/batch.md lists the keys); a batch folder can be resumed, merged and
summarised whichever way its trials ran: the CLI, :func:`run_batch`, or Dask
(rescuesim.dask_batch).
"""

import json
import sys
import time

from . import _rescuesim
from .env import _as_scenario


def trial_options(duration=None, controller="", cameras=False, stop_when_all_found=True):
    """How every trial of a batch runs beyond its scenario (as the CLI's --duration,
    --controller, --cameras and --full-duration)."""
    o = _rescuesim.TrialOptions()
    o.duration = None if duration is None else float(duration)
    o.controller = controller or ""
    o.cameras = bool(cameras)
    o.stop_when_all_found = bool(stop_when_all_found)
    return o


def fingerprint(scenario, options=None):
    """The batch's identity ("rs1-" + 16 hex digits), from the scenario text and the options."""
    return _rescuesim.batch_fingerprint(_as_scenario(scenario), options or trial_options())


def run_trial(scenario, trial, base_seed=None, options=None):
    """Runs trial ``trial`` in this process and returns its record as a dict."""
    scenario = _as_scenario(scenario)
    options = options or trial_options()
    base = scenario.seed if base_seed is None else int(base_seed)
    line = _rescuesim.run_trial(scenario, int(trial), _rescuesim.trial_seed(base, int(trial)), options,
                                _rescuesim.batch_fingerprint(scenario, options))
    return json.loads(line)


class Batch:
    """A batch folder open for a run: the plan (trials not yet recorded) and the results file,
    locked against other batches until :meth:`close`. Used by :func:`run_batch` and the Dask
    runner.
    """

    def __init__(self, scenario, out, trials, *, seed=None, shard="", options=None, retry_failed=False, log=sys.stderr):
        self.scenario = _as_scenario(scenario)
        self.options = options or trial_options()
        self.fingerprint = _rescuesim.batch_fingerprint(self.scenario, self.options)
        self.base_seed = self.scenario.seed if seed is None else int(seed)
        self.out = str(out)
        self.log = log
        self.results = _rescuesim.ResultsFile(self.out)
        try:
            lines, notices = self.results.load()
            for n in notices:
                print(f"{self.out}/{n}", file=log)
            self.results.check_same_batch(self.fingerprint, self.base_seed)
            if retry_failed:
                kept = {t: l for t, l in lines.items() if json.loads(l)["status"] == "ok"}
                if len(kept) != len(lines):
                    self.results.rewrite(list(kept.values()))
                lines = kept
        except Exception:
            self.results.close()
            raise
        self.mine = _rescuesim.shard_trials(int(trials), shard)
        #: trials of this shard with no record yet, in order
        self.todo = [t for t in self.mine if t not in lines]

    def seed_of(self, trial):
        return _rescuesim.trial_seed(self.base_seed, trial)

    def record(self, line):
        """Appends a trial's result line (validated; one write + fsync)."""
        self.results.append(line)

    def record_failure(self, trial, error):
        """Records a trial that produced no result (its worker died, say) as failed."""
        line = _rescuesim.failed_trial(self.scenario, trial, self.seed_of(trial), self.fingerprint, str(error))
        self.results.append(line)
        return line

    def finish(self, jobs=0, trials_run=0, wall_time=0.0):
        """Writes summary.json/.csv/.png and returns summary.json as a dict."""
        self.results.write_summary(jobs, trials_run, wall_time)
        with open(f"{self.out}/summary.json") as f:
            return json.load(f)

    def close(self):
        self.results.close()

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.close()
        return False


def describe(record, done, planned):
    """One progress line for a finished trial."""
    if record["status"] == "ok":
        return (f"[{done}/{planned}] trial {record['trial']} (seed {record['seed']}): "
                f"{record['victims_found']}/{record['victims_total']} victims, {100 * record['coverage']:.0f}% coverage, "
                f"{record['collisions']} collisions, {record['sim_time_s']:.1f} s in {record['wall_time_s']:.1f} s on {record['host']}")
    return f"[{done}/{planned}] trial {record['trial']} (seed {record['seed']}) FAILED: {record['error']}"


def run_batch(scenario, out, trials, *, seed=None, shard="", options=None, retry_failed=False, progress=True):
    """Runs a batch's missing trials one after another in this process (resumable like the CLI)
    and returns summary.json as a dict. For parallel runs use ``rescuesim batch --jobs`` or Dask.
    """
    with Batch(scenario, out, trials, seed=seed, shard=shard, options=options, retry_failed=retry_failed) as b:
        t0 = time.monotonic()
        for k, trial in enumerate(b.todo):
            line = _rescuesim.run_trial(b.scenario, trial, b.seed_of(trial), b.options, b.fingerprint)
            b.record(line)
            if progress:
                print(describe(json.loads(line), k + 1, len(b.todo)), file=sys.stderr)
        return b.finish(1, len(b.todo), time.monotonic() - t0)


def load_results(out):
    """The records of a batch folder as {trial: dict} (corrupt lines are left out)."""
    with _rescuesim.ResultsFile(str(out)) as r:
        lines, _ = r.load()
    return {t: json.loads(l) for t, l in lines.items()}


def merge(dirs, out):
    """Merges batch folders into ``out`` (as ``rescuesim batch merge``); returns the notices."""
    return _rescuesim.merge_results([str(d) for d in dirs], str(out))
