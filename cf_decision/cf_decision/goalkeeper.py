"""The goalkeeper (ROS-free): catch, clear, close down a one on one, or guard the goal."""

from __future__ import annotations

import math

from cf_lang.ontology import FIELD, WorldState
from cf_lang.ontology import actions as act

from .situation import FIELD_HALF_LENGTH, KICKABLE, OWN_GOAL, Decision, dist, opponent_on_ball, point
from .with_ball import best_clearance

KEEPER_OUT_SHARE = 0.25  # the goalkeeper stands this share of the ball's distance out of his goal,
KEEPER_OUT_MAX = 6.0  # m: at most this far
RUSH_DISTANCE = 14.0  # m from our goal: an opponent with the ball this close is closed down by the keeper


def goalkeeper(state: WorldState, me: tuple[float, float], ball: tuple[float, float] | None) -> Decision:
    """The goalkeeper's action, with the ball where he believes it (None: not seen)."""
    if ball is not None:
        d = dist(me, ball)
        in_area = (
            ball[0] < -FIELD_HALF_LENGTH + FIELD.penalty_area_length and abs(ball[1]) < FIELD.penalty_area_width / 2
        )
        if d <= KICKABLE:
            aim, _ = best_clearance(state, ball)
            return Decision("pass", act.Pass(target=point(*aim), power=100.0), "clear the ball")
        if in_area and d <= 1.2:
            direction = math.atan2(ball[1] - me[1], ball[0] - me[0]) - (state.me.positioning.yaw or 0.0)
            direction = math.atan2(math.sin(direction), math.cos(direction))
            return Decision("catch", act.Catch(direction=direction), "ball in reach")
        to_goal = dist(ball, OWN_GOAL)
        if in_area and d < 8.0:
            return Decision("intercept", act.Intercept(), "ball in the penalty area")
        if in_area and to_goal < RUSH_DISTANCE and opponent_on_ball(state, ball):
            # One on one: from the line he could not cover the goal, so close the shooter down.
            return Decision("intercept", act.Intercept(), "one on one: close the shooter down")
        # Stand on the line from the goal centre to the ball, further out the further the ball:
        # at the line a shot from 10 m passes him out of reach on either side.
        out = max(2.0, min(KEEPER_OUT_MAX, KEEPER_OUT_SHARE * to_goal))
        angle = math.atan2(ball[1] - OWN_GOAL[1], ball[0] - OWN_GOAL[0])
        spot = (OWN_GOAL[0] + out * math.cos(angle), OWN_GOAL[1] + out * math.sin(angle))
    else:
        spot = (OWN_GOAL[0] + 2.0, 0.0)
    if dist(me, spot) > 1.0:
        return Decision("moveTo", act.MoveTo(target=point(*spot), speed=80.0), "guard the goal")
    return Decision("turnToDirection", act.TurnToDirection(direction=0.0), "face the field")
