"""A component container for players: one process hosting several players' perception, action and decision.

    ros2 run cf_sim_backend players --ros-args -p side:=l -p team_size:=11          # a whole team
    ros2 run cf_sim_backend players --ros-args -p side:=l -p team_size:=11 -p numbers:=[7]  # one player

Each hosted component is the same node class that runs alone (``perception``, ``action``,
``cf_decision``'s ``decision``), with its own node name, parameters, agent, registration,
lease and inbox; ROS 2 users know this as composition. What the container adds (host.py,
feed.py): one link to the ComMAg for all its agents, delivery between them without DDS, the
simulator's state read once and the cycle's commands sent as one sample, and one executor.

Every hosted agent registers the container's own launch command and its name (``host``
metadata): when the process dies the ComMAg starts it once, and all its agents come back. A
container whose callbacks stop running for ``watchdog`` seconds (hung) exits, so that it is
relaunched rather than left holding its agents' inboxes.
"""

from __future__ import annotations

import sys
from typing import Literal

from pydantic import Field
from rclpy.node import Node
from rclpy.parameter import Parameter

from cf_commag.client import own_launch_command, run
from cf_commag.guarded import GuardedNode
from cf_commag.host import Host
from cf_commag.params import ComponentParams
from cf_commag.runtime import default_executor
from cf_decision.decision_node import DecisionNode
from cf_sim_backend.embedded.action_node import ActionNode
from cf_sim_backend.embedded.feed import StateFeed
from cf_sim_backend.embedded.perception_node import PerceptionNode

ROLES = ("perception", "action", "decision")


class PlayersParams(ComponentParams):
    """The container's parameters; ``name`` is the host's name (default ``<team>_players``)."""

    sim: str = Field("cf_sim", description="the simulation to play in (its topics are /<sim>/...)")
    side: Literal["l", "r"] = Field("l", description="l or r")
    team: str = Field("", description="team name (default: blue for l, red for r)")
    team_size: int = Field(11, ge=1, le=11, description="players in the team")
    numbers: tuple[int, ...] = Field((0,), description="shirt numbers to host (0 or empty: 1..team_size)")
    components: tuple[str, ...] = Field(ROLES, description="components of each player to host")
    skip: tuple[str, ...] = Field((), description="agent names not to host (they run elsewhere)")
    noise: float = Field(0.02, ge=0, description="perception noise: standard deviation per metre of distance")
    seed: int = Field(0, description="random seed of the perception noise")
    watchdog: float = Field(10.0, ge=0, description="exit if no callback ran for this many seconds (0: never)")
    lease: float = Field(2.0, gt=0, le=300, description="lease period (s) of every hosted agent")


class PlayersNode(GuardedNode, Node):
    """The container: hosts the components PlayersParams names. Parameters: PlayersParams."""

    def __init__(self, **kwargs):
        given = PlayersParams.given(kwargs)
        team = given["team"] or ("blue" if given["side"] == "l" else "red")
        super().__init__(given["name"] or f"{team}_players", **kwargs)
        p = self.p = PlayersParams.declare_and_read(self)
        unknown = set(p.components) - set(ROLES)
        if unknown:
            raise ValueError(f"invalid parameters: components: unknown {sorted(unknown)} (known: {list(ROLES)})")
        self.team = team
        numbers = [n for n in p.numbers if 1 <= n <= p.team_size] or list(range(1, p.team_size + 1))
        self.host = Host(self, name=self.get_name(), commag=p.commag, watchdog=p.watchdog)
        self.feed = StateFeed(self, p.sim)
        launch = p.launch_command(own_launch_command())
        self.components: list[Node] = []
        for number in numbers:
            for role in ROLES:  # perception first: a decision finds it at once
                if role in p.components and f"{team}_{number}_{role}" not in p.skip:
                    self.components.append(self._component(role, number, launch))
        self.get_logger().info(f"hosting {len(self.components)} components of {team}: players {numbers}")

    def _component(self, role: str, number: int, launch: list[str]) -> Node:
        p = self.p
        common = {"commag": p.commag, "lease": p.lease, "team": self.team, "number": number}
        if role == "decision":
            values = {**common, "team_size": p.team_size}
            return DecisionNode(host=self.host, launch=launch, **_node_kwargs(values))
        values = {**common, "sim": p.sim, "side": p.side}
        if role == "perception":
            values |= {"noise": p.noise, "seed": p.seed}
            return PerceptionNode(feed=self.feed, host=self.host, launch=launch, **_node_kwargs(values))
        return ActionNode(feed=self.feed, host=self.host, launch=launch, **_node_kwargs(values))

    @property
    def agents(self):
        return [node.agent for node in self.components]


def _node_kwargs(values: dict) -> dict:
    # The container's command line (-p side:=l, ...) is its own, not its components'.
    return {"parameter_overrides": [Parameter(k, value=v) for k, v in values.items()], "use_global_arguments": False}


def _log_stats(node: PlayersNode) -> None:
    for component in node.components:
        if isinstance(component, DecisionNode):
            component.log_stats()
    node.get_logger().info(f"{node.host.delivered} messages delivered in this process")


def _executor(node: PlayersNode):
    executor = default_executor(node)
    for component in node.components:
        executor.add_node(component)
    return executor


def main(args: list[str] | None = None) -> int:
    """Entry point of ``ros2 run cf_sim_backend players``."""
    return run(PlayersNode, agents=lambda node: node.agents, executor=_executor, on_exit=_log_stats, args=args)


if __name__ == "__main__":
    sys.exit(main())
