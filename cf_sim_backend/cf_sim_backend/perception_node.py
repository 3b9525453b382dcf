"""A player's perception component: answers (val ...) queries and informs subscribers every cycle."""

from __future__ import annotations

import contextlib
import random
import sys

from cf_commag.client import Failure, Refuse, Responder, run
from cf_lang import Val, parse_expr, unparse
from cf_lang.acl import AclMessage
from cf_lang.expr import _encode_value
from cf_lang.ontology import WorldState
from cf_lang.sexp import dumps

from .perception import observe
from .player_base import PlayerComponentNode
from .world import World


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
            return dumps(_encode_value(value))
    raise Refuse(f"{val.cls} has no attribute {val.attribute}")


class PerceptionService:
    """The WorldModel service of one player, whatever the back-end: (val ...) queries and subscriptions.

    The back-end calls :meth:`publish` with each cycle's perceived state; every open subscription is
    informed of its value (a value not perceived this cycle, e.g. the ball out of view, is skipped,
    not the subscription).
    """

    def __init__(self, agent, not_yet: str):
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


def _find_player(state: WorldState, key: dict):
    number, team = key.get("playerNumber"), key.get("whichTeam")
    if state.me is not None and state.me.player_number == number and team.value == "our":
        return state.me
    return next((p for p in state.players if p.player_number == number and p.which_team == team), None)


class PerceptionNode(PlayerComponentNode):
    """Perception of one player (service class WorldModel). Parameters: PLAYER_PARAMS, noise, seed."""

    ROLE = "perception"
    SERVICE_CLASS = "WorldModel"

    def __init__(self, **kwargs):
        super().__init__(
            {
                "noise": (0.02, "position noise: standard deviation per metre of distance"),
                "seed": (0, "random seed of the noise"),
            },
            **kwargs,
        )
        self.rng = random.Random(int(self.p["seed"]) * 100 + self.number + (0 if self.p["side"] == "l" else 50))
        self.perception = PerceptionService(self.agent, "the simulator has not started")

    def on_cycle(self, world: World) -> None:
        self.perception.publish(observe(world, self.side, self.number, self.rng, noise=float(self.p["noise"])))


def main() -> int:
    """Entry point of ``ros2 run cf_sim_backend perception``."""
    return run(PerceptionNode)


if __name__ == "__main__":
    sys.exit(main())
