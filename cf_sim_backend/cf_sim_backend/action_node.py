"""A player's action component: executes (exec Player <method> ...) requests, cycle by cycle."""

from __future__ import annotations

import json
import sys

from std_msgs.msg import String

from cf_commag.client import Refuse, Responder, run
from cf_lang import Exec, parse_expr
from cf_lang.acl import AclMessage
from cf_lang.ontology import Team

from .player_base import PlayerComponentNode
from .skills import Skill, SkillError, skill_for
from .topics import COMMAND_QOS, command_topic, encode_command
from .world import World


class ActionNode(PlayerComponentNode):
    """Action of one player (service class Action). Parameters: PLAYER_PARAMS.

    A request is agreed when its skill starts and informed when it is done
    (failure if it fails or a newer request replaces it). Unknown methods,
    another player's key or impossible actions are refused with the reason.
    """

    ROLE = "action"
    SERVICE_CLASS = "Action"

    def __init__(self, **kwargs):
        super().__init__(**kwargs)
        self.commands = self.create_publisher(String, command_topic(self.p["sim"]), COMMAND_QOS)
        self.current: tuple[Skill, Responder] | None = None
        self.agent.serve("fipa-request", self._on_request)

    def _on_request(self, msg: AclMessage, responder: Responder) -> None:
        expr = parse_expr(msg.content or "")
        if not isinstance(expr, Exec) or expr.cls != "Player":
            raise Refuse("this action component executes (exec Player <method> ...) only")
        if expr.key.get("playerNumber") != self.number or expr.key.get("whichTeam") is not Team.OUR:
            number, team = expr.key.get("playerNumber"), expr.key.get("whichTeam")
            raise Refuse(f"I act for our player {self.number}, not {team.value if team else '?'} player {number}")
        if self.world is None:
            raise Refuse("the simulator has not started")
        me = self.world.player(self.side, self.number)
        try:
            skill = skill_for(expr.method, expr.action, self.side, self.world, me)
        except SkillError as exc:
            raise Refuse(str(exc)) from None
        if self.current is not None and self.current[1].open:
            self.current[1].failure("replaced by a newer request")
        responder.agree()
        self.current = (skill, responder)

    def on_cycle(self, world: World) -> None:
        self._act(world)
        if self.step is not None:  # tell the simulator we are done with this cycle (its sync mode)
            done = {"side": self.side.value, "number": self.number, "done": self.step}
            self.commands.publish(String(data=json.dumps(done)))

    def _act(self, world: World) -> None:
        if self.current is None:
            return
        skill, responder = self.current
        if not responder.open:
            self.current = None
            return
        step = skill.step(world, world.player(self.side, self.number))
        for cmd in step.commands:
            self.commands.publish(String(data=encode_command(self.side.value, self.number, cmd[0], cmd[1:])))
        if step.status == "done":
            responder.inform(f"(done {skill.name} :cycles {skill.cycles})")
            self.current = None
        elif step.status == "failed":
            responder.failure(step.reason)
            self.current = None


def main() -> int:
    """Entry point of ``ros2 run cf_sim_backend action``."""
    return run(ActionNode)


if __name__ == "__main__":
    sys.exit(main())
