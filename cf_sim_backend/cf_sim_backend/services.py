"""A player's services, whatever the back-end: WorldModel (perception) and Action.

Both back-ends (the embedded simulator and the rcssserver adapter) serve the same Framework
Language through these classes; each only supplies what it perceives and steps the skills.
"""

from __future__ import annotations

import contextlib
from collections.abc import Callable

from cf_commag.agent import Agent, Failure, Refuse, Responder
from cf_lang import Exec, Val, parse_expr, unparse
from cf_lang.acl import AclMessage
from cf_lang.expr import encode_value
from cf_lang.ontology import Team, WorldState
from cf_lang.sexp import dumps
from cf_sim_backend.skills import Skill, SkillError, skill_for
from cf_sim_backend.world import Side, World


def evaluate(val: Val, state: WorldState) -> str:
    """The value a (val ...) names in a perceived world state, as Framework Language text."""
    if val.cls == "WorldState":
        obj = state
    elif val.cls == "Ball":
        obj = state.ball
    elif val.cls == "Game":
        obj = state.game
    elif val.cls == "Player":
        obj = _find_player(state, val.key)
    else:
        raise Refuse(f"this perception knows WorldState, Ball, Game and Player, not {val.cls}")
    if obj is None:
        raise Failure(f"{val.cls} {val.key or ''} is not perceived now")
    if not val.attribute:
        return unparse(obj)
    for name, info in type(obj).model_fields.items():
        if val.attribute in (name, info.alias, info.serialization_alias):
            value = getattr(obj, name)
            if value is None:
                raise Failure(f"{val.cls} {val.attribute} is not known now")
            return dumps(encode_value(value))
    raise Refuse(f"{val.cls} has no attribute {val.attribute}")


def _find_player(state: WorldState, key: dict):
    number, team = key.get("playerNumber"), key.get("whichTeam")
    if state.me is not None and state.me.player_number == number and team.value == "our":
        return state.me
    return next((p for p in state.players if p.player_number == number and p.which_team == team), None)


class PerceptionService:
    """The WorldModel service of one player: (val ...) queries and subscriptions.

    The back-end calls :meth:`publish` with each cycle's perceived state; every open subscription is
    informed of its value (a value not perceived this cycle, e.g. the ball out of view, is skipped,
    not the subscription).
    """

    def __init__(self, agent: Agent, not_yet: str):
        self.state: WorldState | None = None
        self.subscribers: list[tuple[Responder, Val]] = []
        self._not_yet = not_yet
        agent.serve("fipa-query", self._on_query)
        agent.serve("fipa-subscribe", self._on_subscribe)

    def publish(self, state: WorldState) -> None:
        self.state = state
        alive = []
        for responder, val in self.subscribers:
            if not responder.open:
                continue
            with contextlib.suppress(Refuse, Failure):
                responder.inform(evaluate(val, state))
            alive.append((responder, val))
        self.subscribers = alive

    def _val(self, msg: AclMessage) -> Val:
        expr = parse_expr(msg.content or "")
        if not isinstance(expr, Val):
            raise Refuse("perception answers (val ...) expressions only")
        return expr

    def _on_query(self, msg: AclMessage, responder: Responder) -> str:
        val = self._val(msg)
        if self.state is None:
            raise Failure(f"no perception yet: {self._not_yet}")
        return evaluate(val, self.state)

    def _on_subscribe(self, msg: AclMessage, responder: Responder) -> None:
        val = self._val(msg)
        responder.agree()
        self.subscribers.append((responder, val))


class ActionService:
    """The Action service of one player: (exec Player <method> ...) requests become skills.

    A request is agreed when its skill starts and informed when it is done (failure if it fails
    or a newer request replaces it). Unknown methods, another player's key or impossible actions
    are refused with the reason. The back-end steps :attr:`skill` each cycle (or hands it on with
    ``on_start``) and reports how it ended with :meth:`settle`.

    ``me()`` gives our number and side; ``world()`` the world a skill starts in, or None before
    the back-end has started (the request is then refused with ``not_yet``).

    ``say`` (service class Communication) is not a body action: it goes out beside the skill in
    force, which it neither replaces nor ends, through ``on_say(text)`` (the back-end sends it with
    this cycle's commands), and is done at once.
    """

    def __init__(
        self,
        agent: Agent,
        me: Callable[[], tuple[int, Side]],
        world: Callable[[], World | None],
        not_yet: str,
        on_start: Callable[[Skill], None] | None = None,
        on_say: Callable[[str], None] | None = None,
    ):
        self._me, self._world = me, world
        self._not_yet = not_yet
        self._on_start = on_start
        self._on_say = on_say
        self.skill: Skill | None = None
        self.responder: Responder | None = None
        agent.serve("fipa-request", self._on_request)

    def _on_request(self, msg: AclMessage, responder: Responder) -> None:
        expr = parse_expr(msg.content or "")
        if not isinstance(expr, Exec) or expr.cls != "Player":
            raise Refuse("this action component executes (exec Player <method> ...) only")
        number, side = self._me()
        if expr.key.get("playerNumber") != number or expr.key.get("whichTeam") is not Team.OUR:
            asked, team = expr.key.get("playerNumber"), expr.key.get("whichTeam")
            raise Refuse(f"I act for our player {number}, not {team.value if team else '?'} player {asked}")
        world = self._world()
        if world is None:
            raise Refuse(self._not_yet)
        try:
            skill = skill_for(expr.method, expr.action, side, world, world.player(side, number))
        except SkillError as exc:
            raise Refuse(str(exc)) from None
        if expr.method == "say":
            if self._on_say is None:
                raise Refuse("this back-end cannot say")
            self._on_say(expr.action.message)
            responder.agree()
            responder.inform("(done say :cycles 0)")
            return
        if self.responder is not None and self.responder.open:
            self.responder.failure("replaced by a newer request")
        responder.agree()
        self.skill, self.responder = skill, responder
        if self._on_start is not None:
            self._on_start(skill)

    @property
    def active(self) -> bool:
        """A request is in force (its requester has not gone away)."""
        if self.responder is not None and not self.responder.open:
            self.skill = self.responder = None
        return self.responder is not None

    def settle(self, status: str, reason: str = "", name: str = "", cycles: int = 0) -> None:
        """How this cycle's step of the skill went: ``done`` and ``failed`` end the request."""
        if status not in ("done", "failed") or self.responder is None:
            return
        responder, self.skill, self.responder = self.responder, None, None
        if not responder.open:
            return
        if status == "done":
            responder.inform(f"(done {name} :cycles {cycles})")
        else:
            responder.failure(reason)
