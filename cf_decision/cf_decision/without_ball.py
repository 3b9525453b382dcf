"""The players without the ball (ROS-free): who goes for it, who covers, who marks whom, and
where the others stand.
"""

from __future__ import annotations

from cf_lang.ontology import Ball, Team, WorldState
from cf_lang.ontology import actions as act

from . import reach
from .roles import Role, home_position, role_of
from .situation import OWN_GOAL, Decision, dist, point, xy

CLAIM_MARGIN = 2  # cycles: someone must be this much faster to take the ball from the current claimer
NEVER = 10**6  # cycles to the ball of a player who may not touch it
MARK_RADIUS = 15.0  # m from a defender's or midfielder's formation spot: opponents he may mark
MARK_DISTANCE = 1.5  # m goal-side of the marked opponent
TIRED = 0.45  # stamina share
MARK_BALL_X = 15.0  # mark while their ball is short of this x (deeper in their half: keep the shape)
BLOCK_DISTANCE = 3.0  # m from an opponent's ball towards our goal: where the covering player waits for it


def cycles_to_ball(
    me: tuple[float, float], ball: tuple[float, float], velocity=None, speed: float = reach.PLAYER_SPEED
) -> int:
    """Cycles until I, running up to ``speed`` (m/cycle), can have the ball, rolling as it does
    (``velocity``: the ontology's, metres per second)."""
    return reach.cycles_to_ball(me, ball, reach.per_cycle(velocity), speed)


def state_eta(state: WorldState) -> int | None:
    """My cycles to the ball in ``state`` (None: I or the ball are not known)."""
    if not (state.ball and state.ball.positioning and state.me and state.me.positioning):
        return None
    me, ball = xy(state.me.positioning), xy(state.ball.positioning)
    return cycles_to_ball(me, ball, state.ball.velocity, reach.top_speed(state.me))


def choose_interceptor(my_number: int, my_eta: int, claims: dict[int, int]) -> bool:
    """Whether I go for the ball, given team-mates' times to the ball (number -> cycles)."""
    best = min([(eta, n) for n, eta in claims.items() if n != my_number], default=None)
    if best is None:
        return True
    eta, number = best
    return my_eta + (0 if my_eta < eta else CLAIM_MARGIN) < eta or (my_eta == eta and my_number < number)


def second_fastest(my_number: int, my_eta: int, claims: dict[int, int]) -> bool:
    """Whether exactly one team-mate is faster to the ball than I am (ties to the lower number)."""
    ahead = sum(1 for n, eta in claims.items() if n != my_number and (eta, n) < (my_eta, my_number))
    return ahead == 1


def marking(state: WorldState, team_size: int, ball: tuple[float, float]) -> dict[int, tuple[float, float]]:
    """Which opponent each defender and midfielder marks (number -> the opponent's position).

    The pairs nearest each other go first (a player's formation spot to an opponent, within
    MARK_RADIUS); the opponent on the ball is left to those who go for it. Every team-mate
    computes the same from what he sees, so nobody needs to be told.
    """
    opponents = [
        xy(p.positioning)
        for p in state.players
        if p.which_team is Team.OPP and p.positioning and not p.is_goalie and dist(xy(p.positioning), ball) > 3.0
    ]
    pairs = []
    for n in range(2, team_size + 1):
        if role_of(n, team_size) not in (Role.DEFENDER, Role.MIDFIELDER):
            continue
        home = home_position(n, team_size, ball_x=ball[0], ball_y=ball[1])
        pairs += [(dist(home, o), n, i) for i, o in enumerate(opponents) if dist(home, o) < MARK_RADIUS]
    out, taken = {}, set()
    for _, n, i in sorted(pairs):
        if n not in out and i not in taken:
            out[n] = opponents[i]
            taken.add(i)
    return out


def goal_side(mark: tuple[float, float]) -> tuple[float, float]:
    """Where to stand to mark an opponent: MARK_DISTANCE from him towards our goal."""
    d = dist(mark, OWN_GOAL) or 1.0
    return (
        mark[0] + (OWN_GOAL[0] - mark[0]) * MARK_DISTANCE / d,
        mark[1] + (OWN_GOAL[1] - mark[1]) * MARK_DISTANCE / d,
    )


def block(me: tuple[float, float], ball: tuple[float, float], why: str, tired: bool = False) -> Decision:
    """Stand BLOCK_DISTANCE from an opponent's ball on its way to our goal, facing it.

    A chaser from behind never gets the ball in front of his body, where a tackle reaches; a
    player in the dribbler's way does, when the dribbler comes within tackling reach of him.
    """
    d = dist(ball, OWN_GOAL) or 1.0
    k = min(BLOCK_DISTANCE, d / 2) / d
    spot = (ball[0] + (OWN_GOAL[0] - ball[0]) * k, ball[1] + (OWN_GOAL[1] - ball[1]) * k)
    return hold(me, spot, why, 1.0, tired, hurry=True)


def tired(state: WorldState) -> bool:
    """Below TIRED of its stamina a player walks to its spot: under rcssserver's 30 % it recovers slower for good."""
    return state.me is not None and state.me.stamina is not None and state.me.stamina < TIRED


def hold(
    me: tuple[float, float],
    spot: tuple[float, float],
    why: str,
    slack: float = 3.0,
    tired: bool = False,
    hurry: bool = False,
) -> Decision:
    """Go to ``spot`` (fast when far or in a ``hurry``, unless ``tired``), or, within ``slack`` of it, watch the ball."""
    d = dist(me, spot)
    if d > slack:
        speed = 40.0 if tired else 100.0 if hurry or d > 8.0 else 70.0
        return Decision("moveTo", act.MoveTo(target=point(*spot), speed=speed), why)
    return Decision("turnToObject", act.TurnToObject(obj=Ball()), why + ", watch the ball")
