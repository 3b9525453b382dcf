"""What the per-player components share: parameters, the state subscription, the agent."""

from __future__ import annotations

from typing import Literal

from pydantic import Field
from rclpy.node import Node

from cf_commag.client import Agent, own_launch_command
from cf_commag.guarded import GuardedNode
from cf_commag.host import Host
from cf_commag.params import ComponentParams
from cf_sim_backend.embedded.feed import StateFeed
from cf_sim_backend.world import Side, World


class PlayerParams(ComponentParams):
    """The parameters of each player component on the embedded simulator."""

    sim: str = Field("cf_sim", description="the simulation to play in (its topics are /<sim>/...)")
    side: Literal["l", "r"] = Field("l", description="l or r")
    number: int = Field(1, ge=1, le=11, description="shirt number, 1..11")
    team: str = Field("", description="team name (default: blue for l, red for r)")
    relaunch_fails: bool = Field(False, description="register a launch command that fails (to show withdrawal)")
    exit_at_start: bool = Field(False, description="exit with code 3 at once (what a failing launch does)")


class PlayerComponentNode(GuardedNode, Node):
    """A node for one player's component; subclasses set ROLE, SERVICE_CLASS and handle states.

    Alone in its process it makes its own state feed and host; hosted with others (players.py)
    it is given the process's ``feed`` and ``host``, and ``launch`` (the host's launch command).
    """

    ROLE = "component"
    SERVICE_CLASS = "Service"
    PARAMS: type[PlayerParams] = PlayerParams

    def __init__(
        self,
        node_name: str | None = None,
        *,
        feed: StateFeed | None = None,
        host: Host | None = None,
        launch: list[str] | None = None,
        **kwargs,
    ):
        if node_name is None:  # named after its agent, so that ros2 node/param/... can tell players apart
            node_name = self._agent_name(self.PARAMS.given(kwargs))
        super().__init__(node_name, **kwargs)
        self.p = self.PARAMS.declare_and_read(self)
        self.side = Side(self.p.side)
        self.number = self.p.number
        self.team = self.p.team or ("blue" if self.side is Side.LEFT else "red")
        name = self._agent_name(self.p.model_dump())
        if self.p.exit_at_start:
            raise SystemExit(3)
        if launch is None:
            launch = own_launch_command()
            if self.p.relaunch_fails:
                launch += ["--ros-args", "-p", "exit_at_start:=true"]
            launch = self.p.launch_command(launch)
        self.world: World | None = None
        self.step: int | None = None  # the simulator's step counter, for its sync mode
        self.feed = feed if feed is not None else StateFeed(self, self.p.sim)
        self.feed.listen(self._on_state)
        self.agent = Agent(
            self,
            name=name,
            service_class=self.SERVICE_CLASS,
            team=self.team,
            player_number=self.number,
            lease=self.p.lease,
            commag=self.p.commag,
            launch_command=launch,
            host=host,
        )

    @classmethod
    def _agent_name(cls, p: dict) -> str:
        team = p["team"] or ("blue" if p["side"] == Side.LEFT.value else "red")
        return p["name"] or f"{team}_{p['number']}_{cls.ROLE}"

    def _on_state(self, world: World, step: int | None) -> None:
        self.step = step
        if (self.side, self.number) not in world.players:
            self.get_logger().warning("my player is not in this simulation", throttle_duration_sec=5.0)
            return
        self.world = world
        self.on_cycle(world)

    def on_cycle(self, world: World) -> None:
        raise NotImplementedError
