"""One player on the RoboCup 2D server (rcssserver 19): its perception and action services over UDP.

``ros2 run cf_sim_backend rcss_player --ros-args -p team:=CF -p port:=6000 [-p goalie:=true]``

The node connects as a player (``(init TEAM (version 19))``), and once the server has given it a
shirt number it registers two components with the ComMAg, exactly as the embedded simulator's
players do: ``<team>_<n>_perception`` (WorldModel: ``(val ...)`` queries and subscriptions) and
``<team>_<n>_action`` (Action: ``(exec Player <method> ...)`` requests). A decision component
cannot tell the two back-ends apart.

Each cycle it informs the perception subscribers, then runs one step of the action in progress
(at most one body command). In synch mode (the server sends ``(think)``) it waits up to
``synch_wait`` seconds for a decision's new request, acts, and answers ``(done)``; in real time it
acts on the cycle's ``see`` (or right after ``sense_body`` when no see is due this cycle).

The UDP socket is read by a thread that only queues datagrams and wakes the executor (a
Doorbell), so everything else runs on the executor, as in every other component.
"""

from __future__ import annotations

import json
import os
import socket
import sys
import threading
import time
from collections import deque
from typing import Literal

from pydantic import Field
from rclpy.node import Node

from cf_commag.client import Agent, own_launch_command, run
from cf_commag.doorbell import Doorbell
from cf_commag.given_parameters import node_name as safe_node_name
from cf_commag.guarded import GuardedNode
from cf_commag.host import Host
from cf_commag.params import ComponentParams
from cf_commag.runtime import default_executor
from cf_sim_backend.rcss.belief import world_state
from cf_sim_backend.rcss.session import PlayerSession
from cf_sim_backend.services import ActionService, PerceptionService
from cf_sim_backend.world import Side


class RcssPlayerParams(ComponentParams):
    """A player on rcssserver: its perception and action agents are <team>_<number>_perception/_action."""

    host: str = Field("127.0.0.1", description="rcssserver's host")
    port: int = Field(6000, ge=1, le=65535, description="rcssserver's player port")
    team: str = Field("CommonFramework", description="team name on the server (and the components' team)")
    goalie: bool = Field(False, description="connect as the goalkeeper")
    number: int = Field(0, ge=0, le=11, description="the shirt number to take back after a relaunch")
    reconnect: bool = Field(False, description="take over player <number> with (reconnect ...) instead of (init ...)")
    local_port: int = Field(
        0, ge=0, le=65535, description="UDP port to bind (0: any); a relaunch binds its predecessor's"
    )
    version: int = Field(19, ge=1, description="player protocol version")
    synch_wait: float = Field(
        0.03, gt=0, description="synch mode: seconds to wait for a decision's request before (done)"
    )
    see_wait: float = Field(0.015, gt=0, description="real time: seconds to wait for a due see after sense_body")
    server_timeout: float = Field(10.0, gt=0, description="exit with an error when the server is silent this long (s)")
    stats_file: str = Field("", description="write the session's counters (JSON) here every 50 cycles and at exit")
    decision: bool = Field(False, description="host this player's decision component in this process too")
    team_size: int = Field(11, ge=1, le=11, description="players in the team (for the hosted decision's formation)")
    log_requests: bool = Field(False, description="the hosted decision logs every new request (its log_requests)")
    talk: Literal["framework", "say"] = Field(
        "say", description="how the hosted decision talks to team-mates (its talk): say is the rules' way"
    )


class RcssPlayerNode(GuardedNode, Node):
    """A player on rcssserver. Parameters: RcssPlayerParams."""

    def __init__(self, node_name: str | None = None, **kwargs):
        if node_name is None:  # the shirt number is the server's to give: known only on a relaunch
            p = RcssPlayerParams.given(kwargs)
            node_name = safe_node_name(
                f"{p['team']}_{p['number']}_rcss_player" if p["number"] else f"{p['team']}_rcss_player_{os.getpid()}"
            )
        super().__init__(node_name, **kwargs)
        self.p = RcssPlayerParams.declare_and_read(self)
        self.session = PlayerSession(str(self.p.team), bool(self.p.goalie), int(self.p.version))
        self.agents: list[Agent] = []
        self.perception: PerceptionService | None = None  # once the server has given us a number
        self.decision = None  # the hosted decision node (decision:=true)
        self.exit_code: int | None = None  # set when the match is over (or the server is gone)
        self.action: ActionService | None = None
        self.synch = False
        self.cycle_done = -1  # the last server step acted on (belief.steps)
        self.waiting = False  # synch mode: perceived this cycle, (done) not yet sent
        self.finished = False
        self.last_heard = time.monotonic()
        self.cycle_heard = self.last_heard  # when this cycle's sense_body (or think) came

        host = socket.gethostbyname(str(self.p.host))
        self.server = (host, int(self.p.port))
        self.sock = socket.socket(socket.AF_INET, socket.SOCK_DGRAM)
        # A loopback server needs only a loopback socket; otherwise listen where the server can answer.
        # No SO_REUSEADDR: binding a predecessor's port succeeds only once that process is gone,
        # so a relaunched adapter can never steal the player from one that is still alive.
        self.sock.bind(("127.0.0.1" if host.startswith("127.") else "", int(self.p.local_port)))
        self.attached = False  # the server talks to us as its player
        self.last_hello = time.monotonic()
        self.queue: deque[tuple[bytes, tuple]] = deque()
        self.wake = Doorbell(self, self._drain)
        self.act_timer = self.create_timer(float(self.p.synch_wait), self._on_act_timer)
        self.act_timer.cancel()
        self.see_timer = self.create_timer(float(self.p.see_wait), self._on_see_timer)
        self.see_timer.cancel()
        self.create_timer(1.0, self._watch)
        threading.Thread(target=self._read, name="rcss-udp", daemon=True).start()
        self._hello()
        if self.p.reconnect and int(self.p.number):
            # A relaunch registers at once (within the ComMAg's start-up grace), even while the
            # server still refuses to give the player back (it does so only outside play_on).
            self.get_logger().info(f"asking for {self.session.team} {self.p.number} back (reconnect)")
            self._join()

    # ---- the server -------------------------------------------------------------

    def _hello(self) -> None:
        self.last_hello = time.monotonic()
        number = int(self.p.number)
        text = self.session.reconnect(number) if self.p.reconnect and number else self.session.hello()
        self._send(text, to=self.server)

    def _send(self, text: str, to: tuple | None = None) -> None:
        try:
            self.sock.sendto(text.encode() + b"\0", to or self.server)
        except OSError as exc:
            self.get_logger().error(f"cannot send to the server: {exc}", throttle_duration_sec=5.0)

    def _read(self) -> None:
        while True:
            try:
                data, addr = self.sock.recvfrom(65536)
            except OSError:
                return  # socket closed: shutting down
            self.queue.append((data, addr))
            self.wake.ring()

    def _drain(self) -> None:
        while self.queue:
            data, addr = self.queue.popleft()
            self._on_datagram(data, addr)

    def _on_datagram(self, data: bytes, addr: tuple) -> None:
        self.last_heard = time.monotonic()
        joined = bool(self.agents)
        kind = self.session.receive(data)
        if kind in ("sense_body", "think"):
            self.cycle_heard = self.last_heard
        if kind in ("sense_body", "see", "think") and not self.attached:
            self.server = addr  # a relaunch on its predecessor's port: the server talks to us already
        if kind in ("init", "reconnect", "sense_body", "see", "think"):
            self.attached = True
        if kind in ("init", "reconnect") and self.session.ready:
            self.server = addr  # after init the server talks from a port of its own for this player
            if not joined:
                self._join()
        elif kind in ("error", "warning"):
            self.get_logger().warning(f"server: {data.rstrip(bytes(1)).decode(errors='replace')}")
            if not self.session.ready and b"no_more_player" in data:
                self.get_logger().error("the server refused this player (team full, goalie taken or bad version)")
                self.finished = True
        elif kind == "bad":
            self.get_logger().warning(f"unreadable server message: {self.session.belief.errors[-1]}")
        elif kind == "think":
            self.synch = True
            self._perceive()
            self.waiting = True
            self.act_timer.reset()
        if kind == "sense_body" and self.session.stats["cycles"] % 50 == 0:
            self._write_stats()
        if kind == "sense_body" and not self.synch:
            if self.session.belief.expects_see():
                self.see_timer.reset()
            else:
                self._cycle()
        elif kind == "see" and not self.synch:
            self._cycle()
        if self.session.belief.mode == "time_over" and not self.finished:
            self.get_logger().info(f"time over: {self._score_text()}")
            self.finished = True

    def _join(self) -> None:
        b = self.session.belief
        team, n = self.session.team, b.number
        self.get_logger().info(f"playing as {team} {n} on side {b.side.value if b.side else '?'}")
        # A relaunch asks for the player back with (reconnect ...) from our UDP port: it can bind
        # that port only once this process is gone, so it never steals the player from a live one.
        port = self.sock.getsockname()[1]
        launch = [*own_launch_command(), "--ros-args", "-p", f"number:={n}", "-p", "reconnect:=true"]
        launch = self.p.launch_command([*launch, "-p", f"local_port:={port}"])
        # The player's agents share this process: one link to the ComMAg, and a hosted decision
        # talks to them without DDS. Relaunched together (host metadata) when the process dies.
        host = Host(self, name=safe_node_name(f"{team}_{n}_player"), commag=self.p.commag)
        common = {"team": team, "player_number": n, "lease": float(self.p.lease), "commag": self.p.commag}
        common["host"] = host
        perception = Agent(
            self, name=f"{team}_{n}_perception", service_class="WorldModel", launch_command=launch, **common
        )
        # One process serves both; only the perception carries the launch command, so a dead process
        # is relaunched once (the action registration comes back with it).
        action = Agent(self, name=f"{team}_{n}_action", service_class="Action", **common)
        self.perception = PerceptionService(perception, "the server has not sent a cycle")
        self.action = ActionService(
            action, lambda: (b.number, b.side or Side.LEFT), b.world, "", self._on_start, self.session.say
        )
        self.agents.extend([perception, action])  # spin() holds this very list
        if self.p.decision:
            self._host_decision(host, launch)

    def _host_decision(self, host: Host, launch: list[str]) -> None:
        """The player's decision component, unchanged, as a node of this process."""
        from rclpy.parameter import Parameter

        from cf_decision.decision_node import DecisionNode

        b = self.session.belief
        values = {"team": self.session.team, "number": b.number, "team_size": int(self.p.team_size)}
        values |= {"commag": self.p.commag, "lease": float(self.p.lease), "log_requests": bool(self.p.log_requests)}
        values["talk"] = str(self.p.talk)
        node = DecisionNode(
            host=host,
            launch=launch,
            parameter_overrides=[Parameter(k, value=v) for k, v in values.items()],
            use_global_arguments=False,  # our command line is the adapter's
        )
        self.decision = node
        self.agents.append(node.agent)
        if self.executor is not None:  # else (a relaunch joins at once) _executor() adds it
            self.executor.add_node(node)

    def _watch(self) -> None:
        now = time.monotonic()
        silent = now - self.last_heard
        reconnecting = bool(self.p.reconnect) and int(self.p.number) > 0
        if not self.attached and now - self.last_hello > (1.0 if reconnecting else 3.0):
            # The server may not be up yet, or (a relaunch) refuses to reconnect during play_on: ask
            # again. An (init ...) is repeated only after 3 s: each one that arrives takes a shirt number.
            self._hello()
        if silent > float(self.p.server_timeout) and not self.finished:
            self.get_logger().error(f"the server has been silent for {silent:.0f} s")
            self.finished = True
        if self.finished and self.exit_code is None:
            # Ends the spin (run's ``until``), which then deregisters every agent of this process:
            # raised from a callback instead, SystemExit left the executor unable to finish that.
            self._write_stats()
            self.exit_code = 0 if self.session.ready else 2

    # ---- each cycle -----------------------------------------------------------------

    def _on_see_timer(self) -> None:
        self.see_timer.cancel()
        self._cycle()

    def _on_act_timer(self) -> None:
        self.act_timer.cancel()
        self.waiting = False
        self._act()
        self._send("(done)")

    def _cycle(self) -> None:
        self.see_timer.cancel()
        if self.cycle_done == self.session.belief.steps:
            return
        self._perceive()
        self._act()

    def _perceive(self) -> None:
        if not self.session.ready:
            return
        if self.perception is not None:
            self.perception.publish(world_state(self.session.belief))

    def _act(self) -> None:
        self.cycle_done = self.session.belief.steps
        acted = self.session.act()
        for text in acted.commands:
            self._send(text)
        if acted.commands and not self.synch:
            # How long after the cycle's first message the commands went out (real time: a command
            # that reaches the server after the cycle ends runs a cycle late, and the next one not at all).
            stats = self.session.stats
            delay = int((time.monotonic() - self.cycle_heard) * 1000)
            stats["act_ms_max"] = max(stats.get("act_ms_max", 0), delay)
            stats["acts_after_50ms"] = stats.get("acts_after_50ms", 0) + (delay > 50)
        if self.action is not None:
            self.action.settle(acted.status, acted.reason, acted.name, acted.cycles)

    # ---- the services ---------------------------------------------------------------

    def _on_start(self, skill) -> None:
        """A request's skill starts (ActionService agreed to it): the session carries it out."""
        self.session.start(skill)
        if self.synch:
            # In time: carried out this cycle; late: after (done), so from the next cycle on.
            key = "requests_in_time" if self.waiting else "requests_late"
            self.session.stats[key] = self.session.stats.get(key, 0) + 1
        if self.waiting:
            # The decision answered this cycle's perception: act now rather than wait out synch_wait.
            self.act_timer.cancel()
            self._on_act_timer()

    def _score_text(self) -> str:
        b = self.session.belief
        side = b.side or Side.LEFT
        return f"{b.team} {b.score[side]} : {b.score[side.other]} {b.opponent or 'opponent'}"

    def _write_stats(self) -> None:
        path = self.p.stats_file
        if not path:
            return
        b = self.session.belief
        data = {
            **self.session.stats,
            "team": b.team,
            "number": b.number,
            "side": b.side.value if b.side else None,
            "time": b.time,
            "mode": b.mode,
            "kicks": b.counters.get("kick", 0),
            "player_type": b.type_id,
            "top_speed": b.told_top_speed(b.number),  # m/s, as the WorldState tells it
            "mate_types": b.mate_types,
            "score": [b.score[Side.LEFT], b.score[Side.RIGHT]],
            "server_errors": b.errors[-5:],
            "unexecuted_last": self.session.unexecuted,
            "synch": self.synch,
        }
        tmp = f"{path}.tmp"
        with open(tmp, "w") as f:
            json.dump(data, f)
        os.replace(tmp, path)

    def close(self) -> None:
        self._write_stats()
        if self.decision is not None:
            self.decision.log_stats()
        if self.session.ready:
            self._send("(bye)")
        self.sock.close()


def _executor(node: RcssPlayerNode):
    executor = default_executor(node)
    if node.decision is not None:  # made before there was an executor to spin it
        executor.add_node(node.decision)
    return executor


def _player() -> RcssPlayerNode:
    try:
        return RcssPlayerNode()
    except OSError as exc:  # e.g. the predecessor's port is still bound: it is alive, we are not needed
        print(f"rcss_player: cannot open the player's UDP port: {exc}", file=sys.stderr)
        raise SystemExit(4) from None


def main() -> int:
    """Entry point of ``ros2 run cf_sim_backend rcss_player``."""
    # The default executor: the events one has no guard conditions (Jazzy). The agents are
    # made once the server gave us a number: spin() holds this very list.
    return run(
        _player,
        agents=lambda node: node.agents,
        executor=_executor,
        until=lambda node: node.exit_code is not None,
        on_exit=RcssPlayerNode.close,
    )


if __name__ == "__main__":
    sys.exit(main())
