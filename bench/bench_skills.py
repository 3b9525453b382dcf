"""Benchmark: two ball skills on the embedded simulator (rcssserver's physics, with its noise), side by side.

1. Getting a rolling ball: cycles until it is within the kickable distance, for random balls
   rolling past a player, with the skills' intercept (a dash at any angle off the body or a turn
   first, whichever meets the ball sooner: ``intercept.py``) against turn-then-run (turn to face
   the first point of the path full forward dashes reach, then run at it: the skills' way before).
2. A pass from where the ball lies: its speed off the foot for random balls in the kickable area,
   kicked at once against with the first touches the pass skill plans (``kick_plan.py``).

    python bench/bench_skills.py [--balls 300] [--seed 1]

Prints medians and shares; the results go in docs/performance.md.
"""

from __future__ import annotations

import argparse
import math
import random
import statistics
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "cf_sim_backend" / "test"))

from test_sim_core import sim_with

from cf_lang import parse_expr
from cf_sim_backend import skills
from cf_sim_backend.embedded.sim import Simulator
from cf_sim_backend.world import Params, Side, direction_deg, distance, norm_deg

NOISY = Params(auto_kick_off_cycles=1)  # rcssserver's noise on the ball, the players and the kicks
LIMIT = 80  # cycles a chase may take


def _noisy(seed: int, *players) -> Simulator:
    sim = sim_with(*players, params=NOISY)
    sim.rng = random.Random(seed)
    return sim


def turn_then_run(world, me) -> tuple:
    """The reference: the first path point full forward dashes reach (after a turn when it is
    more than 12 degrees off the body); turn to it, else dash straight ahead."""
    prm, b = world.params, world.ball
    reach = skills.INTERCEPT_REACH * prm.kickable_distance
    runs = skills.run_distances(world, me, skills.INTERCEPT_HORIZON)
    x, y, vx, vy = b.x, b.y, b.vx, b.vy
    for n in range(1, skills.INTERCEPT_HORIZON + 1):
        x, y, vx, vy = x + vx, y + vy, vx * prm.ball_decay, vy * prm.ball_decay
        way = distance(me.x, me.y, x, y) - reach
        off = abs(norm_deg(direction_deg(me.x, me.y, x, y) - me.body))
        turns = 0 if off <= skills.AIM_TOLERANCE else 1
        if way <= 0.0 or way <= runs[n - turns]:
            break
    if distance(me.x, me.y, x, y) <= 0.5:
        return ()
    off = norm_deg(direction_deg(me.x, me.y, x, y) - me.body)
    if abs(off) > skills.AIM_TOLERANCE:
        return ("turn", off * (1.0 + prm.inertia_moment * math.hypot(me.vx, me.vy)))
    return ("dash", 100.0)


def chase(seed: int, ours: bool) -> int:
    """Cycles until a random ball rolling by is within the player's kickable distance."""
    rng = random.Random(seed)
    sim = _noisy(seed, (Side.LEFT, 6, 0.0, 0.0, rng.uniform(-180.0, 180.0)))
    me, b = sim.world.player(Side.LEFT, 6), sim.world.ball
    me.vx, me.vy = rng.uniform(-0.3, 0.3), rng.uniform(-0.3, 0.3)
    # A ball 5-20 m off, rolling at 1-2.5 m/cycle towards a point within 6 m of him.
    d, a = rng.uniform(5.0, 20.0), rng.uniform(-math.pi, math.pi)
    b.x, b.y = d * math.cos(a), d * math.sin(a)
    tx, ty = rng.uniform(-6.0, 6.0), rng.uniform(-6.0, 6.0)
    speed, way = rng.uniform(1.0, 2.5), math.atan2(ty - b.y, tx - b.x)
    b.vx, b.vy = speed * math.cos(way), speed * math.sin(way)
    skill = skills.skill_for("intercept", parse_expr("(Intercept)"), Side.LEFT, sim.world, me) if ours else None
    world = sim.world
    for n in range(LIMIT):
        if distance(me.x, me.y, b.x, b.y) <= world.params.kickable_distance:
            return n
        commands = skill.step(world, me).commands if ours else [c for c in [turn_then_run(world, me)] if c]
        for cmd in commands:
            sim.command(Side.LEFT, 6, *cmd)
        sim.step()
    return LIMIT


def pass_speed(seed: int, touches: bool) -> float:
    """The speed (m/cycle) a 20 m pass leaves at from a random ball in the kickable area."""
    rng = random.Random(seed)
    sim = _noisy(seed, (Side.LEFT, 4, 0.0, 0.0, rng.uniform(-180.0, 180.0)), (Side.LEFT, 8, 20.0, 0.0, 0.0))
    b = sim.world.ball
    d, a = rng.uniform(0.45, 1.0), rng.uniform(-math.pi, math.pi)
    b.x, b.y = d * math.cos(a), d * math.sin(a)
    b.vx, b.vy = rng.uniform(-0.5, 0.5), rng.uniform(-0.5, 0.5)
    me = sim.world.player(Side.LEFT, 4)
    action = parse_expr("(Pass :to (Player :playerNumber 8 :whichTeam our))")
    skill = skills.skill_for("pass", action, Side.LEFT, sim.world, me)
    if not touches:
        skill.touches = skills.FIRST_TOUCHES
    fastest = 0.0
    for _ in range(6):
        step = skill.step(sim.world, me)
        for cmd in step.commands:
            sim.command(Side.LEFT, 4, *cmd)
        sim.step()
        fastest = max(fastest, math.hypot(b.vx, b.vy) / sim.world.params.ball_decay)
        if step.status != "running":
            break
    return fastest


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--balls", type=int, default=300)
    ap.add_argument("--seed", type=int, default=1)
    args = ap.parse_args()
    seeds = range(args.seed, args.seed + args.balls)
    mine = [chase(s, True) for s in seeds]
    ref = [chase(s, False) for s in seeds]
    sooner = sum(a < b for a, b in zip(mine, ref, strict=True))
    later = sum(a > b for a, b in zip(mine, ref, strict=True))
    print(f"{args.balls} rolling balls, cycles to have one in reach (median; mean; not within {LIMIT}):")
    print(
        f"  intercept (any angle or a turn): {statistics.median(mine):.0f}; {statistics.mean(mine):.1f}; {mine.count(LIMIT)}"
    )
    print(
        f"  turn then run (reference):       {statistics.median(ref):.0f}; {statistics.mean(ref):.1f}; {ref.count(LIMIT)}"
    )
    print(f"  sooner for {sooner}, later for {later}, same for {args.balls - sooner - later}")
    planned = [pass_speed(s, True) for s in seeds]
    once = [pass_speed(s, False) for s in seeds]
    print(f"{args.balls} balls in the kickable area, a 20 m pass's speed off the foot (m/cycle, median; share >= 2.4):")
    print(
        f"  first touches planned: {statistics.median(planned):.2f}; {sum(v >= 2.4 for v in planned) / len(planned):.0%}"
    )
    print(f"  kicked at once:        {statistics.median(once):.2f}; {sum(v >= 2.4 for v in once) / len(once):.0%}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
