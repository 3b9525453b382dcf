"""Support play (ROS-free): where a midfielder or forward stands while a team-mate has the ball, so
that a pass can reach him before any opponent.

Against real teams the player on the ball rarely had a safe pass forward: team-mates held their
formation spots, often behind an opponent (docs/decision.md). Measured on the game logs, had each
been free to stand within 4 m of his spot, a safe pass gaining 5 m or more existed about four
times as often.
"""

from __future__ import annotations

from collections.abc import Sequence

from cf_lang.ontology import FIELD, WorldState

from . import reach
from .receive import Announced
from .situation import FIELD_HALF_LENGTH, dist, sides, xy

SUPPORT_STEP = 4.0  # m: the spots looked at lie this far around the formation spot
# The passer asks one cycle, but only his margin was measured at one (docs/performance.md, session 38).
SAFE_MARGIN = 2  # cycles: the pass reaches me this much sooner than any opponent
ROOM_CAP = 6  # cycles of room beyond which more makes no difference
STAY_BONUS = 3.0  # m up the field a spot within STAY of me is worth: no dithering between equals
STAY = 2.0  # m
GO_CYCLES = 15  # cycles after his pass that the passer runs on for the ball back
GO_AHEAD = 10.0  # m: how far on he runs, at most
GO_FROM_X = 0.0  # only after a pass from beyond this x (their half): in ours a lost return is a chance for them
OFFSETS = [(dx, dy) for dx in (SUPPORT_STEP, 0.0, -SUPPORT_STEP) for dy in (0.0, SUPPORT_STEP, -SUPPORT_STEP)]


def pass_room(
    ball: tuple[float, float],
    spot: tuple[float, float],
    opponents: list[reach.Runner],
    speed: float = reach.PLAYER_SPEED,
) -> int:
    """How many cycles before any opponent a pass to my feet at ``spot`` reaches me, running up to
    ``speed`` (capped at ROOM_CAP; negative: an opponent is first; -HORIZON: no pass there).
    """
    d = dist(ball, spot)
    if not 4.0 <= d <= 40.0:
        return -reach.HORIZON
    path = reach.in_field(reach.kicked_path(ball, spot, reach.pass_speed(d)))
    mine = reach.first_cycles(path, [reach.Runner(spot, False, speed)])
    if mine is None:
        return -reach.HORIZON
    theirs = reach.first_cycles(path[: mine + ROOM_CAP], opponents)  # later than that: room enough
    return ROOM_CAP if theirs is None else theirs - mine


def open_spot(
    state: WorldState, me: tuple[float, float], ball: tuple[float, float], base: tuple[float, float], max_x: float
) -> tuple[float, float]:
    """The spot near ``base`` (the formation's) a pass reaches safely, the furthest up the field
    (not beyond ``max_x``: onside), of equals the nearest to ``base``; ``base`` when none is safe.
    """
    opponents, speed = sides(state)[1], reach.top_speed(state.me)
    best, best_key = base, None
    for dx, dy in OFFSETS:
        spot = (
            max(-FIELD_HALF_LENGTH + 2.0, min(max_x, FIELD_HALF_LENGTH - 2.0, base[0] + dx)),
            max(-FIELD.width / 2 + 2.0, min(FIELD.width / 2 - 2.0, base[1] + dy)),
        )
        if pass_room(ball, spot, opponents, speed) < SAFE_MARGIN:
            continue
        key = (spot[0] + (STAY_BONUS if dist(me, spot) < STAY else 0.0), -dist(spot, base))
        if best_key is None or key > best_key:
            best, best_key = spot, key
    return best


def go_spot(
    state: WorldState, number: int, passes: Sequence[Announced], line: float | None
) -> tuple[float, float] | None:
    """Where I run after my pass in their half (pass and go): GO_AHEAD up the field, onside of
    ``line``, and in towards the middle, for the receiver to play the ball back ahead of me.

    None: the latest pass is not mine, or not lately, not from their half, or a long kick; or
    there is nowhere to go.

    Against HELIOS base the wide forward who carried the ball on after our kick-off was alone
    with two of theirs within 10 m when he lost it; the passer who stays put leaves the receiver
    alone the same way (docs/performance.md, session 36).
    """
    if not passes or state.me is None or state.me.positioning is None:
        return None
    last = max(passes, key=lambda p: p.kicked)
    elapsed = state.time - last.kicked
    if last.passer != number or not 0 <= elapsed <= GO_CYCLES:
        return None
    if last.ball[0] < GO_FROM_X or last.action.power is not None:
        return None
    me = xy(state.me.positioning)
    limit = FIELD_HALF_LENGTH - 6.0 if line is None else min(FIELD_HALF_LENGTH - 6.0, line - 0.5)
    spot = (min(me[0] + GO_AHEAD, limit), me[1] * 0.7)  # (beyond the line: back onside for it)
    return spot if dist(me, spot) >= 2.0 else None
