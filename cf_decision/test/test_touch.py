"""Which side touched the ball last, as a player can tell."""

from __future__ import annotations

from cf_decision.touch import OFFSIDE_MEMORY, LastTouch
from cf_lang.ontology import AbsolutePositioning, Ball, Game, Player, PlayMode, Team, Velocity, WorldState


def seen(ball, players, ball_age=0, time=10, velocity=None):
    return WorldState(
        time=time,
        ball=Ball(
            positioning=AbsolutePositioning(x=ball[0], y=ball[1]),
            velocity=Velocity(vx=10.0 * velocity[0], vy=10.0 * velocity[1]) if velocity else None,
            age=ball_age,
        ),
        players=tuple(
            Player(player_number=n, which_team=team, positioning=AbsolutePositioning(x=x, y=y), age=age)
            for n, team, x, y, age in players
        ),
        game=Game(time=10),
    )


def test_the_side_whose_men_alone_are_at_the_ball_touched_it_last():
    touch = LastTouch()
    assert touch.team is None
    touch.seen(seen((-39.0, 1.0), [(4, Team.OUR, -39.4, 1.0, 0), (11, Team.OPP, -36.0, 1.0, 0)]))
    assert touch.team is Team.OUR  # our defender at the ball, their forward 3 m off
    touch.seen(seen((-45.0, 1.0), [(4, Team.OUR, -38.0, 1.0, 0)]))
    assert touch.team is Team.OUR  # rolling on towards our goal, nobody at it: still ours
    touch.seen(seen((-44.0, 1.0), [(4, Team.OUR, -43.5, 1.0, 0), (9, Team.OPP, -44.5, 1.0, 0)]))
    assert touch.team is Team.OUR  # both sides as near: cannot tell, the last known stands
    touch.seen(seen((-44.0, 1.0), [(4, Team.OUR, -43.0, 1.0, 0), (9, Team.OPP, -44.7, 1.0, 0)]))
    assert touch.team is Team.OPP  # both at it, theirs clearly nearer: his
    touch.played_by_mate()
    touch.seen(seen((-44.0, 1.0), [(9, Team.OPP, -44.5, 1.0, 3)]))
    assert touch.team is Team.OUR  # an opponent seen 3 cycles ago does not count
    touch.seen(seen((-44.0, 1.0), [(9, Team.OPP, -44.5, 1.0, 0)], ball_age=4))
    assert touch.team is Team.OUR  # nor does a ball not seen lately
    touch.seen(seen((-44.0, 1.0), [(9, Team.OPP, -44.5, 1.0, 1)]))
    assert touch.team is Team.OPP
    touch.played_by_mate()  # a team-mate announced his pass
    assert touch.team is Team.OUR


def test_a_ball_rolling_on_its_course_past_a_team_mate_was_not_touched_by_him():
    touch = LastTouch()
    shooter = [(9, Team.OPP, -35.5, 0.0, 0)]
    touch.seen(seen((-35.0, 0.0), shooter, time=1, velocity=(-2.5, 0.0)))
    assert touch.team is Team.OPP
    # Two cycles on it passes our defender a metre off, as fast and where rolling on puts it: still theirs.
    by = [(4, Team.OUR, -39.9, 1.0, 0)]
    touch.seen(seen((-35.0 - 2.5 - 2.35, 0.1), by, time=3, velocity=(-2.21, 0.0)))
    assert touch.team is Team.OPP
    # He turned it: off its course and slowed, his.
    touch.seen(seen((-41.0, 1.5), [(4, Team.OUR, -40.5, 1.0, 0)], time=4, velocity=(-0.5, 1.0)))
    assert touch.team is Team.OUR
    # A ball still by a man may be at his feet: no course to follow.
    touch = LastTouch()
    touch.seen(seen((-40.0, 0.0), shooter, time=1, velocity=(0.0, 0.0)))
    touch.seen(seen((-40.0, 0.0), [(4, Team.OUR, -40.5, 0.0, 0)], time=2, velocity=(0.0, 0.0)))
    assert touch.team is Team.OUR


def as_nine(me, ball, players, time=10, mode=PlayMode.PLAY_ON):
    """What our number 9 at ``me`` sees: their keeper, and one of theirs at x 25 (their line)."""
    st = seen(ball, [(1, Team.OPP, 50.0, 0.0, 0), (4, Team.OPP, 25.0, -8.0, 0), *players], time=time)
    me_ = Player(player_number=9, which_team=Team.OUR, positioning=AbsolutePositioning(x=me[0], y=me[1]))
    return st.model_copy(update={"me": me_, "game": Game(time=time, play_mode=mode)})


def test_a_player_offside_at_a_team_mates_touch_may_not_play_the_ball_until_somebody_else_touches_it():
    touch = LastTouch()
    dribbler = [(8, Team.OUR, 19.6, 5.0, 0)]
    touch.seen(as_nine((30.0, 0.0), (20.0, 5.0), dribbler, time=10))  # a team-mate at the ball, I 5 m beyond their line
    assert touch.team is Team.OUR and touch.offside(10) and touch.offside(10 + OFFSIDE_MEMORY)
    assert not touch.offside(11 + OFFSIDE_MEMORY)  # a touch nobody followed is not kept for ever
    # The ball comes my way: still not mine until somebody else has touched it.
    touch.seen(as_nine((29.0, 0.0), (27.0, 3.0), [], time=14))
    assert touch.offside(14)
    touch.seen(as_nine((29.0, 0.0), (27.0, 3.0), [(4, Team.OPP, 27.3, 3.0, 0)], time=15))
    assert touch.team is Team.OPP and not touch.offside(15)  # theirs now: play on
    # An opponent believed at the ball has it, though neither he nor the ball was seen lately.
    touch.seen(as_nine((30.0, 0.0), (20.0, 5.0), dribbler, time=16))
    assert touch.offside(16)
    stale = as_nine((30.0, 0.0), (27.0, 3.0), [(4, Team.OPP, 27.5, 3.5, 6)], time=17)
    touch.seen(stale.model_copy(update={"ball": stale.ball.model_copy(update={"age": 5})}))
    assert not touch.offside(17)
    # Not while one of ours is as near it (our dribbler, pressed).
    touch.seen(as_nine((30.0, 0.0), (20.0, 5.0), dribbler, time=18))
    pressed = as_nine((30.0, 0.0), (20.0, 5.0), [*dribbler, (4, Team.OPP, 20.5, 5.5, 6)], time=19)
    touch.seen(pressed.model_copy(update={"ball": pressed.ball.model_copy(update={"age": 5})}))
    assert touch.offside(19)
    # Onside at the team-mate's touch: free to play it.
    touch.seen(as_nine((24.0, 0.0), (20.0, 5.0), dribbler, time=20))
    assert touch.team is Team.OUR and not touch.offside(20)
    # At the ball 0.7 m beyond it (their line is the ball's x there), with a team-mate a metre
    # behind it: nearer than him, the touch is mine; further, his.
    touch.seen(as_nine((27.7, 3.0), (27.0, 3.0), [(10, Team.OUR, 26.0, 3.0, 0)], time=25))
    assert touch.team is Team.OUR and not touch.offside(25)
    touch.seen(as_nine((27.7, 3.0), (27.0, 3.0), [(10, Team.OUR, 26.6, 3.0, 0)], time=26))
    assert touch.offside(26)
    # A pass announced while I stood offside bars me too; any stoppage ends it.
    touch.played_by_mate(offside_at=30)
    assert touch.team is Team.OUR and touch.offside(31)
    touch.seen(as_nine((30.0, 0.0), (27.0, 3.0), [], time=32, mode=PlayMode.FREE_KICK_OPP))
    assert not touch.offside(32)
