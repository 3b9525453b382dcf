"""The naive team: every player runs at the ball and kicks it at the opponents' goal (ROS-free).

It is the opponent the evaluation plays against, and the load of the simulator benchmark.
"""

from __future__ import annotations

from cf_sim_backend.embedded.sim import Simulator
from cf_sim_backend.world import Side, direction_deg, distance, norm_deg


def chase_commands(sim: Simulator, side: Side) -> None:
    """Queue one cycle of commands for every player of ``side``."""
    w = sim.world
    b = w.ball
    goal_x = side.sign * w.params.field_length / 2
    kickable = w.params.kickable_distance
    for p in w.players.values():
        if p.side is not side:
            continue
        d = distance(p.x, p.y, b.x, b.y)
        if d <= kickable:
            aim = norm_deg(direction_deg(p.x, p.y, goal_x, 0.0) - p.body)
            sim.command(side, p.number, "kick", 100.0, aim)
            continue
        turn = norm_deg(direction_deg(p.x, p.y, b.x + b.vx, b.y + b.vy) - p.body)
        if abs(turn) > 15.0:
            sim.command(side, p.number, "turn", turn * 2)  # the moment damped by speed
        else:
            sim.command(side, p.number, "dash", 100.0)
