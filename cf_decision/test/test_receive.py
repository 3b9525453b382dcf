"""The receiver of an announced pass: who meets it, where, and for how long it is awaited."""

from __future__ import annotations

import math

from test_policy import at, mate, opp, state

from cf_decision import reach
from cf_decision.policy import decide
from cf_decision.receive import AWAIT_MAX, Announced, meeting, to_announce
from cf_decision.situation import Decision, offside_mates
from cf_decision.with_ball import best_pass
from cf_lang.ontology import Ball, Player, PlayMode, Team, Velocity
from cf_lang.ontology import actions as act


def to(n):
    return act.Pass(to=Player(player_number=n, which_team=Team.OUR))


def on_segment(p, a, b, slack=0.5):
    return math.dist(a, p) + math.dist(p, b) <= math.dist(a, b) + slack


def test_a_pass_to_me_is_met_on_its_way_before_the_ball_is_seen_rolling():
    ball, me = (-30.0, 0.0), (-20.0, -10.0)
    st = state(me, ball, [mate(4, -30.5, 0.0)], number=2)  # time 100; the ball still at the passer's feet
    passes = [Announced(4, to(2), ball, 101)]
    spot, cycles = meeting(st, 2, passes)
    assert on_segment(spot, ball, me) and math.dist(spot, me) > 1.0 and cycles > 0
    d = decide(st, 2, 11, {4: 0}, passes=passes)
    assert d.method == "moveTo" and d.action.speed == 100.0 and "meet the pass" in d.why
    assert math.dist((d.action.target.x, d.action.target.y), spot) < 0.01
    # Without the word from the passer, blue 2 leaves the ball to him and does not run to it.
    plain = decide(st, 2, 11, {4: 0})
    assert "meet" not in plain.why


def test_a_pass_into_space_is_met_by_the_team_mate_first_on_its_path_only():
    ball = (0.0, 0.0)
    into_space = act.Pass(target=at(20.0, 10.0))
    passes = [Announced(4, into_space, ball, 101)]
    near, far = (15.0, 12.0), (5.0, 25.0)
    st_near = state(near, ball, [mate(4, -0.5, 0.0), mate(9, *far)], number=8)
    st_far = state(far, ball, [mate(4, -0.5, 0.0), mate(8, *near)], number=9)
    spot, _ = meeting(st_near, 8, passes)
    assert on_segment(spot, ball, (20.0, 10.0))
    assert meeting(st_far, 9, passes) is None
    # A pass to another team-mate is not mine; my own pass is not mine to meet.
    assert meeting(st_near, 8, [Announced(4, to(9), ball, 101)]) is None
    assert meeting(st_near, 8, [Announced(8, into_space, ball, 101)]) is None


def test_a_pass_is_awaited_until_it_has_rolled_past_and_never_longer_than_await_max():
    ball, me = (-30.0, 0.0), (-20.0, -10.0)
    st = state(me, ball, [mate(4, -30.5, 0.0)], number=2)
    assert meeting(st, 2, [Announced(4, to(2), ball, 100 - AWAIT_MAX - 1)]) is None
    # 25 m at a pass's pace: rolled past a man 14 m away long before 20 cycles are up.
    long = act.Pass(target=at(-5.0, 0.0))
    assert meeting(st, 2, [Announced(4, long, ball, 101)]) is not None
    assert meeting(st, 2, [Announced(4, long, ball, 100 - 18)]) is None
    # Of two passes the latest counts.
    newer = [Announced(4, to(2), ball, 90), Announced(4, to(9), ball, 101)]
    assert meeting(st, 2, newer) is None


def test_only_a_pass_in_play_with_the_ball_at_my_feet_is_told():
    a_pass = Decision("pass", to(9), "forward pass")
    assert to_announce(state((0.0, 0.0), (0.5, 0.0)), a_pass)
    assert not to_announce(state((0.0, 0.0), (3.0, 0.0)), a_pass)  # a ball still to be won
    assert not to_announce(state((0.0, 0.0), (0.5, 0.0), mode=PlayMode.FREE_KICK_OUR), a_pass)
    dribble = Decision("dribble", act.Dribble(target=at(10.0, 0.0)), "go")
    assert not to_announce(state((0.0, 0.0), (0.5, 0.0)), dribble)


def test_once_the_ball_is_seen_rolling_the_pass_is_met_where_it_rolls_not_where_it_was_meant_to():
    # Asked for along the x axis towards (0, 0); kicked 3 cycles ago, it rolls at a slant instead.
    start, me = (-20.0, 0.0), (-8.0, 4.0)
    passes = [Announced(4, act.Pass(target=at(0.0, 0.0)), start, 97)]
    seen = (-14.0, 1.5)
    st = state(me, seen, [mate(4, -20.5, 0.0)], number=6)
    velocity = Velocity(vx=17.0, vy=5.0)  # m/s: 1.7 m and 0.5 m a cycle, rolling up and to my side
    rolling_ball = st.model_copy(update={"ball": Ball(positioning=at(*seen), velocity=velocity, age=0)})
    spot, _ = meeting(rolling_ball, 6, passes)
    line = reach.ball_path(seen, (1.7, 0.5))
    assert min(math.dist(spot, p) for p in line) < 0.01  # on the path it rolls
    assert abs(spot[1]) > 1.5  # not on the line it was meant to take (y = 0)
    # Seen only 3 cycles ago, the ball is taken to follow the pass as asked for.
    stale = st.model_copy(update={"ball": Ball(positioning=at(*seen), velocity=velocity, age=3)})
    old_spot, _ = meeting(stale, 6, passes)
    assert abs(old_spot[1]) < 0.01


def test_after_his_pass_in_their_half_the_passer_runs_on_onside_for_the_ball_back():
    # Blue 9 passed to 10 from (15, 12) a cycle ago; their second-last man stands at x = 22.5.
    ball, me = (15.0, 12.0), (15.5, 12.5)
    players = [mate(10, 14.0, 4.0), opp(5, 22.0, 10.0), opp(4, 22.5, 0.0), opp(1, 50.0, 0.0, goalie=True)]
    st = state(me, (17.0, 9.0), players, number=9)
    passes = [Announced(9, to(10), ball, 99)]
    d = decide(st, 9, 11, {10: 3}, passes=passes)
    assert d.method == "moveTo" and d.action.speed == 100.0 and "pass and go" in d.why
    target = (d.action.target.x, d.action.target.y)
    assert 20.0 < target[0] <= 22.5 - 0.5 and abs(target[1]) < abs(me[1])  # up, onside, in towards the middle
    # Offside now (the ball went back to (13, 8), their second-last man stepped up to x = 14): back onside.
    stepped_up = [mate(10, 14.0, 4.0), opp(5, 14.0, 16.0), opp(4, 12.0, 0.0), opp(1, 50.0, 0.0, goalie=True)]
    d = decide(state(me, (13.0, 8.0), stepped_up, number=9), 9, 11, {10: 3}, passes=passes)
    assert "pass and go" in d.why and d.action.target.x <= 14.0 - 0.5 < me[0]
    # Not after a team-mate's pass, nor long after mine, nor after a pass from our half, nor a long kick.
    assert "pass and go" not in decide(st, 9, 11, {10: 3}, passes=[Announced(8, to(10), ball, 99)]).why
    assert "pass and go" not in decide(st, 9, 11, {10: 3}, passes=[Announced(9, to(10), ball, 80)]).why
    ours = (-15.0, 12.0)
    assert "pass and go" not in decide(st, 9, 11, {10: 3}, passes=[Announced(9, to(10), ours, 99)]).why
    long = act.Pass(target=at(40.0, 0.0), power=100.0)
    assert "pass and go" not in decide(st, 9, 11, {10: 3}, passes=[Announced(9, long, ball, 99)]).why
    # A defender stays where he is.
    assert "pass and go" not in decide(state(me, (17.0, 9.0), players, number=3), 3, 11, {}, passes=passes).why


def test_a_pass_seen_rolling_near_its_meeting_is_got_by_the_intercept_skill_a_far_one_by_a_run():
    start, me = (-20.0, 0.0), (-13.0, 1.5)
    passes = [Announced(4, act.Pass(target=at(0.0, 0.0)), start, 97)]
    seen = (-15.0, 0.0)
    st = state(me, seen, [mate(4, -20.5, 0.0)], number=6)
    rolling_ball = st.model_copy(
        update={"ball": Ball(positioning=at(*seen), velocity=Velocity(vx=20.0, vy=0.0), age=0)}
    )
    near = decide(rolling_ball, 6, 11, {4: 90, 5: 3}, passes=passes)  # (5 claims it sooner: my own chase is long)
    assert near.method == "intercept" and "meet the pass: get it" in near.why
    # Not yet seen rolling (the ball's velocity unknown): the run to where it is met, as before.
    unseen = st.model_copy(update={"ball": Ball(positioning=at(*start), age=0)})
    assert decide(unseen, 6, 11, {4: 0}, passes=passes).method == "moveTo"
    # Rolling, but the meeting is far off: run to the spot.
    far = rolling_ball.model_copy(update={"me": rolling_ball.me.model_copy(update={"positioning": at(-2.0, 6.0)})})
    got = decide(far, 6, 11, {4: 90, 5: 3}, passes=passes)
    assert got.method == "moveTo" and "meet the pass (" in got.why


def test_a_team_mate_offside_when_the_pass_is_heard_leaves_it_to_an_onside_one():
    # Their line at x 25 (keeper and one man); blue 9 stands 3 m beyond it, blue 8 onside.
    ball, passer, off9, on8 = (10.0, 0.0), (9.5, 0.0), (28.0, 8.0), (20.0, 12.0)
    theirs = [opp(1, 50.0, 0.0, goalie=True), opp(2, 25.0, 5.0)]
    as9 = state(off9, ball, [mate(4, *passer), mate(8, *on8), *theirs], number=9)
    as8 = state(on8, ball, [mate(4, *passer), mate(9, *off9), *theirs], number=8)
    assert offside_mates(as9, ball) == offside_mates(as8, ball) == frozenset({9})
    into_space = act.Pass(target=at(35.0, 10.0))
    # Nearer its path, blue 9 would meet it if he did not count as offside: this is what changes.
    assert meeting(as9, 9, [Announced(4, into_space, ball, 101)]) is not None
    assert meeting(as8, 8, [Announced(4, into_space, ball, 101)]) is None
    heard = [Announced(4, into_space, ball, 101, offside_mates(as8, ball))]
    assert meeting(as9, 9, heard) is None
    spot, _ = meeting(as8, 8, heard)
    assert on_segment(spot, ball, (45.0, 14.0))  # on its way (it rolls on past its target)
    # The passer picks his receiver by the same rule: never blue 9, and a ball to a point is met by
    # the team-mate he meant.
    as4 = state(passer, ball, [mate(8, *on8), mate(9, *off9), *theirs], number=4)
    choice = best_pass(as4, ball)
    assert choice is not None and choice.number == 8
    if choice.target is not None:
        meant = Announced(4, act.Pass(target=at(*choice.target)), ball, 101, offside_mates(as8, ball))
        assert meeting(as8, 8, [meant]) is not None
    # A ball played to him by name stays his (the passer believed him onside).
    assert meeting(as9, 9, [Announced(4, to(9), ball, 101, frozenset({9}))]) is not None
