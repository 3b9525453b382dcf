"""A player's memory on the embedded simulator: what it saw lately is told on, as rcssserver's belief does."""

from __future__ import annotations

import math
import random

import pytest
from test_sim_core import sim_with

from cf_lang.ontology import Team
from cf_sim_backend.memory import BALL_MEMORY, PLAYER_MEMORY, PLAYER_SIGMA_GROWTH, Memory
from cf_sim_backend.perception import observe
from cf_sim_backend.world import Side


def look(sim, memory: Memory, number: int = 2):
    return memory.recall(observe(sim.world, Side.LEFT, number, random.Random(0), noise=0.0))


def opponents(state):
    return {p.player_number: p for p in state.players if p.which_team is Team.OPP}


def test_a_player_out_of_sight_is_told_where_last_seen_more_unsure_each_cycle_until_forgotten():
    sim = sim_with((Side.LEFT, 2, 0.0, 0.0, 0.0), (Side.RIGHT, 7, 10.0, 5.0, 0.0))
    w, me, memory = sim.world, sim.world.player(Side.LEFT, 2), Memory()
    seen = opponents(look(sim, memory))[7]
    assert seen.age == 0 and (seen.positioning.x, seen.positioning.y) == pytest.approx((10.0, 5.0), abs=0.05)
    me.body = 180.0  # he turns his back: no longer in view
    w.player(Side.RIGHT, 7).x = 20.0  # (and moves on, unseen)
    w.time += 3
    state = look(sim, memory)
    assert 7 not in opponents(observe(w, Side.LEFT, 2, random.Random(0), noise=0.0))
    told = opponents(state)[7]
    assert told.age == 3 and told.positioning.x == seen.positioning.x  # where he was seen
    assert told.positioning.sigma_x == pytest.approx(seen.positioning.sigma_x + 3 * PLAYER_SIGMA_GROWTH)
    # Seen from the player's body, now turned: behind him.
    assert told.relative.distance == pytest.approx(math.hypot(10.0, 5.0), abs=0.5)  # (from his own, noisy place)
    assert abs(told.relative.direction) > math.radians(150)
    w.time += PLAYER_MEMORY - 2
    assert 7 not in opponents(look(sim, memory))


def test_a_player_seen_running_is_told_running_on_out_of_sight_as_on_rcssserver():
    sim = sim_with((Side.LEFT, 2, 0.0, 0.0, 0.0), (Side.RIGHT, 7, 10.0, 5.0, 0.0))
    w, me, memory = sim.world, sim.world.player(Side.LEFT, 2), Memory()
    w.player(Side.RIGHT, 7).vx = 0.4  # after the cycle's decay (0.4): a 1 m step a cycle
    seen = opponents(look(sim, memory))[7]
    assert seen.velocity.vx == pytest.approx(4.0)  # m/s
    me.body = 180.0  # out of view
    w.time += 3
    told = opponents(look(sim, memory))[7]
    assert told.age == 3 and told.positioning.x == pytest.approx(10.0 + 1.0 + 0.9 + 0.81, abs=0.05)
    assert told.positioning.y == pytest.approx(5.0, abs=0.05)


def test_a_sighting_without_a_number_is_the_known_player_near_it_else_told_once():
    sim = sim_with((Side.LEFT, 2, 0.0, 0.0, 0.0), (Side.RIGHT, 7, 15.0, 0.0, 0.0), (Side.RIGHT, 8, 15.0, 30.0, 0.0))
    w, memory = sim.world, Memory()
    assert set(opponents(look(sim, memory))) == {7}  # 8 is out of view
    w.player(Side.RIGHT, 7).x = 20.5  # beyond 20 m his number is not read
    w.time += 4  # (5.5 m in 4 cycles: he may have run that far)
    raw = observe(w, Side.LEFT, 2, random.Random(0), noise=0.0)
    assert [p.player_number for p in raw.players] == [None]
    told = opponents(look(sim, memory))
    assert set(told) == {7} and told[7].age == 0 and told[7].positioning.x == pytest.approx(20.5, abs=0.05)
    # A man nobody knows near where he is seen: told this cycle, not remembered.
    w.player(Side.RIGHT, 8).x, w.player(Side.RIGHT, 8).y = 32.0, 10.0
    w.player(Side.RIGHT, 7).x = 35.0
    w.time += 1
    state = look(sim, memory)
    numbers = sorted((p.player_number or 0) for p in state.players)
    # 7 where last seen (a sighting 10 m on is too far from there to be him), and two men unknown.
    assert numbers == [0, 0, 7]
    w.time += 1
    w.player(Side.LEFT, 2).body = 180.0
    assert sorted((p.player_number or 0) for p in look(sim, memory).players) == [7]


def test_the_ball_out_of_sight_rolls_on_until_it_should_be_seen_or_the_referee_moves_it():
    sim = sim_with((Side.LEFT, 2, 0.0, 0.0, 0.0))
    w, me, memory = sim.world, sim.world.player(Side.LEFT, 2), Memory(sim.world.params)
    w.ball.x, w.ball.y, w.ball.vx, w.ball.vy = 10.0, 0.0, 1.0, 0.0
    assert look(sim, memory).ball.age == 0
    me.body = 180.0
    w.time += 2
    ball = look(sim, memory).ball
    assert ball.age == 2 and ball.positioning.x == pytest.approx(10.0 + 1.0 + 0.94, abs=0.05)
    assert ball.velocity.vx == pytest.approx(10 * 0.94**2)
    me.body = 0.0  # he looks where it should be, and it is not there (it was kicked away)
    w.ball.x, w.ball.y = -30.0, 20.0
    w.time += 1
    assert look(sim, memory).ball is None
    me.body = 180.0
    w.ball.x, w.ball.y = -10.0, 0.0
    w.time += 1
    assert look(sim, memory).ball.age == 0
    w.mode = "kick_in_r"  # the referee places it where the perception cannot tell: forgotten
    w.ball.x, w.ball.y = 30.0, 34.0
    w.time += 1
    assert look(sim, memory).ball is None
    w.mode = "kick_off_l"
    w.ball.x, w.ball.y = 0.0, 0.0
    w.time += 1
    me.x, me.body = -20.0, 180.0  # his back to the centre spot
    kick_off = look(sim, memory).ball
    assert (kick_off.positioning.x, kick_off.positioning.y) == (0.0, 0.0)  # the centre spot
    w.time += BALL_MEMORY + 1
    assert look(sim, memory).ball is None


def test_a_remembered_ball_that_rolls_beyond_any_position_the_language_has_is_forgotten():
    """It rolled out of the field unseen; telling it on would be a WorldState the ontology refuses."""
    sim = sim_with((Side.LEFT, 2, 0.0, 30.0, 90.0))
    w, me, memory = sim.world, sim.world.player(Side.LEFT, 2), Memory(sim.world.params)
    w.ball.x, w.ball.y, w.ball.vx, w.ball.vy = 0.0, 40.0, 0.0, 2.5
    assert look(sim, memory).ball.age == 0
    me.body = -90.0
    told = []
    for _ in range(10):
        w.time += 1
        ball = look(sim, memory).ball
        told.append(None if ball is None else ball.positioning.y)
    assert told[0] is not None and told[-1] is None and all(y is None or y <= 50.0 for y in told)
