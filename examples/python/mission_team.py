#!/usr/bin/env python3
"""A scripted robot in a rescue team: it drives one robot of worlds/team.yaml while its
teammates keep their built-in explorers, reports the victims it finds to the referee through
the radio, and tells the base what it is doing.

    PYTHONPATH=build/python python3 examples/python/mission_team.py --max-time 60

The policy is a few lines of reactive driving on the laser; the mission calls are what to
copy: env.report(x, y) with a victim's position in the map frame, env.send(to, bytes),
env.inbox(), env.comms_status(), env.drop_relay() and env.mission_score() (docs/missions.md).
"""

import argparse
import math
import os

import numpy as np

import rescuesim

HERE = os.path.dirname(os.path.abspath(__file__))


def main():
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--scenario", default=os.path.join(HERE, "..", "..", "worlds", "team.yaml"))
    p.add_argument("--robot", default="r1", help="the robot this script drives")
    p.add_argument("--max-time", type=float, default=60.0, help="s of sim time")
    p.add_argument("--seed", type=int, default=11)
    a = p.parse_args()

    env = rescuesim.Env(rescuesim.load_scenario(a.scenario), robot=a.robot, max_time=a.max_time)
    obs, info = env.reset(seed=a.seed)
    start = info["pose"]  # the start pose is known to the team (map frame = world frame)
    status = env.comms_status()
    print(f"{a.robot}: in contact {status['in_contact']}, neighbours {[n[0] for n in status['neighbours']]}")
    step = 0
    while True:
        # reactive driving: forward, turning away from the nearer side when something is close
        ranges = np.nan_to_num(obs["laser"], posinf=30.0, neginf=0.0)
        n = len(ranges)
        ahead, left, right = ranges[n // 3: 2 * n // 3].min(), ranges[2 * n // 3:].min(), ranges[: n // 3].min()
        action = (0.5, 0.0) if ahead > 0.8 else (0.0, 1.0 if left > right else -1.0)
        obs, reward, terminated, truncated, info = env.step(action)
        step += 1
        # a victim this robot found during the step: report it where odometry says the robot is,
        # placed at the start pose (the victim sensor's range is small against the 1.5 m radius)
        for name in info["new_victims"]:
            x, y, yaw = obs["odometry"][:3]
            c, s = math.cos(start[2]), math.sin(start[2])
            answer = env.report(start[0] + c * x - s * y, start[1] + s * x + c * y)
            print(f"t={info['sim_time']:.1f} s: saw {name}, report {answer['outcome']} ({answer['message']})")
            env.send("base", f"{a.robot} saw a victim near {x:.1f} {y:.1f}".encode())
        if step % 100 == 0:
            status = env.comms_status()
            print(f"t={info['sim_time']:.0f} s: in contact {status['in_contact']}, hops {status['hops_to_base']}, "
                  f"inbox {len(env.inbox())}")
            if not status["in_contact"] and status["relays_left"] > 0:
                print("  out of contact: drop a relay", env.drop_relay())
        if terminated or truncated:
            break
    score = env.mission_score()
    print(f"team score {score['score']:g}: {score['victims_found']}/{score['victims']} victims reported, "
          f"{score['false_reports']} false, after {info['sim_time']:.0f} s")


if __name__ == "__main__":
    main()
