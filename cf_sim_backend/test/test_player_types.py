"""Heterogeneous player types (ROS-free): rcssserver 19's own, drawn from the seed, and used by the
embedded simulator's physics, perception, skills and game log."""

from __future__ import annotations

import math
import random
from dataclasses import replace
from pathlib import Path

import pytest
from test_rcg import lines_of, players
from test_report import play_logged_match

from cf_lang.sexp import Symbol
from cf_sim_backend.embedded.rcg import export, player_type
from cf_sim_backend.embedded.sim import Simulator
from cf_sim_backend.perception import observe
from cf_sim_backend.player_types import ORDER, SPEED_MIN, hetero_types
from cf_sim_backend.world import Params, Side, world_from_snapshot

SAMPLE = Path(__file__).parent / "data" / "rcssserver-19.rcg"
SAMPLE_SEED = 1795394183  # the sample's (player_param (random_seed ...))
QUIET = Params(ball_rand=0.0, player_rand=0.0, kick_rand=0.0, auto_kick_off_cycles=1)


def test_the_types_are_rcssservers_own_for_the_same_seed():
    """rcssserver 19 wrote the sample's 18 player_type lines: ours for its seed are the same text
    (up to the observation lengths, which every type shares)."""
    real = [
        line.split("(unum_far_length")[0] for line in SAMPLE.read_text().splitlines() if line.startswith("(player_type")
    ]
    ours = [player_type(type_id, params).removesuffix(")") for type_id, params in enumerate(hetero_types(SAMPLE_SEED))]
    assert len(real) == 18
    assert ours == real
    assert hetero_types(SAMPLE_SEED + 1)[1] != hetero_types(SAMPLE_SEED)[1]


def test_every_type_is_between_rcssservers_bounds_and_a_bad_count_is_refused():
    types = hetero_types(7)
    assert types[0] == Params()
    assert all(SPEED_MIN - 1e-9 <= t.top_speed <= t.player_speed_max + 1e-9 for t in types)
    assert len({t.player_decay for t in types}) == 18
    for count in (0, 101):
        with pytest.raises(ValueError, match="player types"):
            hetero_types(7, count)


def test_each_side_gets_the_types_by_our_coachs_rule_and_they_travel_in_the_snapshot():
    sim = Simulator(QUIET, seed=41, player_types=18)
    w = sim.world
    speeds = {t: p.top_speed for t, p in enumerate(w.types)}
    for side in Side:
        got = {n: w.player(side, n).ptype for n in range(1, 12)}
        assert got[1] == 0  # the goalkeeper keeps the default type
        assert len(set(got.values())) == 11  # each type once
        field = sorted((speeds[t] for n, t in got.items() if n != 1), reverse=True)
        assert speeds[got[ORDER[0]]] == field[0]  # the centre forward is the fastest
    again = world_from_snapshot(sim.snapshot(), QUIET)
    assert again.types == w.types
    assert {p.key: p.ptype for p in again.players.values()} == {p.key: p.ptype for p in w.players.values()}
    assert Simulator(QUIET, seed=41).snapshot().get("types") is None  # one type: nothing to tell


def test_a_player_runs_kicks_and_is_told_the_speed_of_his_type():
    sim = Simulator(QUIET, team_sizes=(2, 0), seed=41, player_types=18)
    w = sim.world
    w.mode = "play_on"
    slow, fast = sorted((w.player(Side.LEFT, n) for n in (1, 2)), key=lambda p: w.params_of(p).top_speed)
    for p, y in ((slow, -2.0), (fast, 2.0)):
        p.x, p.y, p.body = 0.0, y, 0.0
    for _ in range(30):
        for p in (slow, fast):
            sim.command(Side.LEFT, p.number, "dash", 100)
        sim.step()
    for p in (slow, fast):  # at full pace after 30 dashes: his type's top speed
        assert math.hypot(p.vx, p.vy) / w.params_of(p).player_decay == pytest.approx(w.params_of(p).top_speed, rel=1e-3)
    assert fast.x > slow.x
    slow.body = math.degrees(math.atan2(fast.y - slow.y, fast.x - slow.x))  # he looks at his team-mate
    state = observe(w, Side.LEFT, slow.number, random.Random(0), noise=0.0)
    assert state.me.top_speed == pytest.approx(w.params_of(slow).top_speed * 10, abs=1e-3)
    assert state.players[0].top_speed == pytest.approx(w.params_of(fast).top_speed * 10, abs=1e-3)
    # The skills read the acting player's type as the world's parameters.
    assert w.as_player(fast).params == w.params_of(fast) and w.as_player(fast).players is w.players
    # His kickable margin is his type's: a ball just beyond the default reach is in his.
    wide = replace(QUIET, kickable_margin=0.8)
    w.types = (QUIET, wide)
    fast.ptype, w.ball.x, w.ball.y = 1, fast.x + 1.15, fast.y
    sim.command(Side.LEFT, fast.number, "kick", 100, 0)
    sim.step()
    assert fast.kicks == 1 and w.ball.vx > 0


def test_the_game_log_tells_every_type_and_each_players(tmp_path: Path):
    play_logged_match(tmp_path / "match.jsonl", types=18)
    _, lines = lines_of(export(tmp_path / "match.jsonl", tmp_path / "match.rcg"))
    param = next(line for line in lines if line[0] == Symbol("player_param"))
    assert [Symbol("player_types"), 18] in param and [Symbol("random_seed"), 4] in param
    assert sum(line[0] == Symbol("player_type") for line in lines) == 18
    show = next(line for line in lines if line[0] == Symbol("show"))
    kinds = {(p[0][0].name, p[0][1]): p[1] for p in players(show)}
    assert kinds[("l", 1)] == 0 and len({t for (side, _), t in kinds.items() if side == "l"}) == 3


@pytest.mark.parametrize("types", [["a", 18], [1], [1, 10**9], [1, 0], 5])
def test_a_snapshot_with_malformed_types_is_refused_with_a_clear_error(types):
    snap = Simulator(QUIET, team_sizes=(1, 1), seed=3, player_types=18).snapshot()
    snap["types"] = types
    with pytest.raises((ValueError, TypeError)):
        world_from_snapshot(snap)


def test_a_player_of_a_type_nobody_drew_plays_as_the_default_type():
    sim = Simulator(QUIET, team_sizes=(1, 1), seed=3, player_types=18)
    snap = sim.snapshot()
    snap["players"][0][-1] = -1
    snap["players"][1][-1] = 99
    w = world_from_snapshot(snap)
    assert all(w.params_of(p) is w.params for p in w.players.values())
