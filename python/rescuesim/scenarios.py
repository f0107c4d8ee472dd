"""Scenarios from Python: the built-in default, a file, or a generated maze."""

from . import _rescuesim


def default_scenario():
    """The built-in default scenario (worlds/default.yaml): an 8x8 maze with 4 victims."""
    return _rescuesim.load_scenario(None)


def _yaml_number(value):
    return repr(float(value))


def maze_scenario(cols=4, rows=4, *, cell_size=1.5, loop_fraction=0.15, rubble=0, raised_fraction=0.0,
                  victims=2, start_cell=(0, 0), seed=1, duration=60.0, name="maze", controller="explorer"):
    """A scenario whose world is a seeded random maze (see docs/worlds.md for each setting).

    ``seed`` is the run seed (maze and noise); ``duration`` the seconds of sim time a run or an
    episode lasts; ``controller`` the robot's built-in controller when the scenario runs as a
    batch trial (an Env drives the robot itself unless asked otherwise). Raises
    rescuesim.Error for impossible settings.
    """
    text = (
        f"name: {name}\n"
        f"seed: {int(seed)}\n"
        f"duration: {_yaml_number(duration)}\n"
        "world:\n"
        "  maze:\n"
        f"    cols: {int(cols)}\n"
        f"    rows: {int(rows)}\n"
        f"    cell_size: {_yaml_number(cell_size)}\n"
        f"    loop_fraction: {_yaml_number(loop_fraction)}\n"
        f"    rubble: {int(rubble)}\n"
        f"    raised_fraction: {_yaml_number(raised_fraction)}\n"
        f"    victims: {int(victims)}\n"
        f"    start_cell: [{int(start_cell[0])}, {int(start_cell[1])}]\n"
        "robots:\n"
        "  - name: robot\n"
        "    model: rescue_robot\n"
        f"    controller: {controller}\n"
    )
    return _rescuesim.parse_scenario(text, "<maze_scenario>")
