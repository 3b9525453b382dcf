"""A player's decision component: the policy, wired to the framework (a thin node).

It finds its player's perception (WorldModel) and action (Action) providers
through the ComMAg, subscribes to the perception's WorldState, and for every
perceived cycle asks the policy what to do; a new decision becomes a
fipa-request to the action provider. Team-mates' decision components
exchange their times to the ball (``inform`` with the intended
``(exec Player intercept ...)`` and an ``:X-eta`` parameter), which the policy
uses to pick who goes for the ball, and the passes they ask for in play
(``inform`` with the same ``(exec Player pass ...)`` the action provider gets),
so that the receiver sets off before the ball is seen rolling.

Redundancy: providers are looked up again for every request, so when the one
in use is withdrawn or suspect the next healthy one takes over (within one
lease); a perception provider that stops informing is replaced the same way.
Two decision components for one player may run: only the one registered with
``active:=true`` acts; a standby takes over when the active one is withdrawn.
"""

from __future__ import annotations

import sys
import time
from typing import Literal

from pydantic import Field
from rclpy.node import Node

from cf_commag.client import Agent, own_launch_command, run
from cf_commag.guarded import GuardedNode, guard
from cf_commag.host import Host
from cf_commag.params import ComponentParams
from cf_lang import Exec, LanguageError, parse_expr
from cf_lang.acl import AclMessage, AgentId, Performative
from cf_lang.expr import to_sexp
from cf_lang.ontology import Team, WorldState
from cf_lang.ontology import actions as act
from cf_lang.sexp import dumps

from .policy import decide
from .receive import Announced, to_announce
from .requests import ActionRequests, choice_text, request_text
from .set_piece import KICKING, SetPieceTaker
from .shared import Heard, merged, to_tell, told_to
from .situation import Decision, offside_mates, xy
from .talk import NOT_ME, Listener, pass_word, seen_claims
from .touch import LastTouch
from .without_ball import NEVER, state_eta


class DecisionParams(ComponentParams):
    team: str = Field("blue", description="team name, as the components register it")
    number: int = Field(1, ge=1, le=11, description="shirt number")
    team_size: int = Field(11, ge=1, le=11, description="players in the team (for the formation)")
    standby: bool = Field(False, description="act only when no other decision component of this player is alive")
    log_requests: bool = Field(
        False, description="log every new request with what it was chosen on (me, ball, claims, passes heard)"
    )
    talk: Literal["framework", "say"] = Field(
        "framework",
        description="framework: tell team-mates' decisions times to the ball, passes and sightings (ACL);"
        " say: only the pass, in a say through the back-end, as a competition's rules allow (talk.py)",
    )


PERCEPTION_SILENCE = 1.0  # seconds without an inform before the perception provider is replaced


def _agent_name(p: dict) -> str:
    return p["name"] or f"{p['team']}_{p['number']}_decision{'_standby' if p['standby'] else ''}"


class DecisionNode(GuardedNode, Node):
    """Decision of one player (service class PlayerDecision). Parameters: DecisionParams."""

    def __init__(
        self, node_name: str | None = None, *, host: Host | None = None, launch: list[str] | None = None, **kwargs
    ):
        """``host`` and ``launch`` (the host's launch command) when hosted with other components."""
        if node_name is None:  # named after its agent, so that ros2 node/param/... can tell players apart
            node_name = _agent_name(DecisionParams.given(kwargs))
        super().__init__(node_name, **kwargs)
        p = DecisionParams.declare_and_read(self)
        self.team, self.number, self.team_size, self.standby = p.team, p.number, p.team_size, p.standby
        self.log_requests = p.log_requests
        self.says = p.talk == "say"  # talk only through the back-end's say (talk.py)
        name = _agent_name(p.model_dump())
        self.agent = Agent(
            self,
            name=name,
            service_class="PlayerDecision",
            team=self.team,
            player_number=self.number,
            lease=p.lease,
            commag=p.commag,
            launch_command=p.launch_command(own_launch_command()) if launch is None else launch,
            on_message=self._on_message,
            host=host,
        )
        self.claims: dict[int, tuple[int, float]] = {}  # team-mate number -> (eta, when heard)
        self.passes: dict[int, Announced] = {}  # team-mate number (or mine) -> the last pass he announced
        self.heard = Heard()  # what team-mates told they saw (shared.py)
        self.listener = Listener()  # what team-mates said (talk say)
        self.last_ball: tuple[float, float] | None = None  # where I believed the ball last
        self.last_offside: frozenset[int] = frozenset()  # which of us I believed offside then
        self.perception: str | None = None
        self.subscription = None
        self.last_inform = 0.0
        self.requests = ActionRequests()
        self.taker = SetPieceTaker()  # the rules forbid our set piece's taker a second touch
        self.touch = LastTouch()  # which side touched the ball last: the keeper may not catch our back pass
        self.create_timer(0.2, self._watch_providers)
        self.last_time: int | None = None  # the game time of the last perception
        self.create_timer(30.0, self.log_stats)

    def log_stats(self) -> None:
        self.get_logger().info(f"requests: {self.requests.stats.line()}")

    # ---- wiring ---------------------------------------------------------------

    def _watch_providers(self) -> None:
        """Subscribe to the best perception provider; replace it if it went quiet or away."""
        best = self.agent.provider("WorldModel", team=self.team, player_number=self.number)
        quiet = time.monotonic() - self.last_inform > PERCEPTION_SILENCE
        if best is None or (best == self.perception and not quiet):
            return
        if self.subscription is not None:
            self.agent.cancel(self.subscription)
        self.perception = best
        self.last_inform = time.monotonic()
        self.subscription = self.agent.request(
            best, "(val WorldState)", protocol="fipa-subscribe", timeout=2.0, on_update=self._on_perception
        )

    def _acting(self) -> bool:
        if not self.standby:
            return True
        others = [
            e
            for e in self.agent.providers("PlayerDecision", team=self.team, player_number=self.number)
            if e.name != self.agent.me.name
        ]
        return not others

    # ---- every cycle ----------------------------------------------------------

    def _on_perception(self, msg: AclMessage) -> None:
        if msg.performative is not Performative.INFORM or not msg.content:
            return
        self.last_inform = time.monotonic()
        try:
            state = parse_expr(msg.content)
        except LanguageError as exc:
            self.get_logger().warning(f"unreadable perception: {exc}", throttle_duration_sec=5.0)
            return
        if not isinstance(state, WorldState) or not self._acting():
            return
        self.heard.perceived()
        word = None if self.says else to_tell(state)  # (my own sighting: not an echo of what team-mates told)
        state, taken = merged(state, self.heard.recent())
        self.requests.stats.from_mates += taken
        if self.last_time is not None and state.time > self.last_time + 1:
            self.requests.stats.missed += state.time - self.last_time - 1
        self.last_time = state.time
        self.last_ball = xy(state.ball.positioning) if state.ball else None
        self.last_offside = offside_mates(state, self.last_ball) if self.last_ball else frozenset()
        if self.says:
            self._read_says(state)
            claims = seen_claims(state, self.number, self.listener.not_theirs(state.time))
        else:
            now = time.monotonic()
            claims = {n: eta for n, (eta, when) in self.claims.items() if now - when < 0.5}
        self.touch.seen(state)
        # Not at all while the rules forbid it: after my set piece, or offside at a team-mate's touch.
        may_touch = self.taker.may_touch(state) and not self.touch.offside(state.time)
        mate_touched = self.touch.team is Team.OUR
        passes = list(self.passes.values())
        decision = decide(state, self.number, self.team_size, claims, may_touch, passes, mate_touched)
        self.taker.decided(state, decision)
        announce = to_announce(state, decision)  # every cycle until it is kicked: the kick is due the next
        if self.says:
            if announce:  # before the request: in synch mode the request's start ends our cycle
                self._say(pass_word(decision.action))
            elif not may_touch:
                self._say(NOT_ME)  # (the framework's claim of NEVER)
        else:
            self._announce(state, may_touch, word, claims)
        if self.requests.wants(decision.method, decision.action):
            if decision.method in KICKING:
                # One line per new way of playing the ball: what a match analysis needs, a few a minute.
                self.requests.stats.chose(decision.why)
                self.get_logger().info(choice_text(state, decision))
            if self.log_requests:
                self.get_logger().info(request_text(state, decision, claims, passes, self._exec(decision)))
            self._request(decision)
        if announce:
            if not self.says:
                self._tell_mates(self._exec(decision))
            # Kept as team-mates keep it: the passer runs on after it (support.go_spot).
            self.passes[self.number] = Announced(
                self.number, decision.action, self.last_ball, state.time + 1, self.last_offside
            )

    def _request(self, decision: Decision) -> None:
        provider = self.agent.provider("Action", team=self.team, player_number=self.number)
        if provider is None:
            return
        content = self._exec(decision)
        future = self.agent.request(provider, content, timeout=3.0)
        self.requests.sent(decision.method, decision.action, future)
        future.add_done_callback(guard(self._on_answer, self.get_logger(), "the answer to a request"))

    def _say(self, text: str) -> None:
        """Ask the action provider to say ``text`` (beside the request in force; answers are not awaited)."""
        provider = self.agent.provider("Action", team=self.team, player_number=self.number)
        if provider is not None:
            self.agent.request(provider, self._exec(Decision("say", act.Say(message=text), "")), timeout=3.0)

    def _read_says(self, state: WorldState) -> None:
        """Take the passes team-mates said (talk ``say``): as a pass told over the framework, heard a
        cycle later, so its kick is taken to be in the cycle it was heard."""
        for passer, action, when in self.listener.hear(state):
            if self.last_ball is not None:
                self.passes[passer] = Announced(passer, action, self.last_ball, when, self.last_offside)
                self.touch.played_by_mate(when if self.number in self.last_offside else None)

    def _exec(self, decision: Decision) -> str:
        """The ``(exec Player <method> ...)`` text of ``decision`` for my player."""
        expr = Exec("Player", decision.method, {"playerNumber": self.number, "whichTeam": Team.OUR}, decision.action)
        return dumps(to_sexp(expr))

    def _on_answer(self, future) -> None:
        # A request we replaced is answered failure by the action component: that says nothing
        # about the request in force, which must not be sent again because of it.
        self.requests.answered(future, future.result().ok)

    def _announce(self, state: WorldState, may_touch: bool, word: WorldState | None, claims: dict[int, int]) -> None:
        """Tell team-mates' decision components how soon my player can reach the ball (never, while
        he may not touch it), and those who may play it next (``shared.told_to``) what he sees
        (``word``): one inform a cycle to each.

        The time to the ball is the user-defined parameter ``:X-eta``; the content is the word, or
        ``(exec Player intercept ...)`` for the others and while my player does not know where he is.
        """
        eta = state_eta(state)
        if eta is not None and not may_touch:
            eta = NEVER
        user = () if eta is None else (("X-eta", str(eta)),)
        near = told_to(claims) if word is not None else set()
        mates = self._mates()
        if near & mates.keys():
            self._send(dumps(to_sexp(word)), [name for n, name in mates.items() if n in near], user)
        others = [name for n, name in mates.items() if n not in near]
        if user and others:
            self._send(f"(exec Player intercept :playerNumber {self.number} :whichTeam our)", others, user)

    def _mates(self) -> dict[int, str]:
        """My team-mates' decision components: shirt number -> agent name."""
        mates = {e.record.player_number: e.name for e in self.agent.providers("PlayerDecision", team=self.team)}
        mates.pop(self.number, None)
        return mates

    def _tell_mates(self, content: str, user: tuple = ()) -> None:
        """Inform my team-mates' decision components of ``content``."""
        self._send(content, list(self._mates().values()), user)

    def _send(self, content: str, names: list[str], user: tuple = ()) -> None:
        if names:
            receivers = tuple(AgentId(m) for m in names)
            self.agent.send(AclMessage(Performative.INFORM, receivers=receivers, content=content, user=user))

    def _on_message(self, msg: AclMessage) -> None:
        if msg.performative is not Performative.INFORM:
            return
        try:
            expr = parse_expr(msg.content or "")
            # A team-mate's word (what he sees, with his time to the ball), or an exec he asked for.
            word = expr if isinstance(expr, WorldState) else None
            if word is not None:
                number = word.me.player_number if word.me and word.me.which_team is Team.OUR else None
            else:
                number = expr.key["playerNumber"]
            if type(number) is not int or not 1 <= number <= 11 or number == self.number:
                return  # a shirt number of a team-mate only: what is kept per sender stays bounded
            if word is not None:
                self.heard.keep(number, word)
            elif isinstance(expr, Exec) and expr.method == "pass" and isinstance(expr.action, act.Pass):
                if self.last_ball is not None and self.last_time is not None:
                    self.passes[number] = Announced(
                        number, expr.action, self.last_ball, self.last_time + 1, self.last_offside
                    )
                    self.touch.played_by_mate(self.last_time if self.number in self.last_offside else None)
                return
            self.claims[number] = (int(dict(msg.user)["X-eta"]), time.monotonic())  # (KeyError: a word without)
        except (LanguageError, AttributeError, KeyError, TypeError, ValueError):
            return


def main() -> int:
    """Entry point of ``ros2 run cf_decision decision``."""
    return run(DecisionNode, on_exit=DecisionNode.log_stats)


if __name__ == "__main__":
    sys.exit(main())
