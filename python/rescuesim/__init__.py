"""rescuesim: a simulator for mobile rescue robots, from Python.

    import rescuesim
    env = rescuesim.Env(rescuesim.maze_scenario(cols=4, rows=4, victims=2))
    obs, info = env.reset(seed=1)
    obs, reward, terminated, truncated, info = env.step([0.3, 0.0])

Environments have the Gymnasium ``reset``/``step`` shape (and are registered with Gymnasium
as ``rescuesim/Rescue-v0`` when it is installed); several run side by side in one process,
each with its own simulation. Batches of seeded trials run with :func:`run_batch` here, with
``rescuesim batch`` on the command line, or on a Dask cluster with
``python3 -m rescuesim.dask_batch``. See docs/python.md and docs/batch.md.
"""

from ._rescuesim import (  # noqa: F401
    Error,
    Scenario,
    TrialOptions,
    ResultsFile,
    __version__,
    load_scenario,
    parse_scenario,
    default_scenario_text,
    set_ray_threads,
)
from .scenarios import default_scenario, maze_scenario  # noqa: F401
from .env import Env, VectorEnv, register_with_gymnasium  # noqa: F401
from .batch import (  # noqa: F401
    trial_options,
    fingerprint,
    run_trial,
    run_batch,
    load_results,
    merge,
)

register_with_gymnasium()

__all__ = [
    "Error",
    "Scenario",
    "TrialOptions",
    "ResultsFile",
    "load_scenario",
    "parse_scenario",
    "default_scenario",
    "maze_scenario",
    "Env",
    "VectorEnv",
    "trial_options",
    "fingerprint",
    "run_trial",
    "run_batch",
    "load_results",
    "merge",
]
