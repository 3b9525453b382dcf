"""Team talk as a competition's rules allow it (ROS-free): a pass in one short say, and who goes
for the ball judged from what the player sees rather than told.

On rcssserver the rules let team-mates talk only through the server: a ``say`` of at most 10
characters, heard within 50 m, one team-mate's message a cycle. With the decision's ``talk`` set
to ``say`` a passer says its pass (:func:`pass_word`; the back-end sends it beside the kick) and
the team-mates read it from their perception's ``:heard`` (:func:`heard_pass`); our set piece's
taker, who may not touch the ball again until another player has, says ``n`` (NOT_ME) until
then; nothing else is said. The times to the ball that team-mates would otherwise announce every
cycle are each player's own estimate from where he sees them (:func:`seen_claims`), as the base
teams do.

A word is readable text: ``p7`` passes to team-mate 7's feet; ``t0725310`` to the point
x = 072.5 - 60 = 12.5, y = 31.0 - 40 = -9.0 (decimetres, offset so that they are never
negative); ``/`` and ``0``-``9`` or ``a`` after it give the power in tens (``t0725310/a``: 100).
"""

from __future__ import annotations

from cf_lang.ontology import AbsolutePositioning, Player, Team, WorldState
from cf_lang.ontology import actions as act

from . import reach
from .situation import xy
from .without_ball import NEVER

X_OFFSET, Y_OFFSET = 60.0, 40.0  # m: a point's coordinates are sent as decimetres from -60, -40
POWERS = "0123456789a"  # a power's tens
NOT_ME = "n"  # our set piece's taker: the ball is not mine to touch until another player has touched it


def pass_word(action: act.Pass) -> str:
    """The say (at most 10 characters) that tells team-mates ``action``."""
    if action.to is not None and action.to.player_number is not None:
        word = f"p{action.to.player_number}"
    else:
        x = min(9999, max(0, round((action.target.x + X_OFFSET) * 10)))
        y = min(999, max(0, round((action.target.y + Y_OFFSET) * 10)))
        word = f"t{x:04d}{y:03d}"
    if action.power is not None:
        word += "/" + POWERS[round(action.power / 10)]
    return word


def heard_pass(text: str) -> act.Pass | None:
    """The pass a team-mate's say tells, or None (another word, or not a word of ours)."""
    text, slash, tens = text.partition("/")
    if slash and (len(tens) != 1 or tens not in POWERS):
        return None
    power = POWERS.index(tens) * 10.0 if tens else None
    try:
        if text.startswith("p") and len(text) in (2, 3):
            number = int(text[1:])
            if not 1 <= number <= 11:
                return None
            return act.Pass(to=Player(player_number=number, which_team=Team.OUR), power=power)
        if text.startswith("t") and len(text) == 8 and text[1:].isdigit():
            x, y = int(text[1:5]) / 10 - X_OFFSET, int(text[5:]) / 10 - Y_OFFSET
            return act.Pass(target=AbsolutePositioning(x=x, y=y), power=power)
    except ValueError:
        return None
    return None


def seen_claims(state: WorldState, number: int, not_theirs: frozenset[int] = frozenset()) -> dict[int, int]:
    """Team-mates' cycles to the ball (number -> cycles) as I see them: where each is believed, at
    his top speed, by the reach model every player uses for himself; never for those who said the
    ball is ``not_theirs`` (NOT_ME)."""
    ball = state.ball
    if ball is None or ball.positioning is None:
        return {}
    at, velocity = xy(ball.positioning), reach.per_cycle(ball.velocity)
    claims = {}
    for p in state.players:
        if p.which_team is Team.OUR and p.player_number not in (None, number) and p.positioning is not None:
            claims[p.player_number] = reach.cycles_to_ball(xy(p.positioning), at, velocity, reach.top_speed(p))
    return {n: NEVER if n in not_theirs else eta for n, eta in claims.items()}
