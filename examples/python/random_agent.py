#!/usr/bin/env python3
"""A random agent in a rescue maze: the Gymnasium-shaped loop with rescuesim.Env.

    PYTHONPATH=build/python python3 examples/python/random_agent.py --episodes 3
    PYTHONPATH=build/python python3 examples/python/random_agent.py --envs 4   # vectorised

Each step drives the robot with a random (linear m/s, angular rad/s) for 0.1 s of sim time and
prints, per episode, the return, the victims found and the collisions. Replace the random
action with your policy: observations are numpy arrays (laser ranges, IMU, odometry, sonars).
"""

import argparse

import numpy as np

import rescuesim


def main():
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--scenario", help="scenario YAML (default: a 5 x 5 maze with two victims)")
    p.add_argument("--episodes", type=int, default=2)
    p.add_argument("--max-time", type=float, default=20.0, help="s of sim time per episode")
    p.add_argument("--seed", type=int, default=1)
    p.add_argument("--envs", type=int, default=1, help="> 1: step that many environments together")
    a = p.parse_args()
    scenario = a.scenario or rescuesim.maze_scenario(cols=5, rows=5, victims=2, rubble=2)
    rng = np.random.default_rng(a.seed)

    if a.envs > 1:
        env = rescuesim.VectorEnv(scenario, a.envs, max_time=a.max_time)
        obs, infos = env.reset(seed=a.seed)
        returns = np.zeros(a.envs)
        finished = 0
        while finished < a.episodes:
            actions = rng.uniform(-1, 1, size=(a.envs, 2)) * [0.6, 1.5]
            obs, rewards, terminated, truncated, infos = env.step(actions)
            returns += rewards
            for i in np.flatnonzero(terminated | truncated):
                print(f"env {i} seed {infos['seed'][i]}: return {returns[i]:+.2f}, victims {infos['victims_found'][i]}/"
                      f"{infos['victims_total'][i]}, collisions {infos['collisions'][i]}, laser min {np.nanmin(obs['laser'][i]):.2f} m")
                returns[i] = 0
                finished += 1
        return

    env = rescuesim.Env(scenario, max_time=a.max_time)
    print("observations:", {k: f"{d}{list(s)}" for k, (d, s) in env.observation_fields.items()})
    for episode in range(a.episodes):
        obs, info = env.reset(seed=a.seed + episode)
        total = 0.0
        while True:
            action = rng.uniform(env.action_low, env.action_high) * [0.6, 0.75]
            obs, reward, terminated, truncated, info = env.step(action)
            total += reward
            if terminated or truncated:
                break
        print(f"episode {episode} (seed {info['seed']}): return {total:+.2f} after {info['sim_time']:.1f} s, "
              f"victims {info['victims_found']}/{info['victims_total']}, collisions {info['collisions']}, "
              f"coverage {100 * info['coverage']:.0f}%")


if __name__ == "__main__":
    main()
