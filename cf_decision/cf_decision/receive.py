"""A pass a team-mate announced (ROS-free): which of us meets it, and where.

The passer's decision tells its team-mates' decisions the pass it asked for, the moment it asks
for it (an inform whose content is the same ``(exec Player pass ...)``). Without that, a receiver
set off only once his own perception showed the ball rolling and the passer's claim on it had
lapsed: 3-4 cycles after the kick on rcssserver, where the real teams' receivers set off after 1-2
(docs/performance.md, session 24).
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass

from cf_lang.ontology import PlayMode, WorldState
from cf_lang.ontology import actions as act

from . import reach
from .situation import KICKABLE, Decision, dist, play_mode, sides, xy
from .with_ball import CLEAR_SPEED

AWAIT_MAX = 20  # cycles after its kick that a pass is awaited at most
ROLLING = 0.5  # m/cycle: a ball seen this fast is on its way (a dribbler's touch is slower)
SEEN_AGE = 1  # cycles: a ball seen this lately moves as it was seen to

Point = tuple[float, float]


@dataclass(frozen=True)
class Announced:
    """A team-mate's pass request as heard: who asked, the action, where the ball was (as the
    hearer believed), the game time it is taken to leave the foot (the cycle after it was asked
    for: the earliest the action kicks it), and which of us stood offside then (as the hearer
    believed: :func:`situation.offside_mates`)."""

    passer: int
    action: act.Pass
    ball: Point
    kicked: int
    offside: frozenset[int] = frozenset()


def to_announce(state: WorldState, decision: Decision) -> bool:
    """Whether team-mates are told of ``decision``: a pass asked for in play with the ball at my
    feet, so about to be kicked (not a ball still to be won, nor a set piece's)."""
    me, ball = state.me, state.ball
    if not isinstance(decision.action, act.Pass) or play_mode(state) is not PlayMode.PLAY_ON:
        return False
    if not (me and me.positioning and ball and ball.positioning):
        return False
    return dist(xy(me.positioning), xy(ball.positioning)) <= KICKABLE


def pass_path(pass_: Announced, my_pos: Point) -> list[Point] | None:
    """The path the ball is foreseen to take: to my feet (``:to``, which is me) or to its target."""
    target = my_pos if pass_.action.to is not None else xy(pass_.action.target)
    d = dist(pass_.ball, target)
    if d < 1.0:
        return None
    power = pass_.action.power
    speed = reach.pass_speed(d) if power is None else CLEAR_SPEED * power / 100.0
    return reach.kicked_path(pass_.ball, target, speed)


def rolling(state: WorldState) -> list[Point] | None:
    """The ball's path as I see it now, if I saw it just now and it rolls at ROLLING or faster."""
    ball = state.ball
    if ball is None or ball.positioning is None or ball.velocity is None:
        return None
    if ball.age is not None and ball.age > SEEN_AGE:
        return None
    velocity = reach.per_cycle(ball.velocity)
    if math.hypot(*velocity) < ROLLING:
        return None
    return reach.ball_path(xy(ball.positioning), velocity)


def meeting(state: WorldState, number: int, passes: Sequence[Announced]) -> tuple[Point, int] | None:
    """Where I meet the latest pass a team-mate announced, and in how many cycles, if it is mine to meet.

    Mine: passed to me, or, passed to a point, I am the team-mate who reaches its path first (as I
    believe: the passer and those offside when it was heard left out, ties to the lower number,
    as the passer chose). The ball is taken to roll from its
    kick as the pass was asked for, and, once I have seen it rolling (:func:`rolling`), as I see
    it. None once it has rolled past my reach, or AWAIT_MAX cycles after its kick.
    """
    if not passes or state.me is None or state.me.positioning is None:
        return None
    pass_ = max(passes, key=lambda p: p.kicked)
    elapsed = state.time - pass_.kicked
    # (Heard in the cycle it was asked for, its kick is a cycle ahead; a little more: clocks differ.)
    if not -2 <= elapsed <= AWAIT_MAX or pass_.passer == number:
        return None
    to = pass_.action.to.player_number if pass_.action.to is not None else None
    if to is not None and to != number:
        return None
    if to is None and number in pass_.offside:
        return None  # (a ball played to me by name is mine: the passer saw me onside)
    me = xy(state.me.positioning)
    path = pass_path(pass_, me)
    if path is None or elapsed >= len(path):
        return None
    rest = path[max(0, elapsed) :]
    seen = rolling(state) if elapsed > 0 else None
    if seen is not None:
        # Once I see it rolling, the ball goes where it was kicked, not where it was meant to go:
        # receivers kept waiting on the pass's foreseen line 3 m from where the ball rolled by, and
        # lost it (docs/performance.md, session 31).
        rest = seen
    react = reach.TURN_CYCLES if elapsed <= 0 else 0  # once it rolls: on my way already
    mine = reach.cycles_to_path(me, rest, react=react, speed=reach.top_speed(state.me))
    if mine is None:
        return None
    if to is None:
        mates = [(n, runner) for n, runner in sides(state)[0] if n != pass_.passer and n not in pass_.offside]
        others = ((reach.cycles_to_path(r.pos, rest, react=react, speed=r.speed), n) for n, r in mates)
        if any(c is not None and (c, n) < (mine, number) for c, n in others):
            return None
    return rest[mine - 1], mine
