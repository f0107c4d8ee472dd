"""Environments with the Gymnasium reset/step shape.

:class:`Env` is one simulation; :class:`VectorEnv` steps K of them together. Observations are
read-only numpy views of buffers the simulation writes into: no copy is made on the way to
Python, and each step overwrites them in place (``copy_observations=True`` returns copies
instead). The task and its reward are described in docs/python.md.
"""

import numpy as np

from . import _rescuesim
from .scenarios import default_scenario


def _as_scenario(scenario):
    if scenario is None:
        return default_scenario()
    if isinstance(scenario, _rescuesim.Scenario):
        return scenario
    return _rescuesim.load_scenario(str(scenario))


def _options(cameras, control_period, max_time, robot, fixed_world, controller, victim_reward,
             collision_penalty, time_penalty, observations):
    o = _rescuesim.EnvOptions()
    o.cameras = bool(cameras)
    o.control_period = float(control_period)
    o.max_time = None if max_time is None else float(max_time)
    o.robot = robot or ""
    o.fixed_world = bool(fixed_world)
    o.controller = controller or ""
    o.victim_reward = float(victim_reward)
    o.collision_penalty = float(collision_penalty)
    o.time_penalty = float(time_penalty)
    o.observations = list(observations or [])
    return o


def _action(action):
    """(linear m/s, angular rad/s) from a pair, a numpy array or a dict."""
    if isinstance(action, dict):
        return float(action["linear"]), float(action["angular"])
    linear, angular = action
    return float(linear), float(angular)


class Env:
    """One rescue simulation as an environment.

    Args:
        scenario: a :class:`rescuesim.Scenario`, a path to scenario YAML, or None for the
            built-in default.
        cameras: render the colour, depth and thermal cameras (needs OpenGL; slower).
        control_period: seconds of sim time per :meth:`step`.
        max_time: seconds of sim time per episode (default: the scenario's duration).
        robot: name of the robot the actions drive (default: the first).
        fixed_world: when True, ``reset(seed)`` reseeds only the noise; the maze stays the
            scenario's.
        controller: "" (the actions drive), or "explorer" / "wall_follower" to let that
            built-in controller drive (the actions are then ignored: for evaluation).
        victim_reward, collision_penalty, time_penalty: the task's reward terms.
        observations: the keys to observe (default: all of them; see observation_fields).
        copy_observations: return copies instead of views.

    ``reset(seed=None)`` starts an episode; without a seed it uses the previous seed + 1 (the
    first: the scenario's seed). ``step(action)`` takes (linear m/s, angular rad/s) and
    returns ``(observations, reward, terminated, truncated, info)``.
    """

    metadata = {"render_modes": []}

    def __init__(self, scenario=None, *, cameras=False, control_period=0.1, max_time=None, robot="",
                 fixed_world=False, controller="", victim_reward=10.0, collision_penalty=1.0,
                 time_penalty=0.01, observations=None, copy_observations=False):
        self.scenario = _as_scenario(scenario)
        self._core = _rescuesim.EnvCore(self.scenario, _options(
            cameras, control_period, max_time, robot, fixed_world, controller, victim_reward,
            collision_penalty, time_penalty, observations))
        self._views = self._core.observation_arrays()
        self._copy = bool(copy_observations)
        self._seed = None
        #: {key: (dtype, shape)} of the observations
        self.observation_fields = {k: (np.dtype(d), tuple(s)) for k, d, s in self._core.fields()}
        #: lowest and highest (linear m/s, angular rad/s) the drive accepts; larger ones are clamped
        self.action_low = np.array([-self._core.max_linear, -self._core.max_angular])
        self.action_high = np.array([self._core.max_linear, self._core.max_angular])

    @property
    def observations(self):
        """The live observation views (overwritten in place by every reset and step)."""
        return self._views

    def _observations(self):
        if self._copy:
            return {k: v.copy() for k, v in self._views.items()}
        return dict(self._views)

    def reset(self, *, seed=None, options=None):
        """Starts an episode with run seed ``seed``. -> (observations, info)

        With the previous episode's seed the simulation is restored to the snapshot taken when it
        was built (exact, and much faster than building it again); another seed builds it anew."""
        del options  # accepted for Gymnasium compatibility
        if seed is None:
            seed = self.scenario.seed if self._seed is None else self._seed + 1
        self._seed = int(seed)
        self._core.reset(self._seed)
        return self._observations(), self._core.info()

    @property
    def builds(self):
        """How many times the simulation was built; a reset with the same seed restores instead."""
        return self._core.builds

    def step(self, action):
        """Drives for one control period. -> (observations, reward, terminated, truncated, info)"""
        linear, angular = _action(action)
        reward, terminated, truncated = self._core.step(linear, angular)
        return self._observations(), reward, terminated, truncated, self._core.info()

    # -- missions (a scenario with a ``mission:`` block; docs/missions.md) --------------------

    def report(self, x, y, z=0.0, image=None):
        """Reports a victim at (x, y, z) m in the map frame (the world frame) to the referee,
        with an optional picture: a uint8 array H x W (grey), H x W x 3 (RGB) or H x W x 4
        (RGBA), at most 4096 pixels a side, written to reports/ with the run's outputs.

        -> dict(id, outcome, victim, distance, score_change, score, reports_left, message);
        outcome is accepted, duplicate, false, repeat, out_of_contact, limit_reached,
        rate_limited, time_over or invalid; the message says whether the picture was kept.
        rescuesim.Error without a mission, or for an array that is no picture."""
        return self._core.report(float(x), float(y), float(z), image)

    def send(self, to, data):
        """Queues a datagram (bytes) to a robot's or base's name, or "*" for every neighbour;
        delivered at the next link update if a radio route exists. -> (accepted, reason)"""
        return self._core.send(str(to), bytes(data))

    def inbox(self):
        """Takes the datagrams delivered to this robot: [dict(from, data, hops, sent, delivered)]."""
        return self._core.inbox()

    def comms_status(self):
        """This robot's radio at the last link update: dict(in_contact, hops_to_base,
        neighbours [(id, rssi_dbm, margin_db)], bytes_sent, bytes_received, bytes_dropped, relays_left)."""
        return self._core.comms_status()

    def drop_relay(self):
        """Drops a relay where the robot stands. -> (ok, relay id or the reason it could not)"""
        return self._core.drop_relay()

    def mission_score(self):
        """The referee's score so far (dict), or None when the scenario has no mission."""
        return self._core.mission_score()

    # -- simulation control (the operations ROS 2's Simulation Interfaces offer; docs/python.md) --

    def entities(self, filter="", categories=()):
        """Names of the entities: robots, victims, rubble, walls and obstacles. ``filter`` is a
        POSIX extended regular expression on the name; ``categories`` picks simulation_interfaces
        EntityCategory values (1 robot, 2 human: victims, 4 dynamic: rubble, 5 static)."""
        return self._core.entities(str(filter), list(categories))

    def entity_state(self, name):
        """dict(position, orientation (x, y, z, w), linear, angular, linear_acceleration,
        angular_acceleration, time) of an entity in the world frame."""
        return self._core.entity_state(str(name))

    def set_entity_state(self, name, position=None, orientation=None, linear=None, angular=None):
        """Teleports a robot or a piece of rubble: what is given replaces its pose (position
        (x, y, z), orientation (x, y, z, w), a unit quaternion) and twist (linear, angular, world
        frame); what is not given stays. A robot moves rigidly, every link with it; its wheel
        odometry does not notice (a kidnapped robot), its ground truth jumps. rescuesim.Error
        for an unknown name, a victim or wall, a non-finite pose or a quaternion that is not a
        unit one."""
        self._core.set_entity_state(str(name), position, orientation, linear, angular)

    def state_hash(self):
        """A 64-bit hash of the whole simulation state (equal hashes: identical states)."""
        return self._core.state_hash()

    def simulator_features(self):
        """dict(features, spawn_formats, custom_info) as GetSimulatorFeatures answers it."""
        return self._core.simulator_features()

    def spawn(self, name, uri="", resource_string="", position=(0.0, 0.0, 0.0), orientation=(0.0, 0.0, 0.0, 1.0),
              namespace="", allow_renaming=False):
        """Adds a robot or a loose body to the running simulation, as SpawnEntity does, and
        returns its name. ``uri``: a built-in robot ("rescue_robot", "tracked_robot"), a built-in
        body ("box", "brick", "cylinder", "sphere"), or a URDF, SDF or rescuesim YAML robot file
        (a path, file://, package:// or model://); or else ``resource_string``: URDF or SDF text,
        or a scenario's robot entry in YAML. The pose is in the world (orientation x, y, z, w); a
        robot's topics are under ``namespace`` (default: its name). rescuesim.Error, with the
        standard's result code, for a name in use, a file not found or not readable, a bad pose
        (docs/ros.md, "Spawning")."""
        return self._core.spawn(str(name), str(uri), str(resource_string), tuple(float(v) for v in position),
                                tuple(float(v) for v in orientation), str(namespace), bool(allow_renaming))

    def delete(self, name):
        """Removes a spawned robot or body (rescuesim.Error for the scenario's own: a reset brings
        those back)."""
        self._core.delete(str(name))

    def close(self):
        """Frees the simulation (the observation views stay valid but stop changing)."""
        self._core = None

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.close()
        return False


class VectorEnv:
    """K independent simulations stepped together (each its own World and State).

    Observations are dicts of [K, ...] arrays: read-only views of one contiguous block per
    key that the K simulations write their rows of. ``step(actions)`` takes a (K, 2) array
    and returns ``(observations, rewards, terminated, truncated, infos)`` with arrays of size
    K. An environment whose episode ended is reset by the following step (Gymnasium's
    "next step" autoreset; ``infos["_reset"]`` marks it), with its previous seed + K.
    ``threads`` > 1 steps the simulations in parallel; results do not depend on it.
    Other keyword arguments are those of :class:`Env`.
    """

    def __init__(self, scenario=None, num_envs=2, *, threads=1, copy_observations=False, **env_kwargs):
        self.scenario = _as_scenario(scenario)
        names = ("cameras", "control_period", "max_time", "robot", "fixed_world", "controller",
                 "victim_reward", "collision_penalty", "time_penalty", "observations")
        unknown = set(env_kwargs) - set(names)
        if unknown:
            raise TypeError(f"VectorEnv: unknown arguments {sorted(unknown)}")
        defaults = dict(cameras=False, control_period=0.1, max_time=None, robot="", fixed_world=False,
                        controller="", victim_reward=10.0, collision_penalty=1.0, time_penalty=0.01,
                        observations=None)
        defaults.update(env_kwargs)
        self._core = _rescuesim.VecEnvCore(self.scenario, _options(**defaults), int(num_envs), int(threads))
        self.num_envs = self._core.size
        self._views = self._core.observation_arrays()
        self._copy = bool(copy_observations)
        self.observation_fields = {k: (np.dtype(d), tuple(s)) for k, d, s in self._core.fields()}
        self._seeds = None

    def _observations(self):
        if self._copy:
            return {k: v.copy() for k, v in self._views.items()}
        return dict(self._views)

    def _infos(self, was_reset=None):
        infos = [self._core.info(i) for i in range(self.num_envs)]
        out = {k: np.array([i[k] for i in infos]) for k in
               ("seed", "sim_time", "steps", "victims_found", "victims_total", "collisions", "distance", "coverage")}
        out["pose"] = np.array([i["pose"] for i in infos])
        out["new_victims"] = [i["new_victims"] for i in infos]
        out["trouble"] = [i["trouble"] for i in infos]
        out["_reset"] = np.zeros(self.num_envs, dtype=bool) if was_reset is None else was_reset
        return out

    def reset(self, *, seed=None, options=None):
        """Resets every environment: env i gets seed + i. -> (observations, infos)"""
        del options
        if seed is None:
            seed = self.scenario.seed if self._seeds is None else self._seeds[-1] + 1
        self._seeds = [int(seed) + i for i in range(self.num_envs)]
        self._core.reset(self._seeds)
        return self._observations(), self._infos()

    def step(self, actions):
        """One step of every environment. -> (observations, rewards, terminated, truncated, infos)"""
        actions = np.asarray(actions, dtype=np.float64).reshape(self.num_envs, 2)
        rewards, terminated, truncated, was_reset = self._core.step(actions)
        return self._observations(), rewards, terminated, truncated, self._infos(was_reset)

    def close(self):
        self._core = None


_registered = False


def register_with_gymnasium():
    """Registers ``rescuesim/Rescue-v0`` with Gymnasium when it is installed (else does nothing).

    ``gymnasium.make("rescuesim/Rescue-v0", scenario=..., **Env arguments)`` then gives a
    :class:`GymEnv` with observation and action spaces.
    """
    global _registered
    try:
        import gymnasium
    except ImportError:
        return False
    if not _registered:
        gymnasium.register(id="rescuesim/Rescue-v0", entry_point="rescuesim.env:GymEnv")
        _registered = True
    return True


def _gym_env_class():
    import gymnasium
    from gymnasium import spaces

    class GymEnv(gymnasium.Env):
        """:class:`Env` as a ``gymnasium.Env``, with spaces; observations are copies (RL
        libraries keep them in replay buffers)."""

        metadata = {"render_modes": []}

        def __init__(self, scenario=None, **kwargs):
            kwargs.setdefault("copy_observations", True)
            self.env = Env(scenario, **kwargs)
            fields = {}
            for key, (dtype, shape) in self.env.observation_fields.items():
                if dtype == np.uint8:
                    fields[key] = spaces.Box(0, 255, shape, dtype)
                elif dtype == np.uint16:
                    fields[key] = spaces.Box(0, 65535, shape, dtype)
                else:
                    fields[key] = spaces.Box(-np.inf, np.inf, shape, dtype)
            self.observation_space = spaces.Dict(fields)
            self.action_space = spaces.Box(self.env.action_low.astype(np.float32),
                                           self.env.action_high.astype(np.float32), dtype=np.float32)

        def reset(self, *, seed=None, options=None):
            super().reset(seed=seed)
            return self.env.reset(seed=seed, options=options)

        def step(self, action):
            return self.env.step(action)

        def close(self):
            self.env.close()

    return GymEnv


def __getattr__(name):
    # GymEnv exists only when Gymnasium can be imported
    if name == "GymEnv":
        cls = _gym_env_class()
        globals()["GymEnv"] = cls
        return cls
    raise AttributeError(name)
