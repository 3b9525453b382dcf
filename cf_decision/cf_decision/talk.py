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
NOT_MINE_FOR = 2  # cycles a team-mate's NOT_ME counts
READ_KEPT = 8  # says remembered as read: a perception tells one for its cycle and the next


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


class Listener:
    """What one player keeps of his team-mates' says: who said NOT_ME lately, and which says he has
    read (on rcssserver a say stays in the perception for the cycle it came and the next: each is
    read once)."""

    def __init__(self) -> None:
        self.not_mine: dict[int, int] = {}  # team-mate -> the time he last said NOT_ME
        self.read: list[tuple[int, int, str]] = []  # (number, time, text) of the latest says read

    def hear(self, state: WorldState) -> list[tuple[int, act.Pass, int]]:
        """The passes first heard in ``state``: (passer, pass, the game time it was heard)."""
        passes = []
        for heard in state.heard:
            said = (heard.player_number, heard.time, heard.message)
            if said in self.read:
                continue
            self.read = [*self.read[-(READ_KEPT - 1) :], said]
            if heard.message == NOT_ME:
                self.not_mine[heard.player_number] = heard.time
            elif (action := heard_pass(heard.message)) is not None:
                passes.append((heard.player_number, action, heard.time))
        return passes

    def not_theirs(self, now: int) -> frozenset[int]:
        """The team-mates who said NOT_ME within NOT_MINE_FOR cycles of ``now``."""
        return frozenset(n for n, t in self.not_mine.items() if now - t <= NOT_MINE_FOR)


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
