"""A small real component: registers a service class and answers requests.

Used by the system tests and `make demo` to show registration, relaunch and
withdrawal with a real process. It answers every fipa-request with
``(done <n>)`` and every fipa-query with ``(Game :time <n>)``, n counting up.

    demo_component --name blue_1_kick --service-class Kick [--team blue]
                   [--player 1] [--lease 0.5] [--commag /commag]
                   [--relaunch-fails]  # its launch command exits at once
                   [--exit-now]        # exit with code 3 before doing anything
                   [--relaunch-slow S] # its launch command waits S seconds before starting
"""

from __future__ import annotations

import argparse
import os
import sys
import time

import rclpy

from .agent import Agent
from .runtime import init, spin


def main(argv: list[str] | None = None) -> int:
    args_in = rclpy.utilities.remove_ros_args(sys.argv if argv is None else argv)
    parser = argparse.ArgumentParser(prog="demo_component")
    parser.add_argument("--name", required=True)
    parser.add_argument("--service-class", default="Action")
    parser.add_argument("--team", default="")
    parser.add_argument("--player", type=int, default=0)
    parser.add_argument("--lease", type=float, default=1.0)
    parser.add_argument("--commag", default="/commag")
    parser.add_argument("--relaunch-fails", action="store_true")
    parser.add_argument("--exit-now", action="store_true")
    parser.add_argument("--relaunch-slow", type=float, default=0.0)
    parser.add_argument("--start-delay", type=float, default=0.0)
    args = parser.parse_args(args_in[1:])
    if args.exit_now:
        print(f"{args.name}: exiting at once, as asked (--exit-now)", flush=True)
        return 3
    if args.start_delay:
        print(f"{args.name}: starting in {args.start_delay} s, as asked (--start-delay)", flush=True)
        time.sleep(args.start_delay)

    # Relaunch with the same arguments, from this very executable.
    launch = [os.path.realpath(sys.argv[0]), *args_in[1:]]
    if args.relaunch_fails:
        launch = [a for a in launch if a != "--relaunch-fails"] + ["--exit-now"]
    if args.relaunch_slow:
        launch += ["--start-delay", str(args.relaunch_slow)]

    init(args=argv)
    node = rclpy.create_node(args.name)
    count = {"n": 0}

    def on_request(message, responder):
        count["n"] += 1
        return f"(done {count['n']})"

    def on_query(message, responder):
        count["n"] += 1
        return f"(Game :time {count['n']})"

    agent = Agent(
        node,
        name=args.name,
        service_class=args.service_class,
        launch_command=launch,
        team=args.team,
        player_number=args.player,
        lease=args.lease,
        commag=args.commag,
    )
    agent.serve("fipa-request", on_request)
    agent.serve("fipa-query", on_query)
    node.get_logger().info(f"{args.name} up (pid {os.getpid()}), serving {args.service_class}")
    spin(node, [agent])
    return 0


if __name__ == "__main__":
    sys.exit(main())
