"""Team talk within the rules: a pass in one say of at most 10 characters, and who goes for the ball
judged from what a player sees."""

from __future__ import annotations

import re

import pytest

from cf_decision.talk import NOT_ME, Listener, heard_pass, pass_word, seen_claims
from cf_decision.without_ball import NEVER, choose_interceptor
from cf_lang.ontology import AbsolutePositioning, Ball, Heard, Player, Team, Velocity, WorldState
from cf_lang.ontology import actions as act

RCSS_SAY = re.compile(r"[A-Za-z0-9 ().+*/?<>_-]{1,10}")  # what rcssserver 19 carries in a say


def to_point(x, y, power=None):
    return act.Pass(target=AbsolutePositioning(x=x, y=y), power=power)


def to_mate(n, power=None):
    return act.Pass(to=Player(player_number=n, which_team=Team.OUR), power=power)


@pytest.mark.parametrize(
    "action",
    [
        to_mate(7),
        to_mate(11),
        to_mate(10, power=100.0),
        to_point(12.5, -9.0),
        to_point(-52.5, 34.0),
        to_point(52.5, -34.0, power=100.0),
        to_point(0.0, 0.0, power=40.0),
    ],
)
def test_a_pass_goes_in_one_say_and_comes_back_the_same(action):
    word = pass_word(action)
    assert RCSS_SAY.fullmatch(word), word
    back = heard_pass(word)
    assert back is not None and back.power == action.power
    if action.to is not None:
        assert back.to.player_number == action.to.player_number and back.to.which_team is Team.OUR
    else:
        assert back.target.x == pytest.approx(action.target.x, abs=0.05)
        assert back.target.y == pytest.approx(action.target.y, abs=0.05)


def test_the_word_is_readable_text():
    assert pass_word(to_mate(7)) == "p7"
    assert pass_word(to_point(12.5, -9.0)) == "t0725310"
    assert pass_word(to_point(12.5, -9.0, power=100.0)) == "t0725310/a"


@pytest.mark.parametrize(
    "word", ["", "p", "p0", "p12", "px", "t123", "t07253101", "tabcdefg", "p7/", "p7/b", "hello", "/a"]
)
def test_other_words_are_no_pass(word):
    assert heard_pass(word) is None


def test_who_goes_for_the_ball_is_judged_from_where_team_mates_are_seen():
    def mate(n, x, y, top=None):
        return Player(player_number=n, which_team=Team.OUR, positioning=AbsolutePositioning(x=x, y=y), top_speed=top)

    state = WorldState(
        time=10,
        me=mate(7, 0.0, 0.0),
        ball=Ball(positioning=AbsolutePositioning(x=10.0, y=0.0), velocity=Velocity(vx=0.0, vy=0.0)),
        players=(
            mate(4, 9.0, 0.0),  # a metre from the ball
            mate(9, 30.0, 0.0),
            Player(which_team=Team.OUR, positioning=AbsolutePositioning(x=10.5, y=0.0)),  # no number: not judged
            Player(player_number=2, which_team=Team.OPP, positioning=AbsolutePositioning(x=10.2, y=0.0)),
        ),
    )
    claims = seen_claims(state, 7)
    assert set(claims) == {4, 9}
    assert claims[4] < claims[9]
    assert not choose_interceptor(7, 10, claims)  # mate 4 is nearer: he goes, I do not
    assert seen_claims(state.model_copy(update={"ball": None}), 7) == {}


def test_a_team_mate_who_said_the_ball_is_not_his_is_never_the_one_to_go():
    """Our set piece's taker may not touch the ball again until another player has: he says NOT_ME."""
    near = Player(player_number=4, which_team=Team.OUR, positioning=AbsolutePositioning(x=9.0, y=0.0))
    state = WorldState(
        time=10,
        me=Player(player_number=7, which_team=Team.OUR, positioning=AbsolutePositioning(x=0.0, y=0.0)),
        ball=Ball(positioning=AbsolutePositioning(x=10.0, y=0.0)),
        players=(near,),
    )
    assert not choose_interceptor(7, 10, seen_claims(state, 7))
    claims = seen_claims(state, 7, frozenset({4}))
    assert claims[4] == NEVER and choose_interceptor(7, 10, claims)
    assert heard_pass(NOT_ME) is None


def test_a_say_is_read_once_though_the_perception_tells_it_two_cycles_and_not_me_lapses():
    """On rcssserver a say stays in the perception for the cycle it came and the next."""
    listener = Listener()

    def state(t, *heard):
        return WorldState(time=t, heard=tuple(Heard(player_number=n, message=m, time=h) for n, m, h in heard))

    first = listener.hear(state(20, (4, "p7", 20), (6, NOT_ME, 20)))
    assert [(n, a.to.player_number, t) for n, a, t in first] == [(4, 7, 20)]
    assert listener.hear(state(21, (4, "p7", 20), (6, NOT_ME, 20))) == []  # told again: not new
    assert listener.not_theirs(22) == {6} and listener.not_theirs(23) == frozenset()
