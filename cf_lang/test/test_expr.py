"""Expressions: the paper's examples, ontology validation and error paths."""

from __future__ import annotations

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from cf_lang import Exec, ExpressionError, Val, parse_expr, unparse
from cf_lang.ontology import AbsolutePositioning, Ball, Player, PlayMode, Team, Velocity, WorldState
from cf_lang.ontology.actions import Kick, TurnToObject

PAPER_INSTANCE = "(AbsolutePositioning :x 10.3 :y -23.67 :yaw 0.23456)"
PAPER_VAL = "(val Player positioning :playerNumber 5 :whichTeam opp)"
PAPER_VAL_GAME = "(val Game time)"
PAPER_EXEC = "(exec Player turnToObject :playerNum 3\n:whichTeam our\n:obj (Player :playerNum 4 :whichTeam our))"


def test_paper_instance():
    assert parse_expr(PAPER_INSTANCE) == AbsolutePositioning(x=10.3, y=-23.67, yaw=0.23456)


def test_paper_val():
    assert parse_expr(PAPER_VAL) == Val("Player", "positioning", {"playerNumber": 5, "whichTeam": Team.OPP})
    assert parse_expr(PAPER_VAL_GAME) == Val("Game", "time", {})


def test_val_of_a_whole_instance():
    assert parse_expr("(val WorldState)") == Val("WorldState", "", {})
    assert parse_expr("(val Player :playerNum 4 :whichTeam our)") == Val(
        "Player", "", {"playerNumber": 4, "whichTeam": Team.OUR}
    )
    assert unparse(parse_expr("(val WorldState)")) == "(val WorldState)"


def test_paper_exec_and_both_player_key_spellings():
    expr = parse_expr(PAPER_EXEC)
    assert isinstance(expr, Exec)
    assert expr.key == {"playerNumber": 3, "whichTeam": Team.OUR}
    assert expr.action == TurnToObject(obj=Player(player_number=4, which_team=Team.OUR))
    # The canonical spelling is written back.
    assert ":playerNumber 3" in unparse(expr)
    assert parse_expr(unparse(expr)) == expr


@pytest.mark.parametrize(
    ("text", "path", "words"),
    [
        ("(Foo :x 1)", "", "unknown class Foo"),
        ("(AbsolutePositioning :x 100 :y 0)", "AbsolutePositioning.x", "less than or equal to 70"),
        ("(AbsolutePositioning :x 1 :y 0 :z 3)", "AbsolutePositioning.z", "Extra inputs"),
        ("(AbsolutePositioning :x 1 :x 2 :y 3)", "AbsolutePositioning.x", "given twice"),
        ("(AbsolutePositioning :x 1 :y)", "AbsolutePositioning", "odd number"),
        ("(AbsolutePositioning x 1 :y 2)", "AbsolutePositioning", "expected a :keyword"),
        ("(val Player positioning :playerNumber 12 :whichTeam our)", "Player.positioning.playerNumber", "11"),
        ("(val Player positioning :playerNumber 5)", "Player.positioning", "missing key :whichTeam"),
        ("(val Player speed :playerNumber 5 :whichTeam our)", "Player.speed", "no attribute speed"),
        ("(val Game time :half 1)", "Game.time.half", "not part of the key"),
        ("(exec Player fly :playerNumber 1 :whichTeam our)", "Player.fly", "no method fly"),
        ("(exec Player kick :playerNumber 1 :whichTeam our :power 200 :direction 0)", "Player.kick.power", "100"),
        ("(exec Player kick :playerNumber 1 :whichTeam their :power 20 :direction 0)", "Player.kick.whichTeam", "our"),
        ("(exec Player pass :playerNumber 1 :whichTeam our)", "Player.pass", "exactly one of"),
        ("(WorldState :time 3 :ball (Ball :velocity (Velocity :vx a :vy 0)))", "WorldState.ball.velocity.vx", "number"),
        ("(Player :playerNumber 4 :whichTeam our :topSpeed 0)", "Player.topSpeed", "greater than 0"),
        ("hello", "", "expected (Class ...)"),
    ],
)
def test_problems_have_paths(text, path, words):
    with pytest.raises(ExpressionError) as info:
        parse_expr(text)
    assert any(p == path and words in msg for p, msg in info.value.problems), info.value.problems


def test_every_problem_is_reported():
    with pytest.raises(ExpressionError) as info:
        parse_expr("(AbsolutePositioning :x 100 :y -100 :yaw 99)")
    assert {p for p, _ in info.value.problems} == {
        "AbsolutePositioning.x",
        "AbsolutePositioning.y",
        "AbsolutePositioning.yaw",
    }


def test_world_state_round_trip():
    state = WorldState(
        time=12,
        ball=Ball(positioning=AbsolutePositioning(x=1, y=2, sigma_x=0.1, sigma_y=0.1), velocity=Velocity(vx=1, vy=0)),
        players=(
            Player(player_number=1, which_team=Team.OUR, is_goalie=True),
            Player(player_number=9, which_team=Team.OPP, stamina=0.5),
            Player(player_number=7, which_team=Team.OUR, top_speed=9.42),
        ),
    )
    text = unparse(state)
    assert "(sequence (Player" in text and ":isGoalie true" in text and ":topSpeed 9.42" in text
    assert parse_expr(text) == state


coords = st.floats(min_value=-34.0, max_value=34.0, allow_nan=False)


@settings(max_examples=200)
@given(coords, coords, st.floats(min_value=-3.14, max_value=3.14), st.integers(1, 11), st.sampled_from(Team))
def test_generated_exec_round_trip(x, y, yaw, number, team):
    for action in (Kick(power=abs(x), direction=yaw),):
        expr = Exec("Player", "kick", {"playerNumber": number, "whichTeam": team}, action)
        assert parse_expr(unparse(expr)) == expr
    pos = AbsolutePositioning(x=x, y=y, yaw=yaw)
    assert parse_expr(unparse(pos)) == pos


def test_enums_and_game():
    game = parse_expr("(Game :time 30 :playMode kick_off_our :scoreOur 1 :scoreOpp 0)")
    assert game.play_mode is PlayMode.KICK_OFF_OUR
