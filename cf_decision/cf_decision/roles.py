"""Roles and the formation: where each player stands, shifting with the ball (ROS-free).

Positions are in the player's own frame (x towards the opponents' goal).
"""

from __future__ import annotations

import math

from cf_lang.ontology import Role

# 4-3-3 for eleven; smaller teams take the first n entries of this order.
_FORMATION: dict[int, tuple[Role, float, float]] = {
    1: (Role.GOALKEEPER, -50.0, 0.0),
    2: (Role.DEFENDER, -32.0, 16.0),
    3: (Role.DEFENDER, -35.0, 5.0),
    4: (Role.DEFENDER, -35.0, -5.0),
    5: (Role.DEFENDER, -32.0, -16.0),
    6: (Role.MIDFIELDER, -15.0, 14.0),
    7: (Role.MIDFIELDER, -18.0, 0.0),
    8: (Role.MIDFIELDER, -15.0, -14.0),
    9: (Role.FORWARD, 2.0, 16.0),
    10: (Role.FORWARD, 5.0, 0.0),
    11: (Role.FORWARD, 2.0, -16.0),
}
UP_SHIFT = {Role.DEFENDER: 1.0, Role.MIDFIELDER: 1.0, Role.FORWARD: 1.0}  # per m of the ball in their half
# The block leans to the ball's wing: with 0.25 a wide forward on the ball by the touch line had
# his nearest team-mate 14-24 m away and four or five of HELIOS base's men within 17 m (session 50).
LATERAL_PULL = 0.45  # m across per m of the ball off the middle
OUTLET_BALL_X = -20.0  # m: with the ball nearer our goal than this, the wide forwards
OUTLET = (-13.0, 26.0)  # drop to here
LINE_BEHIND_BALL = 10.0  # m: our back line holds at most this far behind the ball,
LINE_DEEPEST = -45.0  # m: but never deeper than this,
LINE_HIGHEST = -20.0  # m: nor, from the ball's pull, higher than this
KICK_OFF_WING = 31.0  # m from the middle: where the wide forwards wait for a kick-off
KICK_OFF_MIDFIELD = (-3.0, -8.0)  # x of the wide midfielders and the central one at our kick-off
# For small teams: goalkeeper, then a forward, a defender, a midfielder, ...
_SMALL_ORDER = [1, 10, 3, 7, 9, 4, 8, 11, 2, 6, 5]


def _slot(number: int, team_size: int) -> int:
    if team_size >= 11:
        return number
    return _SMALL_ORDER[(number - 1) % 11]


def role_of(number: int, team_size: int = 11) -> Role:
    return _FORMATION[_slot(number, team_size)][0]


def home_position(
    number: int, team_size: int = 11, *, ball_x: float = 0.0, ball_y: float = 0.0, offside_x: float | None = None
) -> tuple[float, float]:
    """Formation position, pulled towards the ball: the block moves up and down the field with it
    and leans to its wing (LATERAL_PULL).

    Forwards never drop deeper than just behind the halfway line (an outlet when we win the ball),
    but for the wide forwards' OUTLET by the touch lines while the ball is deep in our half, and
    stay a metre onside of ``offside_x`` (the opponents' offside line), as midfielders do.
    Defenders hold our line: never deeper than :func:`back_line`.
    """
    role, x, y = _FORMATION[_slot(number, team_size)]
    if role is Role.GOALKEEPER:
        return (x, 0.0)
    if role is Role.FORWARD and y != 0.0 and ball_x < OUTLET_BALL_X:
        # The ball deep in our half: a base team's men are round it and its back line near the
        # halfway line; between the two, by the touch lines, a team-mate would have been open at a
        # quarter to two fifths of our kicks from our third (docs/performance.md, session 45).
        return (OUTLET[0], math.copysign(OUTLET[1], y))
    # In their half the block follows the ball closer: with the ball 40 m up, midfielders 35 m
    # behind it left a wide forward alone against eight men (HELIOS base, session 23).
    shift = 0.55 * min(ball_x, 0.0) + UP_SHIFT[role] * max(ball_x, 0.0)
    limit = {Role.DEFENDER: (-45.0, 20.0), Role.MIDFIELDER: (-35.0, 35.0), Role.FORWARD: (-5.0, 45.0)}[role]
    hx = max(limit[0], min(limit[1], x + shift))
    if role is Role.DEFENDER:
        # With the ball 20 m into our half the back four stood 7-10 m from our goal line, and HELIOS
        # base's forwards came as near; held up, it shot a quarter less (docs/performance.md, session 46).
        hx = max(hx, back_line(ball_x))
    if offside_x is not None and role is not Role.DEFENDER:
        hx = min(hx, max(0.0, offside_x - 1.0))
    hy = y + LATERAL_PULL * ball_y
    return (hx, max(-30.0, min(30.0, hy)))


def back_line(ball_x: float) -> float:
    """The deepest x a defender takes, as home spot or as marker, while the ball is at ``ball_x``: the
    offside line we hold (a man of theirs beyond it is left offside)."""
    return max(LINE_DEEPEST, min(ball_x - LINE_BEHIND_BALL, LINE_HIGHEST))


def kick_off_position(number: int, team_size: int = 11) -> tuple[float, float]:
    """Where a player stands for a kick-off: the formation in our half, the wide forwards out wide by
    the touch lines, the midfielders near the halfway line.

    A base team packs its kick-off into the middle (HELIOS base: ten men within 10 m of it), so a
    forward waiting near the side line can be found with a pass into the space in front of him.
    From 26 m out he was met 15-20 m into their half; from 31 m, with the midfield 12 m nearer,
    three in five of our kick-offs reached their third, not one in four (docs/performance.md, session 47).
    """
    x, y = home_position(number, team_size, ball_x=0.0)
    role = role_of(number, team_size)
    if role is Role.FORWARD and y != 0.0:
        y = math.copysign(KICK_OFF_WING, y)
    if role is Role.MIDFIELDER:
        x = KICK_OFF_MIDFIELD[0] if y != 0.0 else KICK_OFF_MIDFIELD[1]
    return (min(x, -1.0), y)
