"""The kick planner against the embedded simulator's kick (rcssserver's model), without noise."""

from __future__ import annotations

import math

import pytest
from test_sim_core import sim_with

from cf_sim_backend.embedded.physics import kick
from cf_sim_backend.kick_plan import Kicker, best_touch, rate_at, reach_along
from cf_sim_backend.world import Params, Side


def _power_and_direction(prm: Params, k: Kicker, ax: float, ay: float) -> tuple[float, float]:
    rate = rate_at(prm, k.body, k.bx - k.x, k.by - k.y)
    return math.hypot(ax, ay) / rate, math.degrees(math.atan2(ay, ax)) - k.body


@pytest.mark.parametrize(
    ("ball", "velocity", "body", "mine"),
    [
        ((0.1, 1.0), (0.0, 0.0), 0.0, (0.0, 0.0)),  # beside the body
        ((-0.6, -0.5), (0.3, 0.1), 30.0, (0.3, 0.0)),  # behind it, rolling after me
        ((0.8, 0.2), (-0.5, 0.0), -60.0, (0.0, 0.2)),  # at the edge, rolling in across
    ],
)
def test_the_two_touches_give_the_speed_the_plan_promised(ball, velocity, body, mine):
    sim = sim_with((Side.LEFT, 4, 0.0, 0.0, body))
    w, me = sim.world, sim.world.player(Side.LEFT, 4)
    me.vx, me.vy = mine
    w.ball.x, w.ball.y = ball
    w.ball.vx, w.ball.vy = velocity
    target = (25.0, 10.0)
    k = Kicker(me.x, me.y, me.vx, me.vy, me.body, w.ball.x, w.ball.y, w.ball.vx, w.ball.vy)
    touch = best_touch(w.params, k, target, 3.0)
    way = math.atan2(target[1] - k.by, target[0] - k.bx)
    one_kick = reach_along(
        w.params, math.cos(way), math.sin(way), k.bvx, k.bvy, min(100 * rate_at(w.params, body, *ball), 2.7)
    )
    assert touch is not None and touch.then > (one_kick or 0.0) + 0.3
    assert kick(w, me, *_power_and_direction(w.params, k, touch.ax, touch.ay))
    sim.step()
    way = math.atan2(target[1] - w.ball.y, target[0] - w.ball.x)
    vx, vy = w.ball.vx, w.ball.vy  # what the second kick adds to
    rate = rate_at(w.params, me.body, w.ball.x - me.x, w.ball.y - me.y)
    room = (vx * math.cos(way) + vy * math.sin(way)) ** 2 - vx * vx - vy * vy + min(100 * rate, 2.7) ** 2
    assert room >= 0.0
    assert min(3.0, vx * math.cos(way) + vy * math.sin(way) + math.sqrt(room)) == pytest.approx(touch.then, abs=1e-6)
    assert math.dist((me.x, me.y), (w.ball.x, w.ball.y)) <= w.params.kickable_distance - 0.2


def test_no_spot_near_an_opponent_is_used_and_a_crowd_leaves_none():
    prm = Params()
    k = Kicker(0.0, 0.0, 0.0, 0.0, 0.0, 0.1, 1.0, 0.0, 0.0)
    free = best_touch(prm, k, (20.0, 0.0), 2.7)
    marked = best_touch(prm, k, (20.0, 0.0), 2.7, [(0.0 + free.ax + 0.1, 1.0 + free.ay)], 1.0)
    assert marked is not None and (marked.ax, marked.ay) != (free.ax, free.ay)
    assert math.dist((0.1 + marked.ax, 1.0 + marked.ay), (0.1 + free.ax, 1.0 + free.ay)) > 0.0
    crowd = [(3.0 * math.cos(a), 3.0 * math.sin(a)) for a in (0.0, 2.1, 4.2)]
    assert best_touch(prm, k, (20.0, 0.0), 2.7, crowd, 3.0) is None
