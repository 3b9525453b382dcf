"""The simulator as a ROS node: plays cycles in real time, publishes the true state, takes commands."""

from __future__ import annotations

import json
import sys
import time
from pathlib import Path
from typing import Literal

from pydantic import Field
from rclpy.node import Node
from std_msgs.msg import String

from cf_commag.client import Agent, own_launch_command, run
from cf_commag.guarded import GuardedNode
from cf_commag.params import ComponentParams
from cf_sim_backend.embedded.matchlog import MatchLog
from cf_sim_backend.embedded.physics import CommandError
from cf_sim_backend.embedded.sim import Simulator
from cf_sim_backend.embedded.topics import COMMAND_QOS, STATE_QOS, command_topic, state_topic
from cf_sim_backend.world import Params, Side


class SimParams(ComponentParams):
    """The embedded simulator's parameters (its agent's name is the simulation's unless ``name`` is set)."""

    sim: str = Field("cf_sim", description="name of this simulation: topics are /<sim>/state and /<sim>/commands")
    left_size: int = Field(11, ge=0, le=11, description="players on the left team (0..11)")
    right_size: int = Field(11, ge=0, le=11, description="players on the right team (0..11)")
    left_name: str = Field("blue", description="left team's name")
    right_name: str = Field("red", description="right team's name")
    seed: int = Field(0, description="random seed: the same seed and commands give the same match")
    cycle_period: float = Field(
        0.1, gt=0, description="seconds per cycle in realtime mode (0.1 is real time; smaller runs faster)"
    )
    mode: Literal["realtime", "sync"] = Field(
        "realtime",
        description="realtime: a cycle every cycle_period; sync: a cycle as soon as every player's action "
        "component has reported done (as rcssserver's synch_mode), at most sync_timeout apart",
    )
    sync_timeout: float = Field(
        0.5, gt=0, description="sync mode: seconds to wait for missing players before playing the cycle anyway"
    )
    player_types: int = Field(
        18,
        ge=1,
        le=100,
        description="heterogeneous player types, drawn from the seed as rcssserver 19 draws them "
        "(18, as rcssserver 19; 1: every player of the default type)",
    )
    half_cycles: int = Field(3000, ge=1, description="cycles per half")
    halves: int = Field(2, ge=1, description="number of halves")
    auto_kick_off_cycles: int = Field(50, ge=0, description="cycles before the kick-off happens by itself")
    match_log: str = Field("", description="path of the match log (JSON lines); empty: none")
    exit_at_end: bool = Field(False, description="leave when the match is over")
    lease: float = Field(2.0, gt=0, le=300, description="lease period (s) with the ComMAg")


class SimNode(GuardedNode, Node):
    """Runs the embedded simulator. Parameters: SimParams."""

    def __init__(self, **kwargs):
        super().__init__("sim", **kwargs)
        p = self.p = SimParams.declare_and_read(self)
        self.sim = Simulator(
            Params(half_cycles=p.half_cycles, halves=p.halves, auto_kick_off_cycles=p.auto_kick_off_cycles),
            team_sizes=(p.left_size, p.right_size),
            team_names=(p.left_name, p.right_name),
            seed=p.seed,
            player_types=p.player_types,
        )
        self.rejected = 0
        self.log = MatchLog(Path(p.match_log), self.sim, p.cycle_period) if p.match_log else None
        self.state_pub = self.create_publisher(String, state_topic(p.sim), STATE_QOS)
        self.create_subscription(String, command_topic(p.sim), self._on_command, COMMAND_QOS)
        self.agent = Agent(
            self,
            name=p.name or p.sim,
            service_class="Simulator",
            commag=p.commag,
            lease=p.lease,
            launch_command=p.launch_command(own_launch_command()),
        )
        self.sync = p.mode == "sync"
        self.steps = 0
        self.done_by: set[tuple[str, int]] = set()
        self.last_step = time.monotonic()
        self.sync_timeouts = 0
        self.players = {(p_.side.value, p_.number) for p_ in self.sim.world.players.values()}
        self.timer = self.create_timer(0.002 if self.sync else p.cycle_period, self._on_timer)
        self.done = False
        self.get_logger().info(
            f"simulating {p.left_name} ({p.left_size}) v {p.right_name} ({p.right_size}), "
            f"seed {p.seed}, {p.cycle_period * 1000:.0f} ms per cycle"
        )

    def _on_command(self, msg: String) -> None:
        try:
            data = json.loads(msg.data)
        except ValueError as exc:
            self._refuse(exc, msg.data)
            return
        for c in data if isinstance(data, list) else [data]:
            try:
                self._command(c)
            except (CommandError, ValueError, KeyError, TypeError, AttributeError) as exc:
                self._refuse(exc, json.dumps(c))

    def _command(self, c: dict) -> None:
        if "done" in c:  # sync mode: this player's action component has acted on our last state
            if int(c["done"]) == self.steps:
                self.done_by.add((str(c["side"]), int(c["number"])))
            return
        self.sim.command(Side(c["side"]), int(c["number"]), str(c["cmd"]), *c.get("args", []))

    def _refuse(self, exc: Exception, text: str) -> None:
        self.rejected += 1
        self.get_logger().warning(f"command refused: {exc} ({text[:80]})", throttle_duration_sec=2.0)

    def _on_timer(self) -> None:
        if not self.sync:
            self._on_cycle()
            return
        waited = time.monotonic() - self.last_step
        if self.done_by >= self.players or waited >= self.p.sync_timeout:
            if not self.done_by >= self.players:
                self.sync_timeouts += 1
            self._on_cycle()

    def _on_cycle(self) -> None:
        if self.done:
            return
        events = self.sim.step()
        self.steps += 1
        self.done_by = set()
        self.last_step = time.monotonic()
        snap = self.sim.snapshot()
        snap["step"] = self.steps
        self.state_pub.publish(String(data=json.dumps(snap)))
        if self.log is not None:
            self.log.cycle(snap, events)
        w = self.sim.world
        for event in events:
            self.get_logger().info(f"[{w.time:5d}] {event}  score {w.score[Side.LEFT]}:{w.score[Side.RIGHT]}")
        if self.sim.finished:
            self.done = True
            if self.log is not None:
                self.log.close(
                    extra={"sync": {"steps": self.steps, "timeouts": self.sync_timeouts}} if self.sync else None
                )
            self.get_logger().info(f"match over: {w.score[Side.LEFT]}:{w.score[Side.RIGHT]}")


def main(args: list[str] | None = None) -> int:
    """Entry point of ``ros2 run cf_sim_backend sim``."""
    return run(SimNode, until=lambda node: node.p.exit_at_end and node.done, args=args)


if __name__ == "__main__":
    sys.exit(main())
