"""How much Python adds to a step: the same steps of the default scenario (laser-only
observation, no cameras) timed through ``Env.step`` from Python and looped inside C++,
interleaved in short chunks so that other load on the machine affects both alike.
Prints one JSON object; ``rescuesim bench`` runs this and reports it beside its other figures.

    python3 -m rescuesim.bench_step [--steps N] [--repeats R]
"""

import argparse
import json
import time

from .env import Env
from .scenarios import default_scenario


def measure(observations, steps, repeats, chunk=5, seed=7, action=(0.3, 0.2)):
    """Two environments with the same seed take the same steps, one through Python and one
    looped in C++, alternating every ``chunk`` steps so that both see the same load on the
    machine; the sums of their times give the overhead."""
    py_total = cpp_total = 0.0
    for _ in range(repeats):
        py_env = Env(default_scenario(), observations=observations, max_time=1e6)
        cpp_env = Env(default_scenario(), observations=observations, max_time=1e6)
        py_env.reset(seed=seed)
        cpp_env.reset(seed=seed)
        for _ in range(steps // chunk):
            # Python: the whole public step (action unpacking, observation dict, info dict)
            t0 = time.perf_counter()
            for _ in range(chunk):
                py_env.step(action)
            py_total += time.perf_counter() - t0
            # C++: the same steps from the same state, without leaving C++
            cpp_total += cpp_env._core.native_steps(chunk, *action)
    n = repeats * (steps // chunk) * chunk
    return {
        "observations": list(py_env.observation_fields),
        "steps": n,
        "control_period_s": 0.1,
        "python_steps_per_s": n / py_total,
        "cpp_steps_per_s": n / cpp_total,
        "python_step_us": 1e6 * py_total / n,
        "cpp_step_us": 1e6 * cpp_total / n,
        "python_added_us_per_step": 1e6 * (py_total - cpp_total) / n,
        "overhead": py_total / cpp_total - 1.0,
    }


def main(argv=None):
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--steps", type=int, default=400, help="steps per repeat (0.1 s of sim time each)")
    p.add_argument("--repeats", type=int, default=2, help="repeats, each from a fresh start; times are summed")
    a = p.parse_args(argv)
    report = {
        "laser_only": measure(["laser"], a.steps, a.repeats),
        "all_observations": measure(None, a.steps, a.repeats),
        "target_overhead": 0.10,
    }
    report["meets_target"] = report["laser_only"]["overhead"] <= report["target_overhead"]
    print(json.dumps(report, indent=2))


if __name__ == "__main__":
    main()
