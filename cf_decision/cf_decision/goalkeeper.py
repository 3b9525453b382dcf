"""The goalkeeper (ROS-free): catch, clear, close down a one on one, or guard the goal."""

from __future__ import annotations

import math

from cf_lang.ontology import FIELD, PlayMode, Team, WorldState
from cf_lang.ontology import actions as act

from . import reach
from .set_piece import OUR_SET_PIECES
from .situation import (
    KICKABLE,
    OWN_GOAL,
    Decision,
    dist,
    guard_spot,
    nearest_of_each_side,
    opponent_on_ball,
    play_mode,
    point,
)
from .with_ball import best_clearance, in_our_box, set_piece_kick

KEEPER_SLACK = 0.7  # m from his guard spot within which he stays (the moveTo skill's own tolerance)
RUSH_DISTANCE = 14.0  # m from our goal: an opponent with the ball this close is closed down by the keeper
CATCH_REACH = 1.2  # m: rcssserver's catchable_area_l
# rcssserver bounds a catch's direction to 90 degrees either side of the body (min/max_catch_angle):
# a ball further round cannot be caught. Against HELIOS base two of seven goals came through such
# catches, asked for at 128 and 169 degrees, with the ball within his reach (session 66).
CATCH_ANGLE = math.radians(90.0)
MATE_NEAR = 3.0  # m: a team-mate this close to the ball, and nearer than any opponent, may have played it
SHOT_PACE = 1.0  # m/cycle: a ball at least this fast, rolling into our goal, is a shot
POST_MARGIN = 1.0  # m outside a post: a ball rolling that close by it is a shot all the same (noise)


def goalkeeper(
    state: WorldState, me: tuple[float, float], ball: tuple[float, float] | None, mate_touched: bool = False
) -> Decision:
    """The goalkeeper's action, with the ball where he believes it (None: not seen); ``mate_touched``:
    a team-mate touched it last, as far as he can tell (:mod:`touch`)."""
    if ball is not None:
        d = dist(me, ball)
        in_area = in_our_box(ball)
        mode = play_mode(state)
        may_catch = in_area and mode is PlayMode.PLAY_ON and not mate_touched and not mates_ball(state, ball)
        off = off_body(state, me, ball)
        if may_catch and d <= CATCH_REACH and abs(off) <= CATCH_ANGLE:
            # Caught, the ball is ours at a free kick; cleared in a hurry under pressure, it was lost:
            # 9 of HELIOS base's 47 goals in seven matches followed (docs/performance.md, session 32).
            return catch(off)
        if d <= KICKABLE:
            if mode in OUR_SET_PIECES:  # after a catch, or a goal kick: look, then pass or kick long
                return set_piece_kick(state, me)
            aim, _ = best_clearance(state, ball)
            return Decision("pass", act.Pass(target=point(*aim), power=100.0), "clear the ball")
        if mode is PlayMode.PLAY_ON and shot_at_our_goal(state, ball):
            # Of 78 goals HELIOS base scored in 18 matches he could have had 12 as he stood, setting off
            # as the shot was struck, 4 a cycle later (tools/rcss_keeper.py, docs/performance.md, session
            # 53); he had kept to his spot until the ball was within 8 m.
            return Decision("intercept", act.Intercept(), "a shot at our goal")
        to_goal = dist(ball, OWN_GOAL)
        if in_area and d < 8.0:
            return Decision("intercept", act.Intercept(), "ball in the penalty area")
        if in_area and to_goal < RUSH_DISTANCE and opponent_on_ball(state, ball):
            # One on one: from the line he could not cover the goal, so close the shooter down.
            return Decision("intercept", act.Intercept(), "one on one: close the shooter down")
        spot = guard_spot(ball)
    else:
        spot = (OWN_GOAL[0] + 2.0, 0.0)
    if dist(me, spot) > KEEPER_SLACK:
        # With a metre's slack, at 80% of his pace, he stood a median 0.8 m off the spot at HELIOS base's
        # shots on target, and the spot reached 57 of 132 where he reached 44 (tools/rcss_keeper.py,
        # docs/performance.md, session 39).
        return Decision("moveTo", act.MoveTo(target=point(*spot), speed=100.0), "guard the goal")
    return Decision("turnToDirection", act.TurnToDirection(direction=0.0), "face the field")


def shot_at_our_goal(state: WorldState, ball: tuple[float, float]) -> bool:
    """The ball rolls into our goal (between the posts, or within POST_MARGIN of one) at SHOT_PACE
    or faster, as he believes it."""
    velocity = reach.per_cycle(state.ball.velocity if state.ball else None)
    if math.hypot(*velocity) < SHOT_PACE or velocity[0] >= 0.0:
        return False
    return into_our_goal(reach.ball_path(ball, velocity), POST_MARGIN) is not None


def into_our_goal(path: list[tuple[float, float]], margin: float = 0.0) -> int | None:
    """The index of the first point of ``path`` on or beyond our goal line if it is between the posts
    (or within ``margin`` outside one); None: the path stops short of the line or crosses it wide."""
    n = next((n for n, (x, _) in enumerate(path) if x <= OWN_GOAL[0]), None)
    if n is None or abs(path[n][1] - OWN_GOAL[1]) > FIELD.goal_width / 2 + margin:
        return None
    return n


def off_body(state: WorldState, me: tuple[float, float], ball: tuple[float, float]) -> float:
    """The ball's direction from ``me``, in radians off the way the body faces (-pi..pi)."""
    direction = math.atan2(ball[1] - me[1], ball[0] - me[0]) - (state.me.positioning.yaw or 0.0)
    return math.atan2(math.sin(direction), math.cos(direction))


def catch(direction: float) -> Decision:
    """Catch the ball ``direction`` radians off the way the body faces (:func:`off_body`)."""
    return Decision("catch", act.Catch(direction=direction), "ball in reach")


def mates_ball(state: WorldState, ball: tuple[float, float]) -> bool:
    """A team-mate may have played the ball last: he is within MATE_NEAR of it and nearer than any
    opponent. The keeper may not catch a ball a team-mate kicked to him (rcssserver's back_pass:
    an indirect free kick to the opponents in our penalty area)."""
    nearest = nearest_of_each_side(state, ball)
    mate = nearest.get(Team.OUR, math.inf)
    return mate <= MATE_NEAR and mate < nearest.get(Team.OPP, math.inf)
