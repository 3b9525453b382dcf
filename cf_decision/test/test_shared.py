"""What team-mates see, shared: what a player tells, and how a told position enters a picture."""

from __future__ import annotations

from test_policy import mate, state

from cf_decision.policy import decide
from cf_decision.shared import HEARD_AGE, WORD_ETA, Heard, merged, to_tell, told_to
from cf_lang import parse_expr
from cf_lang.expr import to_sexp
from cf_lang.ontology import AbsolutePositioning, Player, PlayMode, Team, WorldState
from cf_lang.sexp import dumps


def seen(n, x, y, sigma, age=0, team=Team.OPP):
    pos = AbsolutePositioning(x=x, y=y, sigma_x=sigma, sigma_y=sigma)
    return Player(player_number=n, which_team=team, positioning=pos, age=age)


def word(number, me, players=(), time=100):
    """What team-mate ``number`` tells: where he is, the opponents he saw."""
    pos = AbsolutePositioning(x=me[0], y=me[1], sigma_x=0.2, sigma_y=0.2)
    return WorldState(time=time, me=Player(player_number=number, which_team=Team.OUR, positioning=pos), players=players)


def where(st, team, n):
    return next((p.positioning.x, p.positioning.y) for p in st.players if p.which_team is team and p.player_number == n)


def test_a_player_tells_where_he_is_and_the_opponents_he_saw_this_cycle_surely_in_the_language():
    st = state(
        (0.0, 0.0),
        (1.0, 0.0),
        [seen(5, 10.0, 0.0, 0.5), seen(6, 30.0, 0.0, 2.5), seen(7, 5.0, 5.0, 0.3, age=3), seen(None, 4.0, 4.0, 0.3)],
    )
    told = to_tell(st)
    assert told.me.player_number == 7 and told.me.which_team is Team.OUR
    assert [p.player_number for p in told.players] == [5]  # not too unsure, not unseen lately, not unnamed
    assert parse_expr(dumps(to_sexp(told))) == told  # an inform's content any agent can read
    assert to_tell(state((0.0, 0.0)).model_copy(update={"me": None})) is None


def test_a_told_position_replaces_mine_only_where_it_is_surer():
    mine = state((0.0, 0.0), (1.0, 0.0), [seen(5, 10.0, 0.0, 3.0, age=6), seen(6, 12.0, 4.0, 0.3)])
    heard = [word(9, (20.0, 0.0), (seen(5, 11.5, -2.0, 0.4), seen(6, 14.0, 4.0, 1.0)))]
    now, taken = merged(mine, heard)
    assert where(now, Team.OPP, 5) == (11.5, -2.0)  # his 0.4 m against my 3 m: where he saw him
    assert where(now, Team.OPP, 6) == (12.0, 4.0)  # my 0.3 m stands
    assert where(now, Team.OUR, 9) == (20.0, 0.0)  # a team-mate I had not seen: added where he is
    assert taken == 2
    five = next(p for p in now.players if p.player_number == 5)
    assert five.age == 0 and five.positioning.sigma_x == 0.4


def test_a_told_position_grows_unsure_with_its_age_and_goes_stale():
    mine = state((0.0, 0.0), (1.0, 0.0), [seen(5, 10.0, 0.0, 1.0)])
    one_late = merged(mine, [word(9, (20.0, 0.0), (seen(5, 11.0, 0.0, 0.5),), time=99)])[0]
    assert where(one_late, Team.OPP, 5) == (11.0, 0.0)  # 0.5 + 0.4 m, still surer than 1 m
    two_late = merged(mine, [word(9, (20.0, 0.0), (seen(5, 11.0, 0.0, 0.5),), time=98)])[0]
    assert where(two_late, Team.OPP, 5) == (10.0, 0.0)  # 0.5 + 0.8 m: mine stands
    stale = word(9, (20.0, 0.0), time=100 - HEARD_AGE - 1)
    future = word(9, (20.0, 0.0), time=101)
    assert merged(mine, [stale, future]) == (mine, 0)


def test_my_own_place_is_never_replaced_and_an_unnamed_man_near_a_told_one_is_him():
    mine = state((0.0, 0.0), (1.0, 0.0), [seen(None, 15.5, 0.5, 1.5)])
    told = word(7, (5.0, 5.0), (seen(3, 15.0, 0.0, 0.3),))  # (a word claiming to be me: passed over)
    now, taken = merged(mine, [told, word(9, (20.0, 0.0), (seen(3, 15.0, 0.0, 0.3),))])
    assert now.me == mine.me
    assert [(p.player_number, p.which_team) for p in now.players if p.which_team is not Team.OUR] == [(3, Team.OPP)]
    assert taken == 2  # man 3 from the first word, mate 9 from the second (its man 3 no surer)


def test_an_opponent_a_team_mate_sees_in_the_lane_stops_the_pass_i_would_have_played():
    """Blue 7 believes the lane to mate 9 open (the man there seen long ago, 12 m off); mate 9 sees him in it."""
    ball = (0.5, 0.0)
    mine = state((0.0, 0.0), ball, [mate(9, 20.0, 5.0), mate(4, -30.0, 0.0), seen(5, 10.0, -12.0, 6.0, age=15)])
    first = decide(mine, 7, 11, {})
    assert first.method == "pass" and "team-mate 9" in first.why
    heard = [word(9, (20.0, 5.0), (seen(5, 10.0, 2.5, 0.5),))]
    now, _ = merged(mine, heard)
    second = decide(now, 7, 11, {})
    assert "team-mate 9" not in second.why, second


def test_a_word_goes_to_the_team_mates_who_may_play_the_ball_next():
    assert told_to({4: 0, 3: WORD_ETA, 9: WORD_ETA + 1, 2: 40}) == {3, 4}


def test_a_word_heard_more_perceptions_ago_than_heard_age_goes_stale_even_while_the_clock_stops():
    heard = Heard()
    heard.perceived()
    heard.keep(9, word(9, (20.0, 0.0), time=500))  # a set piece: game time 500 for a while
    heard.keep(4, word(4, (-20.0, 0.0), time=500))
    assert len(heard.recent()) == 2
    for _ in range(HEARD_AGE):
        heard.perceived()
    heard.keep(4, word(4, (-21.0, 0.0), time=500))  # mate 4 still tells, mate 9 no more
    assert [w.me.player_number for w in heard.recent()] == [9, 4]
    heard.perceived()
    assert [w.me.player_number for w in heard.recent()] == [4]


def test_at_our_set_piece_only_team_mates_own_places_are_taken():
    mine = state((0.0, 0.0), (1.0, 0.0), [seen(5, 10.0, 0.0, 3.0, age=6)], mode=PlayMode.FREE_KICK_OUR)
    now, taken = merged(mine, [word(9, (20.0, 0.0), (seen(5, 11.5, -2.0, 0.4),))])
    assert where(now, Team.OPP, 5) == (10.0, 0.0) and where(now, Team.OUR, 9) == (20.0, 0.0) and taken == 1
