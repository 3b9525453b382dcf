"""Which decision goes out as a request, and what its answer means (ROS-free).

The action component runs one request at a time: a newer request replaces the
current one, and the replaced one is answered ``failure``. So an answer only
matters when it belongs to the request in force; and a decision that is the
same as the one in force (within the tolerances of :func:`same_action`) is not
sent again while that request runs.
"""

from __future__ import annotations

import math
import re
from collections import Counter
from dataclasses import dataclass, field

from pydantic import BaseModel

from cf_lang.ontology import AbsolutePositioning, Team, WorldState

from .receive import AWAIT_MAX, Announced
from .situation import Decision, dist, offside_line, xy

POSITION_TOLERANCE = 1.0  # m: targets closer than this are one target (a player is ~0.6 m wide)
ANGLE_TOLERANCE = 0.1  # rad (about 6 degrees)
SCALAR_TOLERANCE = 5.0  # power and speed, on their 0..100 scale
_ANGLES = {"angle", "direction", "yaw"}


def _same_value(name: str, a: object, b: object) -> bool:
    if isinstance(a, AbsolutePositioning) and isinstance(b, AbsolutePositioning):
        return math.hypot(a.x - b.x, a.y - b.y) <= POSITION_TOLERANCE and _same_value("yaw", a.yaw, b.yaw)
    if isinstance(a, BaseModel) and isinstance(b, BaseModel):
        return same_action(a, b)
    if isinstance(a, float | int) and isinstance(b, float | int) and not isinstance(a, bool | type(None)):
        if name in _ANGLES:
            diff = (a - b + math.pi) % (2 * math.pi) - math.pi
            return abs(diff) <= ANGLE_TOLERANCE
        return abs(a - b) <= SCALAR_TOLERANCE
    return a == b


def same_action(a: BaseModel, b: BaseModel) -> bool:
    """Whether two ontology actions ask for the same thing, within the tolerances above."""
    if type(a) is not type(b):
        return False
    return all(_same_value(name, getattr(a, name), getattr(b, name)) for name in type(a).model_fields)


def same_request(a: tuple[str, BaseModel] | None, b: tuple[str, BaseModel]) -> bool:
    """Whether two (method, action) pairs ask for the same thing."""
    return a is not None and a[0] == b[0] and same_action(a[1], b[1])


@dataclass
class RequestStats:
    cycles: int = 0  # decisions taken
    missed: int = 0  # cycles of the game whose perception never came (the decision was not run)
    requests: int = 0  # requests sent
    resends: int = 0  # requests for the same action as the one before (its request had ended)
    done: int = 0
    failed: int = 0  # the request in force failed or was refused
    replaced: int = 0  # answers to requests we had replaced already (ignored)
    from_mates: int = 0  # players' positions taken from what team-mates told they saw (shared.py)
    choices: Counter = field(default_factory=Counter)  # why the ball was played as it was, by reason

    def chose(self, why: str) -> None:
        """Count a choice with the ball under its reason without the numbers ("safe pass to team-mate")."""
        bare = re.sub(r"(?<![\w-])-?\d+(\.\d+)?", "", re.sub(r"\([^)]*\)", "", why))
        self.choices[re.sub(r"\s+([:,])", r"\1", " ".join(bare.split()))] += 1

    def line(self) -> str:
        per = self.requests / max(1, self.cycles)
        played = ", ".join(f"{why} {n}" for why, n in self.choices.most_common())
        return (
            f"{self.cycles} cycles ({self.missed} missed), {self.requests} requests ({per:.2f} per cycle), {self.resends} re-sends,"
            f" {self.done} done, {self.failed} failed, {self.replaced} answers to replaced requests,"
            f" {self.from_mates} positions from team-mates" + (f"; with the ball: {played}" if played else "")
        )


@dataclass
class ActionRequests:
    """The request in force for one player, and the rule for sending the next."""

    current: tuple[str, BaseModel] | None = None  # (method, action) of the last request sent
    token: object = None  # what identifies that request (the runtime's future)
    running: bool = False  # it is in force: not answered yet
    stats: RequestStats = field(default_factory=RequestStats)

    def wants(self, method: str, action: BaseModel) -> bool:
        """Whether this cycle's decision must go out as a request."""
        self.stats.cycles += 1
        return not (self.running and same_request(self.current, (method, action)))

    def sent(self, method: str, action: BaseModel, token: object) -> None:
        if same_request(self.current, (method, action)):
            self.stats.resends += 1
        self.current = (method, action)
        self.token, self.running = token, True
        self.stats.requests += 1

    def answered(self, token: object, ok: bool) -> None:
        """The final answer to a request; one to a request we replaced since is ignored."""
        if token is not self.token:
            self.stats.replaced += 1
            return
        self.running = False
        if ok:
            self.stats.done += 1
        else:
            self.stats.failed += 1


AIM_OPPONENTS_WITHIN = 30.0  # m from the ball: the opponents a kick's log line lists


def choice_text(state: WorldState, decision: Decision) -> str:
    """The line a decision logs for each new way of playing the ball: ``t=T method: why @ ...``
    (what tools/rcss_ball_use.py reads back, on either back-end)."""
    return f"t={state.time} {decision.method}: {decision.why}{aim_text(state, decision)}"


def aim_text(state: WorldState, decision: Decision) -> str:
    """`` @ target X Y ball X Y opp X Y S, ...`` (own frame, as believed; S: the position's standard
    deviation, which grows while a player goes unseen): set against the game log, it tells a kick
    that went astray from a choice made on a wrong picture. Empty without a target point."""
    target = getattr(decision.action, "target", None)
    ball = state.ball.positioning if state.ball else None
    if target is None or ball is None:
        return ""
    seen = [
        f"{p.positioning.x:.1f} {p.positioning.y:.1f} {p.positioning.sigma_x or 0.0:.1f}"
        for p in state.players
        if p.which_team is Team.OPP and p.positioning and dist(xy(p.positioning), xy(ball)) <= AIM_OPPONENTS_WITHIN
    ]
    return f" @ target {target.x:.1f} {target.y:.1f} ball {ball.x:.1f} {ball.y:.1f} opp {', '.join(seen)}"


def request_text(
    state: WorldState, decision: Decision, claims: dict[int, int], passes: list[Announced], content: str
) -> str:
    """One line for a new request (``log_requests``): ``request t=T method: why | me X Y | ball X Y
    v VX VY age A | line X | claims N:ETA ... | passes P>R@T ... | (exec ...)``.

    Everything the choice was made on that a match analysis cannot read back from the game log:
    where the player believed himself and the ball, their offside line as he believed it
    (:func:`situation.offside_line`), the team-mates' claims on the ball (``N:ETA``,
    cycles) and the passes they announced that may still be awaited (to team-mate R, or ``pt`` for
    a point; ``@T``: the cycle the ball is taken to leave the foot), then the very request sent.
    """
    me = state.me.positioning if state.me else None
    ball = state.ball
    parts = [f"request t={state.time} {decision.method}: {decision.why}"]
    parts.append(f"me {_m(me.x)} {_m(me.y)}" if me else "me ?")
    if ball is not None and ball.positioning is not None:
        v = ball.velocity
        speed = f" v {_m(v.vx)} {_m(v.vy)}" if v else ""
        parts.append(f"ball {_m(ball.positioning.x)} {_m(ball.positioning.y)}{speed} age {ball.age or 0}")
        line = offside_line(state, xy(ball.positioning))
        parts.append(f"line {_m(line)}" if line is not None else "line ?")
    else:
        parts.extend(("ball ?", "line ?"))
    parts.append("claims " + " ".join(f"{n}:{eta}" for n, eta in sorted(claims.items())))
    recent = [a for a in passes if state.time - a.kicked <= AWAIT_MAX]
    parts.append("passes " + " ".join(f"{a.passer}>{_receiver(a)}@{a.kicked}" for a in recent))
    parts.append(content)
    return " | ".join(parts)


def _receiver(announced: Announced) -> str:
    to = announced.action.to
    return str(to.player_number) if to is not None else "pt"


def _m(value: float) -> str:
    """A figure to a tenth, never "-0.0"."""
    text = f"{value:.1f}"
    return "0.0" if text == "-0.0" else text
