"""Meeting a rolling ball (intercept.py), played out on the embedded simulator without noise."""

from __future__ import annotations

import math

import pytest
from test_sim_core import QUIET, sim_with

from cf_sim_backend.intercept import Runner, cycles_to, meeting
from cf_sim_backend.skills import _turn_moment
from cf_sim_backend.world import Side, distance


def play(sim, me, limit=60):
    """Follow the meeting's first command every cycle until the ball is in reach: the cycles it took."""
    w = sim.world
    for n in range(limit):
        if distance(me.x, me.y, w.ball.x, w.ball.y) <= w.params.kickable_distance:
            return n
        met = meeting(
            w.params, Runner(me.x, me.y, me.vx, me.vy, me.body), (w.ball.x, w.ball.y, w.ball.vx, w.ball.vy), 0.87, 50
        )
        if met is not None and met.command:
            cmd = met.command
            sim.command(Side.LEFT, 6, *(("turn", _turn_moment(w, me, cmd[1])) if cmd[0] == "turn" else cmd))
        sim.step()
    return limit


def test_a_ball_rolling_by_to_the_side_is_met_by_dashing_sideways_at_once():
    sim = sim_with((Side.LEFT, 6, 0.0, 0.0, 0.0))
    b, me = sim.world.ball, sim.world.player(Side.LEFT, 6)
    b.x, b.y, b.vx, b.vy = -8.0, 1.8, 2.5, 0.0  # it will pass 1.8 m to his left, his body facing along it
    met = meeting(QUIET, Runner(0.0, 0.0, 0.0, 0.0, 0.0), (b.x, b.y, b.vx, b.vy), 0.87, 50)
    assert met.command[0] == "dash" and 60.0 <= met.command[2] <= 150.0  # to his left (and back to meet it sooner)
    assert play(sim, me) <= met.cycles + 1


def test_a_ball_far_behind_is_met_after_turns_even_when_he_is_running_too_fast_to_turn_at_once():
    r = Runner(0.0, 0.0, 0.0, 0.6, -95.0)  # running at 0.6 m/cycle: one turn reaches 45 degrees
    n, cmd = cycles_to(QUIET, r, 8.0, 15.0, 0.87, 40)
    assert cmd[0] == "turn"  # not 20-odd cycles of dashing at 150 degrees off the body
    back = cycles_to(QUIET, r, 8.0, 15.0, 0.87, 60)
    assert back[0] == n
    sim = sim_with((Side.LEFT, 6, 0.0, 0.0, -95.0))
    me, b = sim.world.player(Side.LEFT, 6), sim.world.ball
    me.vy = 0.6
    b.x, b.y = 8.0, 15.0
    assert play(sim, me) <= n + 2


@pytest.mark.parametrize(
    "ball", [(10.0, -10.0, 0.0, 2.0), (10.0, -10.0, -1.5, 1.0), (-6.0, 4.0, 1.2, -1.0), (3.0, 0.5, 0.0, 0.0)]
)
def test_the_planned_cycles_are_the_cycles_it_takes(ball):
    sim = sim_with((Side.LEFT, 6, 0.0, 0.0, 30.0))
    b, me = sim.world.ball, sim.world.player(Side.LEFT, 6)
    b.x, b.y, b.vx, b.vy = ball
    met = meeting(QUIET, Runner(0.0, 0.0, 0.0, 0.0, 30.0), ball, 0.87, 50)
    assert met is not None
    # Reach is planned at 0.87 m, the ball is in reach at 1.085: it may come a cycle sooner.
    assert met.cycles - 1 <= play(sim, me) <= met.cycles
    assert math.isfinite(met.x)
