"""Shared by the Python tests: where things are, and a tiny scenario."""

import os
import shutil
import subprocess
import tempfile

EXE = os.environ.get("RESCUESIM_EXE", "rescuesim")
SOURCE_DIR = os.environ.get("RESCUESIM_SOURCE_DIR", os.path.join(os.path.dirname(__file__), "..", ".."))

# a 3 x 3 maze with two victims: an episode or a trial takes a fraction of a second
TINY_YAML = """name: tiny
seed: 11
duration: 5
world:
  maze: {cols: 3, rows: 3, cell_size: 1.5, loop_fraction: 0.2, rubble: 1, raised_fraction: 0, victims: 2, start_cell: [0, 0]}
"""

# a 5 x 5 maze for environments: victims out of sight of the start, so episodes last
ENV_YAML = """name: small
seed: 11
duration: 30
world:
  maze: {cols: 5, rows: 5, cell_size: 1.5, loop_fraction: 0.2, rubble: 2, raised_fraction: 0, victims: 2, start_cell: [0, 0]}
"""


def temp_dir(name):
    """A fresh folder for one test, under the build tree when ctest runs us."""
    root = os.environ.get("RESCUESIM_TEST_TMP") or tempfile.gettempdir()
    path = os.path.join(root, f"{name}-{os.getpid()}")
    shutil.rmtree(path, ignore_errors=True)
    os.makedirs(path)
    return path


def write_tiny(folder, text=TINY_YAML):
    path = os.path.join(folder, "tiny.yaml")
    with open(path, "w") as f:
        f.write(text)
    return path


def cli(*args, check=True):
    """Runs the rescuesim executable; returns the CompletedProcess."""
    r = subprocess.run([EXE, *args], capture_output=True, text=True)
    if check and r.returncode != 0:
        raise AssertionError(f"rescuesim {' '.join(args)} exited {r.returncode}:\n{r.stdout}\n{r.stderr}")
    return r
