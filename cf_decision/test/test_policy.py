"""The policy without ROS or simulator: roles, formation, who goes for the ball, pass and shot choices."""

from __future__ import annotations

import math

import pytest

from cf_decision.goalkeeper import guard_spot
from cf_decision.policy import LINE_AHEAD_MAX, decide
from cf_decision.reach import Runner, ball_path, cycles_to_ball, cycles_to_path, first_cycles, kicked_path, pass_speed
from cf_decision.roles import KICK_OFF_WING, Role, back_line, home_position, kick_off_position, role_of
from cf_decision.set_piece import SetPieceTaker
from cf_decision.situation import offside_line, their_ball, unsure
from cf_decision.with_ball import (
    CLEAR_SPEED,
    WAY_OFF_UP_FIELD,
    best_clearance,
    best_pass,
    best_shot,
    free_ways,
    roomiest,
    their_guard_spot,
)
from cf_decision.without_ball import NEVER, choose_interceptor, marking
from cf_lang.ontology import AbsolutePositioning, Ball, Game, Player, PlayMode, Team, Velocity, WorldState
from cf_lang.ontology import actions as act


def at(x, y, yaw=0.0):
    return AbsolutePositioning(x=x, y=y, yaw=yaw)


def state(me, ball=None, players=(), mode=PlayMode.PLAY_ON, number=7):
    return WorldState(
        time=100,
        me=Player(player_number=number, which_team=Team.OUR, positioning=at(*me)),
        ball=Ball(positioning=at(*ball)) if ball else None,
        players=tuple(players),
        game=Game(time=100, play_mode=mode),
    )


def mate(n, x, y):
    return Player(player_number=n, which_team=Team.OUR, positioning=at(x, y))


def opp(n, x, y, goalie=False):
    return Player(player_number=n, which_team=Team.OPP, positioning=at(x, y), is_goalie=goalie)


def test_roles_and_formation_shift_with_the_ball():
    assert [role_of(n) for n in (1, 3, 7, 10)] == [Role.GOALKEEPER, Role.DEFENDER, Role.MIDFIELDER, Role.FORWARD]
    assert role_of(2, team_size=3) is Role.FORWARD  # small teams: keeper, then a forward, then a defender
    back, _ = home_position(4, ball_x=-30.0)
    up, _ = home_position(4, ball_x=30.0)
    assert back < up and home_position(1, ball_x=30.0) == (-50.0, 0.0)


def test_in_their_half_the_block_follows_the_ball_closer_than_in_ours():
    def behind(number, ball_x):
        return ball_x - home_position(number, ball_x=ball_x)[0]

    assert behind(7, 40.0) <= 18.0 and behind(3, 40.0) < 50.0  # midfield within 18 m, the back line up
    assert abs(home_position(7, ball_x=-20.0)[0] - (-18.0 - 0.55 * 20.0)) < 1e-9  # in our half: 0.55 m a metre
    assert home_position(7, ball_x=10.0)[0] - home_position(7, ball_x=0.0)[0] == 10.0


def test_with_the_ball_deep_in_our_half_the_wide_forwards_drop_to_the_outlets_by_the_touch_lines():
    assert home_position(9, ball_x=-30.0, ball_y=-10.0) == (-13.0, 26.0)
    assert home_position(11, ball_x=-30.0, ball_y=10.0) == (-13.0, -26.0)
    assert home_position(10, ball_x=-30.0)[0] == -5.0  # the centre forward stays up
    assert home_position(9, ball_x=-15.0)[0] == -5.0 and home_position(9, ball_x=10.0)[0] == 12.0
    d = decide(state((-5.0, 16.0), ball=(-35.0, 0.0), players=[mate(3, -34.0, 0.0)], number=9), 9, 11, {3: 1})
    assert d.method == "moveTo" and math.dist((d.action.target.x, d.action.target.y), (-13.0, 26.0)) <= 4.0


def test_fastest_player_goes_for_the_ball_and_ties_go_to_the_lower_number():
    assert choose_interceptor(7, 5, {7: 5, 8: 9})
    assert not choose_interceptor(8, 9, {7: 5, 8: 9})
    assert choose_interceptor(3, 6, {3: 6, 9: 6}) and not choose_interceptor(9, 6, {3: 6, 9: 6})
    assert choose_interceptor(4, 10, {})


def test_a_rolling_ball_is_met_where_it_will_be():
    assert cycles_to_ball((0.0, 0.0), (0.5, 0.0)) == 0
    still = cycles_to_ball((0.0, 0.0), (10.0, 0.0))
    coming = cycles_to_ball((0.0, 0.0), (10.0, 0.0), (-1.5, 0.0))
    going = cycles_to_ball((0.0, 0.0), (10.0, 0.0), (1.5, 0.0))
    assert coming < still < going
    path = ball_path((0.0, 0.0), (2.0, 0.0), 3)
    assert path[0] == (2.0, 0.0) and abs(path[2][0] - (2.0 + 1.88 + 1.7672)) < 1e-9
    assert cycles_to_path((30.0, 40.0), kicked_path((0.0, 0.0), (20.0, 0.0), 1.5)) is None  # too far to get there


def test_shoot_when_the_ball_beats_the_keeper():
    keeper = opp(1, 51.0, 4.0, goalie=True)
    d = decide(state((40.0, 3.0), ball=(40.5, 3.0), players=[keeper]), 9, 11, {})
    assert d.method == "shoot" and d.action.target.y < 0  # away from the keeper's side
    assert best_shot(state((0.0, 0.0), players=[keeper]), (10.0, 0.0)) is None  # out of range
    wall = [keeper] + [opp(n, 47.0, y) for n, y in zip(range(2, 9), (-6, -4, -2, 0, 2, 4, 6), strict=True)]
    assert best_shot(state((40.0, 0.0), players=wall), (40.5, 0.0)) is None  # every line blocked


def test_an_unseen_goalkeeper_counts_as_standing_at_his_guard_spot():
    # Their keeper out of sight: from 28 m no line beats him where he would stand; seen far off, free.
    far = (27.5, 12.0)
    assert best_shot(state((27.0, 12.0)), far) is None
    assert best_shot(state((27.0, 12.0), players=[opp(1, 52.0, -20.0, goalie=True)]), far) is not None
    assert best_shot(state((41.5, 0.0)), (42.0, 0.0)) is not None  # 10 m out in the middle: past him
    assert best_shot(state((40.0, 6.0)), (40.5, 6.0)) is None  # 12 m out to one side: not
    spot = their_guard_spot((40.5, 6.0))
    assert 2.0 <= 52.5 - spot[0] <= 6.0 and 0.0 < spot[1] < 6.0  # out of his goal, on the ball's side


def test_an_opponent_not_seen_lately_may_be_nearer_the_pass_than_believed():
    # 5 m off the pass's way: seen just now he cannot get there first; 6 cycles unseen (2.4 m of
    # doubt) he may: no longer a safe pass. Far off its way, his doubt does not matter.
    def chosen(y, age):
        man = Player(player_number=9, which_team=Team.OPP, positioning=at(-12.0, y), age=age)
        return best_pass(state((-20.0, 0.0), players=[mate(6, -5.0, 0.0), man]), (-19.5, 0.0))

    assert chosen(5.0, 0) is not None and chosen(5.0, 6) is None
    assert chosen(7.0, 6) is not None and chosen(7.0, 60) is not None  # (the doubt stops at 3 m)
    assert unsure(Player(player_number=9, which_team=Team.OPP, age=2)) == 0.8


def test_pass_forward_to_a_team_mate_who_gets_there_first():
    keeper, back = opp(1, 50.0, 0.0, goalie=True), opp(3, 30.0, -25.0)  # their line at 30: 10 is onside
    players = [mate(10, 15.0, 5.0), mate(11, -5.0, -10.0), opp(4, 2.0, -20.0), opp(5, 1.0, 3.0), keeper, back]
    d = decide(state((0.0, 0.0), ball=(0.5, 0.0), players=players), 7, 11, {})
    assert d.method == "pass" and (d.action.to or d.action.target) is not None
    choice = best_pass(state((0.0, 0.0), players=players), (0.5, 0.0))
    assert choice.number == 10 and choice.gain > 10.0


def test_a_pass_is_judged_with_the_receivers_top_speed_and_an_unknown_one_as_the_defaults():
    marker = opp(4, 16.0, 10.0)
    told = mate(10, 15.0, 10.0).model_copy(update={"top_speed": 10.0})
    slow = mate(10, 15.0, 10.0).model_copy(update={"top_speed": 8.0})  # 0.8 m/cycle
    choice = best_pass(state((0.0, 0.0), players=[mate(10, 15.0, 10.0), marker]), (0.5, 0.0))
    assert choice.number == 10 and choice.target == (25.0, 10.0)  # a ball ahead of him
    assert best_pass(state((0.0, 0.0), players=[told, marker]), (0.5, 0.0)) == choice
    assert best_pass(state((0.0, 0.0), players=[slow, marker]), (0.5, 0.0)) is None  # the marker is first
    path = kicked_path((0.0, 0.0), (25.0, 10.0), pass_speed(27.0))
    assert first_cycles(path, [Runner((15.0, 10.0), speed=0.8)]) > first_cycles(path, [Runner((15.0, 10.0))])


def test_no_pass_an_opponent_reaches_first():
    players = [mate(10, 20.0, 0.0), opp(4, 10.0, 0.3), opp(5, 3.0, 3.0)]
    assert best_pass(state((0.0, 0.0), players=players), (0.5, 0.0)) is None
    d = decide(state((0.0, 0.0), ball=(0.5, 0.0), players=players[1:]), 7, 11, {})
    assert d.method == "dribble"  # nobody to pass to in their half: take it on
    free = [mate(10, 20.0, 0.0), opp(4, 10.0, 12.0)]
    assert best_pass(state((0.0, 0.0), players=free), (0.5, 0.0)).number == 10


def test_with_space_ahead_carry_the_ball():
    players = [mate(10, -8.0, 0.0), opp(4, 12.0, 0.0)]
    d = decide(state((0.0, 0.0), ball=(0.5, 0.0), players=players), 7, 11, {})
    assert d.method == "dribble" and "space" in d.why and d.action.speed == 70.0  # a man 12 m ahead: close control
    open_run = decide(state((0.0, 0.0), ball=(0.5, 0.0), players=[players[0], opp(4, 25.0, 0.0)]), 7, 11, {})
    assert open_run.method == "dribble" and open_run.action.speed == 100.0  # nobody on the way: full speed


def test_forwards_stay_onside_and_up_the_field():
    players = [opp(1, 50.0, 0.0, goalie=True), opp(2, 20.0, 5.0), opp(3, 30.0, -5.0)]
    assert offside_line(state((0.0, 0.0), players=players), (-30.0, 0.0)) == 30.0  # second-last
    assert offside_line(state((0.0, 0.0), players=players[:1]), (-30.0, 0.0)) is None
    assert home_position(10, ball_x=-40.0)[0] >= -5.0  # an outlet when we win the ball
    assert home_position(10, ball_x=40.0, offside_x=20.0)[0] == 19.0
    assert home_position(3, ball_x=40.0, offside_x=-20.0) == home_position(3, ball_x=40.0)  # not defenders


def test_intercept_or_hold_position():
    assert decide(state((0.0, 0.0), ball=(5.0, 0.0)), 7, 11, {}).method == "intercept"
    d = decide(state((-18.0, 0.0), ball=(5.0, 0.0)), 7, 11, {9: 1})
    assert d.method in ("moveTo", "turnToObject")


def test_the_interceptor_asks_for_the_kick_as_the_ball_comes_into_reach():
    """A ball in reach next cycle: the pass is asked for now, judged from where the ball will be
    (the kick skill gets to it itself); a ball further off is intercepted first."""
    players = [mate(10, 15.0, 5.0), opp(5, 1.0, 8.0)]
    coming = state((0.0, 0.0), ball=(2.5, 0.0), players=players)
    coming = coming.model_copy(update={"ball": Ball(positioning=at(2.5, 0.0), velocity=Velocity(vx=-15.0, vy=0.0))})
    d = decide(coming, 7, 11, {})
    assert d.method == "pass" and "the ball comes: 1 cycles" in d.why
    assert decide(coming, 7, 11, {}, may_touch=False).method != "pass"
    far = coming.model_copy(update={"ball": Ball(positioning=at(8.0, 0.0), velocity=Velocity(vx=-5.0, vy=0.0))})
    assert decide(far, 7, 11, {}).method == "intercept"
    still_set_piece = state((0.0, 0.0), ball=(1.8, 0.0), players=players, mode=PlayMode.FREE_KICK_OUR)
    assert "the ball comes" not in decide(still_set_piece, 7, 11, {}).why


def test_an_opponents_pass_stays_their_ball_while_it_rolls_by_one_of_us():
    """Nearest the ball, our midfielder was "on the ball" for a cycle or two of an opponent's pass
    rolling by him: the defenders stopped marking and started again. The ball is the receiver's."""
    players = [opp(6, 10.0, 0.0), opp(9, -12.0, 0.0)]
    rolling = state((3.0, 3.0), ball=(4.0, 0.0), players=players)
    rolling = rolling.model_copy(update={"ball": Ball(positioning=at(4.0, 0.0), velocity=Velocity(vx=-25.0, vy=0.0))})
    assert their_ball(rolling, (4.0, 0.0))
    mine = rolling.model_copy(update={"ball": Ball(positioning=at(4.0, 0.0), velocity=Velocity(vx=-3.0, vy=10.0))})
    assert not their_ball(mine, (4.0, 0.0))  # a slow ball rolling my way is mine
    still = state((3.0, 3.0), ball=(4.0, 0.0), players=[opp(6, 9.0, 0.0)])
    assert not their_ball(still, (4.0, 0.0))  # a still ball: the nearer player's
    at_feet = state((3.0, 3.0), ball=(4.0, 0.0), players=[opp(6, 5.5, 0.0)])
    assert their_ball(at_feet, (4.0, 0.0))


def test_before_kick_off_take_the_formation():
    d = decide(state((10.0, 10.0), ball=(0.0, 0.0), mode=PlayMode.BEFORE_KICK_OFF), 3, 11, {})
    assert isinstance(d.action, act.Move) and d.action.target.x < 0


def test_at_our_kick_off_the_wide_forwards_wait_out_wide_and_the_pass_finds_one_in_space():
    wide = decide(state((10.0, 10.0), ball=(0.0, 0.0), mode=PlayMode.BEFORE_KICK_OFF), 9, 11, {})
    assert isinstance(wide.action, act.Move) and wide.action.target.x < 0 and abs(wide.action.target.y) >= 25.0
    assert abs(home_position(9, ball_x=0.0)[1]) < 20.0  # in play he comes back in
    assert [abs(kick_off_position(n)[1]) for n in (9, 11)] == [KICK_OFF_WING] * 2 and KICK_OFF_WING > 30.0
    midfield = [kick_off_position(n) for n in (6, 7, 8)]
    assert all(-10.0 < x < 0.0 for x, _ in midfield)  # near the halfway line, in our half,
    assert all(
        x > home_position(n, ball_x=0.0)[0] + 8.0 for n, (x, _) in zip((6, 7, 8), midfield, strict=True)
    )  # 10-12 m up
    # HELIOS base's kick-off: ten men in two rows of five, within 10 m of the middle.
    rows = [opp(2 + i, x, y) for i, (x, y) in enumerate((x, y) for x in (15.0, 25.0) for y in (-10, -5, 0, 5, 10))]
    left, right = kick_off_position(9, 11), kick_off_position(11, 11)
    players = [*rows, mate(9, *left), mate(11, *right), mate(7, -18.0, 0.0)]
    waiting = decide(
        state(right, ball=(0.0, 0.0), players=players, mode=PlayMode.KICK_OFF_OUR, number=11), 11, 11, {10: 1}
    )
    assert waiting.method == "turnToObject"  # he keeps his place while the taker looks
    kick = decide(
        state((-0.5, 0.0), ball=(0.0, 0.0), players=players, mode=PlayMode.KICK_OFF_OUR, number=10), 10, 11, {}
    )
    assert kick.method == "pass" and "team-mate 9" in kick.why  # into the space in front of a wide forward
    assert kick.action.target.x > 0.0 and abs(kick.action.target.y) > 20.0


def test_goalkeeper_guards_catches_clears():
    keeper = dict(number=1)
    pressed = [opp(9, -46.0, 2.0), mate(3, -40.0, 0.0)]
    d = decide(state((-50.0, 0.0), ball=(-49.2, 0.3), players=pressed, **keeper), 1, 11, {})
    assert d.method == "catch"  # in his area, from an opponent: caught, the ball is ours at a free kick
    d = decide(state((-50.0, 0.0), ball=(-48.9, 0.0), **keeper), 1, 11, {})
    assert d.method == "catch"
    # A team-mate nearer the ball than any opponent may have played it to him: no catch (a back
    # pass), clear it.
    back = [opp(9, -40.0, 2.0), mate(3, -47.0, 0.0)]
    d = decide(state((-50.0, 0.0), ball=(-49.2, 0.3), players=back, **keeper), 1, 11, {})
    assert d.method == "pass" and d.why == "clear the ball"
    # ... nor when he believes a team-mate touched it last, whoever is near it now.
    d = decide(state((-50.0, 0.0), ball=(-49.2, 0.3), players=pressed, **keeper), 1, 11, {}, mate_touched=True)
    assert d.method == "pass" and d.why == "clear the ball"
    # Out of his area he kicks, never catches.
    d = decide(state((-34.0, 0.0), ball=(-33.5, 0.3), players=pressed, **keeper), 1, 11, {})
    assert d.method == "pass"
    # The ball caught, the free kick is ours: he takes it as a set piece (a safe pass to a team-mate).
    free = [mate(3, -38.0, 15.0), opp(9, -40.0, -8.0)]
    d = decide(state((-49.0, 0.0), ball=(-48.5, 0.0), players=free, mode=PlayMode.FREE_KICK_OUR, **keeper), 1, 11, {})
    assert d.method == "pass" and d.why == "set piece to team-mate 3"
    d = decide(state((-40.0, 10.0), ball=(20.0, 0.0), **keeper), 1, 11, {})
    assert d.method == "moveTo" and d.action.target.x < -46  # far ball: a few metres out, in the middle
    near = decide(state((-51.0, 0.0), ball=(-35.0, 10.0), **keeper), 1, 11, {})
    spot = (near.action.target.x, near.action.target.y)
    assert near.method == "moveTo" and -49.0 < spot[0] < -46.0 and 2.0 < spot[1] < 4.0  # towards the ball


def test_the_goalkeeper_catches_only_within_the_servers_catch_angle():
    # HELIOS base's ball from by our goal line came at his back: he asked to catch it 128 and 169
    # degrees off his body, which rcssserver bounds to 90, and it went in (session 66).
    keeper, shooter = dict(number=1), [opp(9, -46.0, -12.0)]
    behind = state((-51.9, 6.2), ball=(-52.4, 5.8), players=shooter, **keeper)  # body facing up the field
    d = decide(behind, 1, 11, {})
    assert d.method == "pass" and d.why == "clear the ball"  # kickable at any angle: not a catch
    turned = behind.model_copy(update={"me": behind.me.model_copy(update={"positioning": at(-51.9, 6.2, math.pi)})})
    assert decide(turned, 1, 11, {}).method == "catch"


def off_line(point, a, b):
    """How far ``point`` is from the line through ``a`` and ``b``."""
    (ax, ay), (bx, by), (px, py) = a, b, point
    return abs((bx - ax) * (py - ay) - (by - ay) * (px - ax)) / math.dist(a, b)


@pytest.mark.parametrize("ball", [(-50.5, 15.9), (-40.0, -12.0), (-30.0, 0.0)])
def test_the_goalkeepers_spot_is_as_far_from_a_shot_at_either_post(ball):
    # By the goal line 16 m out, his spot on the line to the goal's centre was 1.2 m off a shot at the
    # near post and 0.5 m off one at the far post: HELIOS base shot past him at the near post.
    spot = guard_spot(ball)
    near, far = (-52.5, math.copysign(7.01, ball[1] or 1.0)), (-52.5, -math.copysign(7.01, ball[1] or 1.0))
    assert off_line(spot, ball, near) == pytest.approx(off_line(spot, ball, far), abs=1e-6)
    assert spot[0] > -52.5 and abs(spot[1]) < 7.01  # in front of his goal
    if ball[0] < -50.0:  # so tight that both are well within his catch where he stands
        assert off_line(spot, ball, near) < 0.8
        centre_line = (-52.0, 3.97)  # the spot before: 4 m out on the line to the goal's centre
        assert off_line(centre_line, ball, near) > 2 * off_line(centre_line, ball, far)


def test_the_goalkeeper_keeps_to_his_guard_spot_within_the_move_skills_tolerance():
    keeper, ball = dict(number=1), (-35.0, 10.0)
    x, y = guard_spot(ball)
    d = decide(state((x, y - 0.9), ball=ball, **keeper), 1, 11, {})
    assert d.method == "moveTo" and d.action.speed == 100.0  # 0.9 m off: back to it at full speed
    assert math.dist((d.action.target.x, d.action.target.y), (x, y)) < 1e-6
    d = decide(state((x, y - 0.5), ball=ball, **keeper), 1, 11, {})
    assert d.method == "turnToDirection"  # within the skill's 0.7 m: a move would end at once


def test_the_goalkeeper_closes_down_an_opponent_through_on_goal():
    keeper = dict(number=1)
    through = [opp(9, -42.0, 2.0)]
    d = decide(state((-50.0, 0.0), ball=(-41.5, 2.0), players=through, **keeper), 1, 11, {})
    assert d.method == "intercept" and "one on one" in d.why
    loose = decide(state((-50.0, 0.0), ball=(-41.5, 2.0), **keeper), 1, 11, {})
    assert loose.method != "intercept"  # nobody on it: keep the goal (a defender goes for it)


def test_the_goalkeeper_goes_for_a_shot_at_our_goal_as_soon_as_it_is_struck():
    keeper, spot = dict(number=1), guard_spot((-38.0, 8.0))

    def shot_state(towards, speed):
        angle = math.atan2(towards[1] - 8.0, towards[0] + 38.0)
        st = state(spot, ball=(-38.0, 8.0), **keeper)
        velocity = Velocity(vx=10.0 * speed * math.cos(angle), vy=10.0 * speed * math.sin(angle))
        return st.model_copy(update={"ball": st.ball.model_copy(update={"velocity": velocity})})

    # 15 m out, struck at the far post: he sets off at once (before, he kept to his spot until it was 8 m off).
    d = decide(shot_state((-52.5, -3.5), 2.5), 1, 11, {})
    assert d.method == "intercept" and d.why == "a shot at our goal"
    assert decide(shot_state((-52.5, 7.5), 2.5), 1, 11, {}).why == "a shot at our goal"  # just by the post
    wide = decide(shot_state((-52.5, -12.0), 2.5), 1, 11, {})  # rolling wide of the goal
    slow = decide(shot_state((-52.5, 0.0), 0.6), 1, 11, {})  # a ball that stops short of the line
    assert "a shot at our goal" not in (wide.why, slow.why)


def test_at_our_set_piece_pass_back_or_kick_long_never_dribble():
    back = [mate(6, -12.0, 3.0), opp(9, 8.0, 0.0)]
    d = decide(state((0.0, 0.0), ball=(0.5, 0.0), players=back, mode=PlayMode.KICK_OFF_OUR), 10, 11, {})
    assert d.method == "pass" and d.action.to.player_number == 6  # backwards: no open mate ahead
    d = decide(state((0.0, 0.0), ball=(0.5, 0.0), players=[opp(9, 8.0, 0.0)], mode=PlayMode.FREE_KICK_OUR), 10, 11, {})
    assert d.method == "pass" and d.action.target is not None and d.action.target.x > 20.0  # nobody: kick long
    d = decide(state((0.0, 0.0), ball=(0.5, 0.0), players=back), 10, 11, {})
    assert d.method == "dribble"  # in play_on the same player dribbles


def test_at_our_set_piece_the_taker_first_looks_for_opponents_near_the_ball_he_has_not_seen_lately():
    ahead = opp(4, 12.0, 28.0).model_copy(update={"age": 5})
    kick_in = state((0.0, 30.0), ball=(0.5, 30.0), players=[ahead], mode=PlayMode.KICK_IN_OUR)
    d = decide(kick_in, 7, 11, {})
    assert d.method == "turnToObject" and d.why == "set piece: look first"
    seen = kick_in.model_copy(update={"players": (ahead.model_copy(update={"age": 1}),)})
    assert decide(seen, 7, 11, {}).method == "pass"  # seen just now: he kicks
    behind = opp(4, -12.0, 28.0).model_copy(update={"age": 5})  # 12 m nearer our goal: no threat to the kick
    assert decide(kick_in.model_copy(update={"players": (behind,)}), 7, 11, {}).method == "pass"
    in_play = kick_in.model_copy(update={"game": Game(time=100, play_mode=PlayMode.PLAY_ON)})
    assert decide(in_play, 7, 11, {}).method != "turnToObject"  # in play there is no time to wait


def test_at_our_kick_off_after_a_goal_the_taker_looks_until_nobody_is_believed_in_our_half():
    # The goal stopped the clock: the scorers are believed near our goal, as fresh as a cycle ago.
    scorers = [opp(n, -40.0, y).model_copy(update={"age": 1}) for n, y in ((9, 3.0), (10, -4.0))]
    kick_off = state((-0.3, 0.0), ball=(0.0, 0.0), players=scorers, mode=PlayMode.KICK_OFF_OUR, number=10)
    d = decide(kick_off, 10, 11, {})
    assert d.method == "turnToObject" and d.why == "set piece: look first"
    in_front = [opp(n, 15.0, y).model_copy(update={"age": 0}) for n, y in ((9, 3.0), (10, -4.0))]
    assert decide(kick_off.model_copy(update={"players": tuple(in_front)}), 10, 11, {}).method == "pass"
    kick_in = kick_off.model_copy(update={"game": Game(time=100, play_mode=PlayMode.KICK_IN_OUR)})
    assert decide(kick_in, 10, 11, {}).method == "pass"  # at other set pieces men behind the ball may be there


def test_the_taker_of_our_set_piece_leaves_the_ball_until_someone_else_touched_it():
    taker = SetPieceTaker()
    kick_in = state((0.0, 30.0), ball=(0.5, 30.0), mode=PlayMode.KICK_IN_OUR)
    assert taker.may_touch(kick_in)
    taker.decided(kick_in, decide(kick_in, 7, 11, {}))
    # The kick went 3 m: the ball is still the taker's nearest, and play is on.
    after = state((0.0, 30.0), ball=(3.0, 29.0), players=[mate(8, 15.0, 20.0)])
    assert not taker.may_touch(after)
    d = decide(after, 7, 11, {7: 2, 8: 15}, may_touch=False)
    assert d.method not in ("intercept", "pass", "dribble", "shoot")
    assert NEVER > 10**5
    touched = state((0.0, 30.0), ball=(9.0, 26.0), players=[mate(8, 9.5, 26.5)])
    assert taker.may_touch(touched) and taker.may_touch(after)  # a team-mate reached it: play on


def test_a_stale_sighting_near_the_ball_does_not_release_the_taker():
    taker = SetPieceTaker()
    free_kick = state((-12.0, 5.0), ball=(-11.5, 5.0), mode=PlayMode.FREE_KICK_OUR)
    taker.decided(free_kick, decide(free_kick, 7, 11, {}))
    # Kicked softly; the opponent who committed the foul was last seen beside the ball 5 cycles ago.
    stale = opp(7, -11.0, 5.2).model_copy(update={"age": 5})
    assert not taker.may_touch(state((-12.0, 5.0), ball=(-10.9, 5.1), players=[stale]))
    fresh = stale.model_copy(update={"age": 0})
    assert taker.may_touch(state((-12.0, 5.0), ball=(-10.9, 5.1), players=[fresh]))  # he is there: it was touched


def where(player):
    return (player.positioning.x, player.positioning.y)


def off_by(frm, to, other):
    """Degrees between the ways from ``frm`` to ``to`` and to ``other``."""
    a = math.atan2(to[1] - frm[1], to[0] - frm[0]) - math.atan2(other[1] - frm[1], other[0] - frm[0])
    return abs(math.degrees(math.remainder(a, math.tau)))


def test_pressed_in_our_own_third_clear_it_past_the_presser_instead_of_dribbling():
    d = decide(state((-40.0, 5.0), ball=(-39.5, 5.0), players=[opp(9, -36.0, 4.0)]), 4, 11, {})
    assert d.method == "pass" and d.why == "clear the ball" and d.action.power == 100.0
    aim = (d.action.target.x, d.action.target.y)
    assert aim[0] > -39.5 and off_by((-39.5, 5.0), aim, (-36.0, 4.0)) > 20.0  # not into the man
    d = decide(state((-40.0, 5.0), ball=(-39.5, 5.0), players=[opp(9, -20.0, 30.0)]), 4, 11, {})
    assert d.method == "dribble"  # not pressed: carry it out


def test_in_our_half_without_a_forward_pass_or_an_open_run_clear_it():
    players = [mate(3, -35.0, 0.0), opp(9, -20.0, 2.0)]  # a man 10 m ahead: space, but no open run
    d = decide(state((-30.0, -5.0), ball=(-29.5, -5.0), players=players), 4, 11, {})
    assert d.method == "pass" and d.why == "clear the ball"
    assert off_by((-29.5, -5.0), (d.action.target.x, d.action.target.y), (-20.0, 2.0)) > 20.0
    ahead = decide(state((10.0, -5.0), ball=(10.5, -5.0), players=[opp(9, 20.0, -3.0)]), 9, 11, {})
    assert ahead.method == "dribble" and "space" in ahead.why  # in their half, far from goal: carry it


def test_near_their_goal_with_nothing_better_shoot_away_from_the_keeper():
    keeper = opp(1, 51.0, -3.0, goalie=True)
    blockers = [opp(n, 33.0, y) for n, y in zip(range(2, 7), (-6.0, -3.0, 0.0, 3.0, 6.0), strict=True)]
    st = state((30.0, 0.0), ball=(30.5, 0.0), players=[keeper, *blockers])
    assert best_shot(st, (30.5, 0.0)) is None  # no free line
    d = decide(st, 9, 11, {})
    assert d.method == "shoot" and d.why == "a hopeful shot" and d.action.target.y > 0.0
    far = state((20.0, 0.0), ball=(20.5, 0.0), players=[keeper, *[opp(n, 23.0, y) for n, y in ((2, -2.0), (3, 2.0))]])
    assert decide(far, 9, 11, {}).method != "shoot"  # 32 m out: not yet
    corner = decide(state((40.0, 15.0), ball=(40.0, 15.0), players=[keeper], mode=PlayMode.FREE_KICK_OUR), 9, 11, {})
    assert corner.method == "shoot" and corner.action.target.y > 0.0  # a set piece's shot: away from him too


def test_from_further_than_a_close_shot_with_room_drive_at_goal_before_the_hopeful_shot():
    keeper, back = opp(1, 51.0, 0.0, goalie=True), opp(2, 42.0, 2.0)  # a man 11 m on: no open run, but room
    st = state((32.0, 8.0), ball=(32.5, 8.0), players=[keeper, back])
    assert best_shot(st, (32.5, 8.0)) is None
    d = decide(st, 9, 11, {})
    assert d.method == "dribble" and d.why == "drive at goal" and d.action.speed < 100.0  # close control
    to_goal = math.dist((d.action.target.x, d.action.target.y), (52.5, 0.0))
    assert to_goal <= math.dist((32.5, 8.0), (52.5, 0.0)) - 4.0
    close = state((39.0, 5.0), ball=(39.5, 5.0), players=[keeper, opp(2, 45.0, 1.0)])  # 14 m out: shoot
    assert decide(close, 9, 11, {}).why in ("a hopeful shot", "a free shot")
    pressed = state((32.0, 8.0), ball=(32.5, 8.0), players=[keeper, opp(2, 34.5, 7.0), opp(3, 34.0, 10.0)])
    assert decide(pressed, 9, 11, {}).why == "a hopeful shot"  # no room: the shot at least may go in


def test_by_their_corner_flag_the_carry_takes_a_way_towards_goal_not_along_the_touch_line():
    # A man 10 m off in both ways towards goal: the roomiest way runs along the touch line.
    keeper, inside = opp(1, 51.0, 0.0, goalie=True), opp(2, 47.0, -21.0)
    st = state((40.0, -29.0), ball=(40.5, -29.0), players=[keeper, inside])
    d = decide(st, 11, 11, {})
    assert d.method == "dribble" and d.why == "drive at goal from further out"
    to_goal = math.dist((d.action.target.x, d.action.target.y), (52.5, 0.0))
    assert to_goal <= math.dist((40.5, -29.0), (52.5, 0.0)) - 4.0


def test_at_an_indirect_free_kick_near_their_goal_a_team_mate_touches_it_before_any_shot():
    # HELIOS base's back pass (session 63): our free kick 10.8 m out, their men on the goal line.
    line = [opp(1, 52.1, 0.0, goalie=True), *(opp(n, 52.3, y) for n, y in ((2, 5.3), (3, 2.7), (4, -3.3)))]
    marked = [mate(11, 41.0, 2.0), opp(6, 40.0, 3.0), opp(7, 41.5, 3.5)]  # his one team-mate near is marked
    for mode in (PlayMode.FREE_KICK_OUR, PlayMode.INDIRECT_FREE_KICK_OUR):
        st = state((45.0, 8.5), ball=(45.4, 8.2), players=[*line, *marked], mode=mode, number=10)
        d = decide(st, 10, 11, {})
        if mode is PlayMode.FREE_KICK_OUR:
            assert d.method == "shoot" and d.why == "set piece near goal"
        else:  # no goal can come of a shot: the nearest team-mate gets it, safe or not
            assert d.method == "pass" and d.action.to.player_number == 11 and "indirect" in d.why, d


def test_in_our_half_the_second_fastest_covers_the_way_from_an_opponents_ball_to_our_goal():
    players = [opp(9, -20.5, 0.0)]
    cover = decide(state((-15.0, 5.0), ball=(-20.0, 0.0), players=players), 6, 11, {4: 3, 6: 7, 8: 12})
    # Not after the ball (a chaser from behind never has it in front of him): in its way to our goal.
    assert cover.method == "moveTo" and "cover" in cover.why and cover.action.speed == 100.0
    assert (cover.action.target.x, cover.action.target.y) == (-23.0, 0.0)  # 3 m towards our goal
    there = decide(state((-23.5, 0.5), ball=(-20.0, 0.0), players=players), 6, 11, {4: 3, 6: 7, 8: 12})
    assert there.method == "turnToObject" and "cover" in there.why  # waits for him, facing the ball
    close = decide(state((-21.5, 0.5), ball=(-20.0, 0.0), players=players), 6, 11, {4: 3, 6: 7, 8: 12})
    assert close.method == "pass" and "tackling reach" in close.why  # he came to him: tackle (or close in)
    hold = decide(state((-15.0, 5.0), ball=(-20.0, 0.0), players=players), 6, 11, {4: 3, 5: 4, 6: 7})
    assert hold.method not in ("intercept", "pass")  # third fastest: holds
    loose = decide(state((-15.0, 5.0), ball=(-20.0, 0.0)), 6, 11, {4: 3, 6: 7})
    assert loose.method != "intercept"  # nobody on the ball: one goes
    ahead = decide(state((25.0, 5.0), ball=(20.0, 0.0), players=[opp(3, 20.5, 0.0)]), 10, 11, {10: 4, 9: 12})
    assert ahead.method == "dribble" and "win it" in ahead.why  # in their half: win it and go


def test_when_they_have_the_ball_defenders_and_midfielders_mark_goal_side():
    holder, runner, far = opp(9, -32.0, 0.0), opp(10, -40.0, 6.0), opp(11, 30.0, 20.0)
    players = [holder, runner, far, mate(4, -35.0, -10.0)]
    st = state((-36.0, 4.0), ball=(-32.5, 0.0), players=players, number=3)
    marks = marking(st, 11, (-32.5, 0.0))
    assert marks.get(3) == (-40.0, 6.0)  # the nearest pair; the man on the ball is the pressers'
    assert (30.0, 20.0) not in marks.values()  # too far from anyone's spot
    d = decide(st, 3, 11, {4: 2, 3: 20, 7: 5})
    assert d.method == "moveTo" and "mark" in d.why and d.action.target.x < -40.0  # between him and our goal
    ours = state((-36.0, 4.0), ball=(-32.5, 0.0), players=[holder, runner, mate(7, -33.0, 0.5)], number=3)
    assert "mark" not in decide(ours, 3, 11, {7: 0, 3: 20}).why  # our ball: keep the shape


def test_the_block_leans_to_the_balls_wing():
    middle = {n: home_position(n, ball_x=10.0, ball_y=0.0) for n in range(2, 12)}
    wing = {n: home_position(n, ball_x=10.0, ball_y=-28.0) for n in range(2, 12)}
    assert all(wing[n][1] - middle[n][1] == pytest.approx(-0.45 * 28.0) for n in wing)  # everyone 12.6 m over
    assert wing[8][1] == pytest.approx(-26.6) and wing[11][1] == pytest.approx(-28.6)  # two on the ball's wing
    assert wing[10][1] == pytest.approx(-12.6) and wing[7][1] == pytest.approx(-12.6)  # two in the channel inside it
    assert home_position(5, ball_x=10.0, ball_y=-34.0)[1] == -30.0  # none beyond 30 m out


def test_our_back_line_holds_behind_the_ball_and_no_man_draws_it_deeper():
    assert back_line(-20.5) == -30.5 and back_line(-40.0) == -45.0 and back_line(10.0) == -20.0
    assert home_position(3, ball_x=-20.0)[0] == -30.0  # (the formation alone: -46, at the -45 limit)
    assert home_position(3, ball_x=30.0)[0] == -35.0 + 30.0  # up the field the shift rules
    runner = opp(10, -40.0, 6.0)  # a man of theirs 20 m behind the ball, by our goal
    st = state((-33.0, 4.0), ball=(-20.5, 0.0), players=[opp(9, -20.0, 0.0), runner], number=3)
    d = decide(st, 3, 11, {4: 2, 3: 20, 7: 5})
    assert d.method == "moveTo" and "mark" in d.why and d.action.target.x == -30.5  # he is left offside
    assert home_position(7, ball_x=-20.0)[0] == -18.0 - 0.55 * 20.0  # midfielders are not held up


def test_any_player_within_tackling_reach_of_an_opponents_ball_goes_for_it():
    holder, runner = opp(9, -30.0, 0.0), opp(10, -40.0, 6.0)
    close = state((-32.3, 0.5), ball=(-30.8, 0.0), players=[holder, runner], number=3)
    d = decide(close, 3, 11, {7: 1, 4: 2, 3: 5})  # neither the fastest nor the second
    assert d.method == "pass" and "tackling reach" in d.why  # the kick skill's approach tackles
    further = state((-34.0, 0.5), ball=(-30.8, 0.0), players=[holder, runner], number=3)
    assert "tackling reach" not in decide(further, 3, 11, {7: 1, 4: 2, 3: 5}).why
    loose = state((-32.3, 0.5), ball=(-30.8, 0.0), players=[runner], number=3)
    assert "tackling reach" not in decide(loose, 3, 11, {7: 1, 4: 2, 3: 5}).why


def test_a_ball_won_in_our_half_goes_to_a_team_mate_who_gets_it_safely_else_is_cleared():
    holder = opp(9, -30.0, 5.0)
    free = [holder, mate(8, -15.0, 20.0), opp(10, -35.0, -6.0)]
    d = decide(state((-32.0, 4.0), ball=(-30.8, 5.0), players=free, number=4), 4, 11, {4: 1, 7: 5})
    assert d.method == "pass" and "win it and pass it" in d.why
    assert (
        d.action.to.player_number == 8 and d.action.target is None
    )  # to him, where he stands when the request arrives
    marked = [holder, mate(8, -15.0, 20.0), opp(10, -16.0, 18.0), opp(11, -22.0, 12.0)]
    d = decide(state((-32.0, 4.0), ball=(-30.8, 5.0), players=marked, number=4), 4, 11, {4: 1, 7: 5})
    assert d.method == "pass" and "win it and clear it" in d.why and abs(d.action.target.y) == 25.0


def test_in_their_half_a_safe_pass_that_loses_no_ground_comes_before_a_dribble():
    players = [mate(8, 16.0, 10.0), opp(4, 22.0, 0.0), opp(5, 25.0, 12.0)]
    d = decide(state((10.0, 0.0), ball=(10.5, 0.0), players=players), 7, 11, {})
    assert d.method == "pass" and d.why == "safe pass on to team-mate 8"
    behind = [mate(8, 2.0, 5.0), opp(4, 22.0, 0.0), opp(5, 25.0, 12.0)]
    d = decide(state((10.0, 0.0), ball=(10.5, 0.0), players=behind), 7, 11, {})
    assert d.method == "dribble" and "space" in d.why  # a pass back is no better than carrying it on


def test_by_their_goal_line_out_of_range_a_safe_pass_back_to_a_team_mate_in_range_sets_up_a_shot():
    # Blue 9 carried the ball up the wing to (45, 28), 29 m from the goal; team-mate 7 waits at
    # the edge of the area, 23 m out, and nobody of theirs is near the way.
    keeper, far = opp(1, 51.0, 0.0, goalie=True), opp(4, 40.0, -8.0)
    players = [mate(7, 30.0, 7.0), mate(6, 30.0, 24.0), keeper, far, opp(5, 47.0, 30.0)]
    d = decide(state((45.0, 28.0), ball=(45.5, 28.0), players=players, number=9), 9, 11, {})
    assert d.method == "pass" and d.why == "set up a shot to team-mate 7"
    # A team-mate out of range is no set-up: the pass back to 6 only keeps the ball.
    players = [mate(6, 30.0, 24.0), keeper, far, opp(5, 47.0, 30.0)]
    d = decide(state((45.0, 28.0), ball=(45.5, 28.0), players=players, number=9), 9, 11, {})
    assert "set up" not in d.why
    # Nor one an opponent could reach first.
    players = [mate(7, 30.0, 7.0), opp(3, 37.0, 17.0), keeper, far, opp(5, 47.0, 30.0)]
    d = decide(state((45.0, 28.0), ball=(45.5, 28.0), players=players, number=9), 9, 11, {})
    assert "set up" not in d.why


def test_a_tired_player_walks_to_its_spot():
    st = state((-5.0, 20.0), ball=(30.0, 0.0), number=4)
    fresh = decide(st, 4, 11, {9: 1})
    tired = decide(st.model_copy(update={"me": st.me.model_copy(update={"stamina": 0.3})}), 4, 11, {9: 1})
    assert fresh.action.speed == 100.0 and tired.action.speed < 50.0


def test_with_a_man_in_the_way_carry_it_past_him_to_the_side():
    d = decide(state((10.0, -5.0), ball=(10.5, -5.0), players=[opp(4, 14.0, -5.5)]), 9, 11, {})
    assert d.method == "dribble" and d.action.target.y > -5.0  # round him, towards the middle


def test_a_wide_dribbler_takes_the_way_with_the_most_room_not_the_first_free_one():
    # A wide forward in their half; HELIOS base's block is 10 m on towards the goal, the wing is empty.
    block = [opp(2 + i, x, y) for i, (x, y) in enumerate(((20.0, 18.0), (21.0, 12.0), (24.0, 6.0)))]
    me = (10.0, 25.0)
    space = roomiest(free_ways(state(me, ball=(10.5, 25.0), players=block), me))
    assert space is not None and space[1] >= 24.0  # up the wing, not into the block
    # Nobody near: the straightest way, towards the goal.
    free = roomiest(free_ways(state(me, ball=(10.5, 25.0)), me))
    assert free is not None and free[1] < 25.0 - 4.0
    # A man within 2.5 m: no dribble at all.
    assert free_ways(state(me, ball=(10.5, 25.0), players=[opp(2, 11.5, 23.5)]), me) == []
    # Deep on the wing the way to goal is 37 degrees inward, and 60 off it is back: never a way.
    wing = (15.0, 28.0)
    for x, y in (w for w, _ in free_ways(state(wing, ball=(15.5, 28.0)), wing)):
        assert abs(math.degrees(math.atan2(y - wing[1], x - wing[0]))) <= WAY_OFF_UP_FIELD + 0.1
    assert len(free_ways(state(wing, ball=(15.5, 28.0)), wing)) == 4  # of five: the one 97 degrees off up


def test_forwards_wait_on_their_last_line_whoever_has_the_ball():
    players = [opp(1, 50.0, 0.0, goalie=True), opp(2, 25.0, 5.0), opp(3, 22.0, 10.0), mate(7, 0.5, 0.0)]
    d = decide(state((0.0, -16.0), ball=(0.0, 0.0), players=players, number=11), 11, 11, {7: 0})
    assert d.method == "moveTo" and d.action.target.x == 24.0 and "last line" in d.why  # the second-last: 25
    theirs = [*players[:3], opp(9, 0.5, 0.0), mate(7, -1.5, 0.0)]  # their ball: still on the line
    d = decide(state((0.0, -16.0), ball=(0.0, 0.0), players=theirs, number=11), 11, 11, {7: 1})
    assert d.method == "moveTo" and d.action.target.x == 24.0 and "last line" in d.why
    deep = [opp(1, 50.0, 0.0, goalie=True), opp(2, 45.0, 5.0), opp(3, 44.0, 10.0), *theirs[3:]]
    d = decide(state((0.0, -16.0), ball=(0.0, 0.0), players=deep, number=11), 11, 11, {7: 1})
    assert d.action.target.x == LINE_AHEAD_MAX  # a deep line: no further than this beyond the ball
    d = decide(state((-20.0, -16.0), ball=(-25.0, 0.0), players=theirs, number=11), 11, 11, {7: 1})
    assert "last line" not in d.why  # their ball deep in our half: the outlet by the touch line


def test_a_through_ball_goes_into_the_space_behind_their_last_line():
    # Their back line 7 m beyond our ball, as HELIOS base holds it; our forward 1 m onside of it.
    line = [opp(1, 50.0, 0.0, goalie=True), *(opp(n, 17.0, y) for n, y in ((2, -20.0), (3, -7.0), (4, 7.0), (5, 20.0)))]
    forward = mate(10, 16.0, 0.0)
    choice = best_pass(state((9.5, 0.0), players=[*line, forward]), (10.0, 0.0))
    assert choice.number == 10 and choice.target is not None and choice.target[0] > 17.0  # aimed behind the line
    d = decide(state((9.5, 0.0), ball=(10.0, 0.0), players=[*line, forward]), 7, 11, {})
    assert d.method == "pass" and d.action.target.x > 17.0
    # The gap closed: a man of theirs between the forward and the space: no through ball.
    shut = [*line, opp(6, 19.0, 0.0), opp(7, 19.0, -4.0), opp(8, 19.0, 4.0), forward]
    shut_choice = best_pass(state((9.5, 0.0), players=shut), (10.0, 0.0))
    assert shut_choice is None or shut_choice.at[0] <= 17.0
    # A team-mate beyond their line at the kick is offside: never the receiver.
    offside = mate(9, 22.0, 0.0)  # alone in the gap: to his feet, were he onside
    assert best_pass(state((9.5, 0.0), players=[*line, offside]), (10.0, 0.0)) is None


def test_a_clearance_goes_where_a_team_mate_gets_it_first_else_where_they_get_it_furthest_up():
    ball = (-40.0, 0.0)
    pressers = [opp(9, -34.0, 0.0), opp(10, -34.0, 6.0)]

    def first(aim, players):
        path = kicked_path(ball, aim, CLEAR_SPEED)
        ours = first_cycles(path, [Runner(where(p)) for p in players if p.which_team is Team.OUR])
        theirs = first_cycles(path, [Runner(where(p)) for p in players if p.which_team is Team.OPP])
        return ours, theirs, path

    with_mate = [*pressers, mate(2, -22.0, -20.0)]
    ours, theirs, _ = first(best_clearance(state((-40.5, 0.0), ball=ball, players=with_mate), ball)[0], with_mate)
    assert ours is not None and theirs - ours >= 2  # the free team-mate on the right wing gets it
    alone = [*pressers, opp(6, -20.0, -15.0)]
    aim, kept = best_clearance(state((-40.5, 0.0), ball=ball, players=alone), ball)
    assert not kept
    assert min(off_by(ball, aim, where(p)) for p in pressers) > 15.0  # not into a presser
    _, theirs, path = first(aim, alone)
    _, straight, straight_path = first((ball[0] + 20.0, 0.0), alone)
    assert path[theirs - 1][0] > straight_path[straight - 1][0]  # they get it further from our goal


def test_a_clearance_is_not_kept_by_a_team_mate_standing_offside():
    # In their half: their line at x 25 (the keeper and one man); our only man up the field stands
    # beyond it, and would be called offside if he went for the ball.
    ball = (10.0, 0.0)
    theirs = [opp(1, 50.0, 0.0, goalie=True), opp(4, 25.0, -10.0), opp(9, 14.0, 0.0)]
    offside = [*theirs, mate(11, 32.0, 12.0)]
    _, kept = best_clearance(state((9.5, 0.0), ball=ball, players=offside), ball)
    assert not kept
    onside = [*theirs, mate(11, 23.0, 12.0)]
    _, kept = best_clearance(state((9.5, 0.0), ball=ball, players=onside), ball)
    assert kept  # the same man a couple of metres onside gets it


def test_in_their_half_a_ball_into_space_a_team_mate_reaches_first_comes_before_a_dribble():
    players = [opp(1, 50.0, 0.0, goalie=True), opp(4, 22.0, 3.0), opp(8, 18.0, 8.0), opp(6, 12.8, -7.5)]
    # Our forward, with a man on the line to his feet, and one of theirs covering the space behind
    # their line (else it is a through ball, below).
    blocked = [*players, opp(5, 35.0, -20.0), mate(11, 20.0, -10.0)]
    assert best_pass(state((5.0, -5.0), players=blocked), (5.5, -5.0), min_gain=10.0) is None
    d = decide(state((5.0, -5.0), ball=(5.5, -5.0), players=blocked, number=9), 9, 11, {})
    assert d.method == "pass" and d.why == "kick it into space for a team-mate" and d.action.power == 100.0
    assert d.action.target.y < -12.0  # out wide, past the man, where the forward gets it first
    uncovered = [*players, mate(11, 20.0, -10.0)]
    d = decide(state((5.0, -5.0), ball=(5.5, -5.0), players=uncovered, number=9), 9, 11, {})
    assert d.method == "pass" and d.action.power is None and d.action.target.x > 22.0  # behind their line
    assert d.action.target.y < -12.0  # out wide too, past the man
    d = decide(state((5.0, -5.0), ball=(5.5, -5.0), players=players, number=9), 9, 11, {})
    assert d.method == "dribble"  # nobody of ours to reach it: carry it as before


def test_while_a_team_mate_has_the_ball_a_midfielder_stands_where_a_pass_reaches_him_first():
    ball, spot = (0.0, 0.0), home_position(6, ball_x=0.0, ball_y=0.0)  # (-15 + 0, 14)
    carrier = mate(10, 0.5, 0.0)
    # An opponent near the lane to the formation spot: a pass there is cut out.
    lane = opp(7, -7.5, 4.0)
    players = [carrier, lane, opp(1, 50.0, 0.0, goalie=True), opp(2, 20.0, 0.0)]
    d = decide(state(spot, ball=ball, players=players, number=6), 6, 11, {10: 0})
    assert d.method == "moveTo" and "open for a pass" in d.why
    target = (d.action.target.x, d.action.target.y)
    assert target == (spot[0] + 4.0, spot[1])  # of the safe spots, the furthest up, then the nearest
    path = kicked_path(ball, target, pass_speed(dist_of(ball, target)))
    mine = first_cycles(path, [Runner(target)])
    assert (
        mine is not None and (first_cycles(path, [Runner((lane.positioning.x, lane.positioning.y))]) or 99) >= mine + 2
    )
    # The same, but the lane is clear: the furthest-up safe spot, never offside.
    players = [carrier, opp(1, 50.0, 0.0, goalie=True), opp(2, 9.0, 20.0), opp(3, 10.0, -20.0)]
    d = decide(state(spot, ball=ball, players=players, number=6), 6, 11, {10: 0})
    assert d.method == "moveTo" and d.action.target.x == spot[0] + 4.0
    # At our set piece the receivers stand still, as the taker's pass model has them.
    d = decide(state(spot, ball=ball, players=players, mode=PlayMode.FREE_KICK_OUR, number=6), 6, 11, {10: 0})
    assert "open for a pass" not in d.why
    # A loose ball or theirs: the formation spot, as before.
    d = decide(state(spot, ball=(0.0, 0.0), players=[lane, opp(2, 0.5, 0.0)], number=6), 6, 11, {10: 9})
    assert "open for a pass" not in d.why


def dist_of(a, b):
    return math.hypot(a[0] - b[0], a[1] - b[1])


def test_in_our_half_a_safe_pass_that_loses_little_ground_comes_before_a_clearance():
    presser = opp(9, -20.0, 2.0)  # 10 m ahead: space, but no open run
    beside = [mate(6, -33.0, 15.0), presser]
    d = decide(state((-30.0, -5.0), ball=(-29.5, -5.0), players=beside), 4, 11, {})
    assert d.method == "pass" and d.why == "keep it: safe pass to team-mate 6"
    in_our_box = state((-38.0, -5.0), ball=(-37.5, -5.0), players=[mate(3, -42.0, 6.0), opp(9, -28.0, -2.0)])
    # Safe, but received in our penalty area: never offered (the keeper there may not catch a back pass).
    assert best_pass(in_our_box, (-37.5, -5.0)) is None
    d = decide(in_our_box, 4, 11, {})
    assert d.method == "pass" and d.why == "clear the ball"


def test_a_pass_is_never_judged_received_beyond_the_touch_line():
    # A wide forward near the touch line: a through ball 10 m ahead of him rolls on past its point
    # and would be "received" 3.6 m outside the field, gaining 13 m. Out there the ball is theirs.
    ball, wide = (3.78, 11.39), (2.77, 29.48)
    players = [mate(11, *wide), opp(2, 3.82, 9.28), opp(3, 20.12, 15.46), opp(4, 8.44, 16.11)]
    choice = best_pass(state((3.28, 11.39), ball=ball, players=players, number=10), ball)
    assert choice is not None and choice.number == 11
    target = choice.target or wide
    path = kicked_path(ball, target, pass_speed(math.dist(ball, target)))
    received = path[first_cycles(path, [Runner(wide)]) - 1]
    assert abs(received[1]) <= 34.0 and choice.gain < 10.0  # not a "forward pass" into touch


def test_a_clearance_from_the_touch_line_is_never_kicked_straight_out():
    # On the line with a team-mate beside the ball: the ways that cross the line at once are not "kept".
    ball = (-30.0, 33.8)
    players = [mate(5, -29.5, 33.4), opp(9, -25.0, 30.0)]
    aim, _ = best_clearance(state((-30.5, 33.8), ball=ball, players=players), ball)
    path = kicked_path(ball, aim, CLEAR_SPEED)
    assert abs(path[0][1]) <= 34.0  # its first cycle stays in the field
