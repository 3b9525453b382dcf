"""Our whole team on a running rcssserver: the ComMAg, 11 rcss_player adapters and 11 cf_decision components.

    ros2 run cf_sim_backend rcss_team -- --team CF --port 6000 [--players 11] [--layout player] [--no-commag]

(on the bare machine: ``install/cf_sim_backend/lib/cf_sim_backend/rcss_team --team CF``).

rcssserver gives shirt numbers in the order players connect, so the adapters start one after
another: each next one once the previous has its number (its perception registered with the
ComMAg); number 1 connects as the goalkeeper. Each player's decision component, unchanged from
the embedded simulator's team, runs in its adapter's process (``--layout player``, the default:
hosted, see docs/hosting.md) or in a process of its own (``--layout process``). It runs until the server's match is over
(every adapter has exited) or until Ctrl-C, then stops everything it started.
"""

from __future__ import annotations

import argparse
import signal
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import rclpy
from ament_index_python.packages import get_package_prefix
from rclpy.executors import SingleThreadedExecutor
from rclpy.signals import SignalHandlerOptions
from rclpy.utilities import remove_ros_args

from cf_commag.given_parameters import node_name as safe_node_name
from cf_commag.respawn import Respawner
from cf_commag.transport.qos import SNAPSHOT_QOS
from cf_interfaces.msg import Registry
from cf_sim_backend.rcss import coach


def executable(package: str, name: str) -> str:
    return str(Path(get_package_prefix(package)) / "lib" / package / name)


def parse_args(argv: list[str]) -> argparse.Namespace:
    ap = argparse.ArgumentParser(prog="rcss_team", description=__doc__.split("\n\n")[0])
    ap.add_argument("--team", default="CommonFramework", help="team name on the server")
    ap.add_argument("--host", default="127.0.0.1")
    ap.add_argument("--port", type=int, default=6000, help="the server's player port")
    ap.add_argument("--players", type=int, default=11, help="how many players (1..11)")
    ap.add_argument("--commag", default="/commag", help="the ComMAg's node name")
    ap.add_argument("--no-commag", action="store_true", help="use a ComMAg that is already running")
    ap.add_argument(
        "--coach-port",
        type=int,
        default=None,
        help="the server's online coach port (default: --port + 2, as rcssserver's own defaults)",
    )
    ap.add_argument("--no-coach", action="store_true", help="do not choose heterogeneous player types (rcss_coach)")
    ap.add_argument("--log-dir", default="", help="one log file per process (default: a new temp dir)")
    ap.add_argument("--stats-dir", default="", help="each adapter writes its counters here (JSON)")
    ap.add_argument(
        "--lease", type=float, default=3.0, help="lease (s) of every component (22 processes share the CPU)"
    )
    ap.add_argument(
        "--synch-wait", type=float, default=0.1, help="synch mode: each adapter's wait for its decision (s)"
    )
    ap.add_argument(
        "--log-requests",
        action="store_true",
        help="every decision logs each new request with what it was chosen on (docs/decision.md)",
    )
    ap.add_argument(
        "--talk",
        choices=("framework", "say"),
        default="say",
        help="how team-mates' decisions talk: say (the server's say and hear only, as the rules of a competition"
        " demand; the default) or framework (times to the ball, passes and sightings over the framework;"
        " docs/decision.md)",
    )
    ap.add_argument("--join-timeout", type=float, default=30.0, help="seconds each adapter may take to join")
    ap.add_argument(
        "--layout",
        choices=("player", "process"),
        default="player",
        help="player: each adapter hosts its player's decision; process: decisions in processes of their own",
    )
    return ap.parse_args(argv)


class TeamProcesses:
    """The processes of one team, started in order and stopped together."""

    def __init__(self, args: argparse.Namespace):
        self.args = args
        self.logs = Path(args.log_dir or tempfile.mkdtemp(prefix=f"rcss-team-{args.team}-"))
        self.logs.mkdir(parents=True, exist_ok=True)
        self.procs: dict[str, subprocess.Popen] = {}
        self.registered: set[str] = set()
        self.commag: Respawner | None = None
        rclpy.init(signal_handler_options=SignalHandlerOptions.NO)  # our handlers stop the children first
        self.node = rclpy.create_node(f"rcss_team_{args.team.lower()}")
        self.node.create_subscription(Registry, f"{args.commag}/registry", self._on_registry, SNAPSHOT_QOS)
        self.executor = SingleThreadedExecutor()
        self.executor.add_node(self.node)

    def _on_registry(self, msg: Registry) -> None:
        self.registered = {c.name for c in msg.records}

    def start(self, name: str, argv: list[str]) -> None:
        log = open(self.logs / f"{name}.log", "ab")  # noqa: SIM115 - the child writes it
        self.procs[name] = subprocess.Popen(argv, stdout=log, stderr=subprocess.STDOUT, start_new_session=True)
        log.close()

    def spin_once(self, timeout: float) -> None:
        self.executor.spin_once(timeout_sec=timeout)
        if self.commag is not None and self.commag.poll():
            print(f"the ComMAg exited ({self.commag.exits[-1]}): started again", flush=True)

    def wait_for(self, name: str, process: str, timeout: float) -> None:
        deadline = time.monotonic() + timeout
        while name not in self.registered:
            if self.procs[process].poll() is not None:
                raise RuntimeError(f"{process} exited with {self.procs[process].returncode}: see {self.logs}")
            if time.monotonic() > deadline:
                raise RuntimeError(f"{name} did not register in {timeout:.0f} s: see {self.logs}")
            self.spin_once(0.1)

    def run(self) -> int:
        a = self.args
        ros = ["--ros-args", "-p"]
        if not a.no_commag:
            node = a.commag.strip("/")
            argv = [executable("cf_commag", "commag"), "--ros-args", "-r", f"__node:={node}"]
            # A fresh registry per match: components of an earlier match must not be relaunched.
            argv += ["-p", f"persistence_path:={self.logs / 'registry.json'}", "-p", f"log_dir:={self.logs}"]
            argv += ["-p", "stop_launched_on_exit:=true"]  # relaunched components end with the team
            # 23 processes on a small machine: a relaunched one may need more than 5 s to register.
            argv += ["-p", f"startup_grace:={max(5.0, 3 * a.lease)}"]
            # Supervised like launch's respawn=True: a ComMAg that dies comes back with every registration.
            self.commag = Respawner(argv, log=self.logs / "commag.log")
            self.commag.start()
        for n in range(1, a.players + 1):
            stats = ["-p", f"stats_file:={Path(a.stats_dir) / f'{a.team}_{n}.json'}"] if a.stats_dir else []
            argv = [executable("cf_sim_backend", "rcss_player"), *ros, f"team:={a.team}", "-p", f"host:={a.host}"]
            argv += ["-p", f"port:={a.port}", "-p", f"commag:={a.commag}", "-p", f"goalie:={str(n == 1).lower()}"]
            argv += ["-p", f"lease:={a.lease}", "-p", f"synch_wait:={a.synch_wait}"]
            if a.layout == "player":
                argv += ["-p", "decision:=true", "-p", f"team_size:={a.players}"]
                argv += ["-p", "log_requests:=true"] if a.log_requests else []
                argv += ["-p", f"talk:={a.talk}"]
            argv += ["-r", f"__node:={safe_node_name(f'{a.team}_{n}_rcss_player')}"]  # the server gives n in order
            self.start(f"{a.team}_{n}_rcss_player", argv + stats)
            self.wait_for(f"{a.team}_{n}_perception", f"{a.team}_{n}_rcss_player", a.join_timeout)
            print(f"player {n} joined", flush=True)
        for n in range(1, a.players + 1):
            if a.layout == "player":  # hosted by the adapter: registered once it has its number
                self.wait_for(f"{a.team}_{n}_decision", f"{a.team}_{n}_rcss_player", a.join_timeout)
                continue
            argv = [executable("cf_decision", "decision"), *ros, f"team:={a.team}", "-p", f"number:={n}"]
            argv += ["-p", f"team_size:={a.players}", "-p", f"commag:={a.commag}", "-p", f"lease:={a.lease}"]
            argv += ["-p", "log_requests:=true"] if a.log_requests else []
            argv += ["-p", f"talk:={a.talk}"]
            # One after another too: eleven Python processes starting at once starve the running adapters.
            self.start(f"{a.team}_{n}_decision", argv)
            self.wait_for(f"{a.team}_{n}_decision", f"{a.team}_{n}_decision", a.join_timeout)
        if not a.no_coach:
            self.choose_types()
        print(f"team {a.team}: {a.players} players and their decisions are up; logs in {self.logs}", flush=True)
        adapters = [p for name, p in self.procs.items() if name.endswith("_rcss_player")]
        while any(p.poll() is None for p in adapters):
            self.spin_once(0.2)
        # Adapters the ComMAg relaunched are not our children: let them finish (deregister) too.
        ours = {f"{a.team}_{n}_perception" for n in range(1, a.players + 1)}
        deadline = time.monotonic() + 10.0
        while self.registered & ours and time.monotonic() < deadline:
            self.spin_once(0.2)
        ended = {name: p.returncode for name, p in self.procs.items() if name.endswith("_rcss_player")}
        killed = [name for name, code in ended.items() if code < 0]  # by a signal: the ComMAg relaunched them
        failed = [name for name, code in ended.items() if code > 0]
        print(f"the match is over; adapters killed (relaunched by the ComMAg): {killed or 'none'}", flush=True)
        print(f"adapters that failed: {failed or 'none'}", flush=True)
        return 1 if failed else 0

    def choose_types(self) -> None:
        """Our online coach picks each player's type now, before the kick-off; a refusal is logged, not fatal."""
        a = self.args
        port = a.coach_port if a.coach_port is not None else a.port + 2
        try:
            chosen, answers = coach.run(a.team, a.host, port, a.players)
        except (OSError, RuntimeError) as exc:
            print(f"the coach could not choose player types: {exc}", flush=True)
            return
        said = ", ".join(f"{n}: {t} ({answers.get(n, 'no answer')})" for n, t in sorted(chosen.items()))
        print(f"player types chosen by the coach: {said}", flush=True)

    def stop(self) -> None:
        if self.commag is not None:
            self.commag.stop()  # it kills what it relaunched (stop_launched_on_exit)
        for p in self.procs.values():
            if p.poll() is None:
                p.send_signal(signal.SIGINT)  # components deregister on SIGINT
        deadline = time.monotonic() + 5.0
        for p in self.procs.values():
            try:
                p.wait(timeout=max(0.1, deadline - time.monotonic()))
            except subprocess.TimeoutExpired:
                p.kill()
        self.node.destroy_node()
        rclpy.try_shutdown()


def main(argv: list[str] | None = None) -> int:
    """Entry point of ``ros2 run cf_sim_backend rcss_team``."""
    # ros2 launch adds --ros-args ...: they are ROS's, not ours.
    args = parse_args(remove_ros_args(sys.argv)[1:] if argv is None else argv)
    team = TeamProcesses(args)

    def interrupt(signum, frame):
        raise KeyboardInterrupt

    signal.signal(signal.SIGTERM, interrupt)
    signal.signal(signal.SIGINT, interrupt)
    try:
        return team.run()
    except KeyboardInterrupt:
        return 130
    except RuntimeError as exc:
        print(f"rcss_team: {exc}", file=sys.stderr)
        return 1
    finally:
        team.stop()


if __name__ == "__main__":
    sys.exit(main())
