"""A short match of our team on a real rcssserver, for the integration tests and the benchmark.

    python tools/rcss_match.py --server $RCSSSERVER [--players 11] [--opponents 0] [--cycles 300]
                               [--realtime] [--layout player|process] [--out DIR] [--no-isolate] [--game-log]
                               [--kick-off referee|trainer] [--no-coach] [--log-requests] [--talk framework|say]

It starts the server (synch mode unless --realtime; trainer with referee; logs off; its own
config dir), our team with ``rcss_team`` (the ComMAg, the adapters, the decisions), optionally
a second instance of our team as the opponent, and a trainer that kicks off once every player
is up (the server would otherwise kick off on its own before our players have joined) and
answers ``(done)`` in synch mode. It kicks off with the referee's own ``(start)``, as a monitor's
button does, so the server hands out heterogeneous player types as in a competition (our coach
and the opponent's choose theirs before it; docs/rcssserver.md); ``--kick-off trainer`` sets the
play mode instead, and every player no coach changed keeps the default type. At time over it
collects each adapter's counters and prints one JSON summary on stdout.

rcssserver always binds 0.0.0.0. Unless --no-isolate, the whole match runs in a private network
namespace (``unshare -n``, loopback only), so nothing is reachable from outside and parallel runs
cannot collide.
"""

from __future__ import annotations

import argparse
import contextlib
import json
import os
import re
import shlex
import shutil
import signal
import socket
import subprocess
import sys
import tempfile
import time
from collections.abc import Callable
from pathlib import Path

from ament_index_python.packages import get_package_prefix
from proctree import PASSED_ON, CpuMeter, descendants, run_passing_on

POLL_SPAN = 0.2  # s a trainer's poll reads for at most
TEAM_EXIT_WAIT = 60.0  # s the team has to leave once time is over (it leaves as soon as it can)
# What is played once everyone is up: (args, trainer, server, our team's processes, summary); time over ends it.
Play = Callable[[argparse.Namespace, "Trainer", subprocess.Popen, list, dict], None]


def udp_port_open(port: int) -> bool:
    for table in ("/proc/net/udp", "/proc/net/udp6"):
        try:
            lines = Path(table).read_text().splitlines()[1:]
        except OSError:
            continue
        if any(line.split()[1].endswith(f":{port:04X}") for line in lines):
            return True
    return False


class Trainer:
    """The offline coach: kicks off, answers (done) in synch mode, reads the referee's messages."""

    def __init__(self, port: int):
        self.sock = socket.socket(socket.AF_INET, socket.SOCK_DGRAM)
        self.sock.bind(("127.0.0.1", 0))
        self.sock.settimeout(0.05)
        self.addr = ("127.0.0.1", port)
        self.mode = "before_kick_off"
        self.time = 0
        self.thinks = 0  # synch mode, the eye on: the server's (think)s, one a simulation step in any play mode
        self.looked: str | None = None
        self.half_time = False  # the referee called half time

    def send(self, text: str) -> None:
        self.sock.sendto(text.encode() + b"\0", self.addr)

    def connect(self) -> None:
        for _ in range(100):
            self.send("(init (version 19))")
            try:
                data, addr = self.sock.recvfrom(65536)
            except TimeoutError:
                continue
            if data.startswith(b"(init ok"):
                self.addr = addr
                return
        raise RuntimeError("the trainer could not connect")

    def players(self, team: str) -> int:
        """How many players of ``team`` are on the field (the server answers the trainer's look)."""
        self.send("(look)")
        for _ in range(40):
            self.poll()
            if self.looked is not None:
                seen, self.looked = self.looked, None
                return len(set(re.findall(rf'\(\(p "{re.escape(team)}" (\d+)', seen)))
        return 0

    def poll(self) -> None:
        """Read what is there (for at most POLL_SPAN s: with the eye on and no player left, the server
        steps as fast as we answer); answer (think) with (done)."""
        end = time.monotonic() + POLL_SPAN
        while time.monotonic() < end:
            try:
                data, _ = self.sock.recvfrom(65536)
            except TimeoutError:
                return
            text = data.rstrip(b"\0").decode(errors="replace")
            if text.startswith("(ok look"):
                self.looked = text
            elif text == "(think)":
                self.thinks += 1
                self.send("(done)")
            elif text.startswith("(see_global "):  # the eye on: the game time every step
                self.time = int(text[12 : text.index(" ", 12)])
            elif text.startswith("(hear ") and " referee " in text:  # (hear referee TIME MODE) for a trainer
                parts = text.strip("()").split()
                self.mode = parts[-1]
                self.half_time |= self.mode == "half_time"
                self.time = next((int(p) for p in parts if p.isdigit()), self.time)


def kill_adapter(team: str, number: int, root: int) -> int | None:
    """kill -9 the adapter of our player ``number`` (found by its stats file) among the processes
    below ``root`` (our team's), not another match's on the same machine; returns its pid."""
    for pid in descendants(root):
        try:
            argv = Path(f"/proc/{pid}/cmdline").read_bytes().split(b"\0")
        except OSError:
            continue
        if any(a.endswith(b"rcss_player") for a in argv) and any(
            a.endswith(f"/{team}_{number}.json".encode()) for a in argv
        ):
            os.kill(pid, signal.SIGKILL)
            return pid
    return None


def relaunched_processes(commag_log: str) -> int:
    """Processes the ComMAg started again that came back: the agents of one host count once."""
    count, joined = 0, set()
    for line in commag_log.splitlines():
        m = re.search(r"\]: (\w+): (relaunching|relaunched) \((.*)\)$", line)
        if not m:
            continue
        name, kind, reason = m.groups()
        if kind == "relaunching":
            (joined.add if "with its host" in reason else joined.discard)(name)
        elif name not in joined:
            count += 1
    return count


def set_aside_earlier(out: Path) -> Path | None:
    """Move an earlier match's files in ``out`` into ``out/earlier-N`` (None: there were none).

    The players' logs are appended to (a relaunched process carries on in its log), and the
    analysis tools read a match directory's game log and logs: a match played again into the same
    directory would have mixed its lines with the earlier one's.
    """
    if not out.is_dir():
        return None
    ours = {"server.log", "error.log", "conf", "stats"}
    found = [
        p
        for p in out.iterdir()
        if p.suffix in (".rcg", ".rcl") or p.name in ours or p.name.startswith(("team-", "logs-"))
    ]
    if not found:
        return None
    n = 1
    while (out / f"earlier-{n}").exists():
        n += 1
    aside = out / f"earlier-{n}"
    aside.mkdir()
    for p in found:
        p.rename(aside / p.name)
    print(f"rcss_match: an earlier match's files in {out} are now in {aside}", file=sys.stderr, flush=True)
    return aside


def run(args: argparse.Namespace, play: Play | None = None) -> dict:
    """Start the server, the trainer and both teams, ``play`` (a match unless told), stop them all; the summary."""
    out = Path(args.out or tempfile.mkdtemp(prefix="rcss-match-")).resolve()
    set_aside_earlier(out)
    (out / "conf").mkdir(parents=True, exist_ok=True)
    (out / "stats").mkdir(exist_ok=True)
    port = args.port
    half_seconds = max(1, args.cycles // 10 // args.halves)
    server_argv = [
        args.server,
        f"server::synch_mode={'false' if args.realtime else 'true'}",
        # Synch mode: the server polls for the clients' (done) every synch_micro_sleep µs (1 by default:
        # it spins, taking a core's share from the players it waits for); 0.5 ms is plenty.
        "server::synch_micro_sleep=500",
        "server::auto_mode=false",
        "server::coach_w_referee=true",
        *([f"player::random_seed={args.seed}"] if args.seed >= 0 else []),
        f"server::game_logging={'true' if args.game_log else 'false'}",
        "server::text_logging=false",
        f"server::half_time={half_seconds}",
        f"server::nr_normal_halfs={args.halves}",
        "server::nr_extra_halfs=0",
        "server::penalty_shoot_outs=false",
        f"server::port={port}",
        f"server::coach_port={port + 1}",
        f"server::olcoach_port={port + 2}",
        f"server::game_log_dir={out}",
        f"server::text_log_dir={out}",
    ]
    env = {**os.environ, "RCSS_CONF_DIR": str(out / "conf")}
    procs: list[subprocess.Popen] = []
    summary: dict = {"out": str(out)}
    with open(out / "server.log", "wb") as log:
        server = subprocess.Popen(server_argv, stdout=log, stderr=subprocess.STDOUT, env=env, start_new_session=True)
    procs.append(server)
    try:
        deadline = time.monotonic() + 20
        while not udp_port_open(port):
            if server.poll() is not None or time.monotonic() > deadline:
                raise RuntimeError(f"rcssserver did not start: see {out / 'server.log'}")
            time.sleep(0.1)
        trainer = Trainer(port + 1)
        trainer.connect()
        trainer.send("(ear on)")  # the referee's decisions
        team_exe = str(Path(get_package_prefix("cf_sim_backend")) / "lib" / "cf_sim_backend" / "rcss_team")
        teams = [(args.team, args.players)] + ([(args.opponent, args.opponents)] if args.opponents else [])
        team_procs = []
        for i, (name, players) in enumerate(teams):
            argv = [team_exe, "--team", name, "--port", str(port), "--players", str(players), "--layout", args.layout]
            argv += ["--no-coach"] if args.no_coach else []
            argv += ["--log-requests"] if args.log_requests and i == 0 else []
            argv += ["--talk", args.talk]
            argv += ["--log-dir", str(out / f"logs-{name}"), "--stats-dir", str(out / "stats")]
            if i > 0:
                argv += ["--no-commag"]  # one ComMAg serves both teams
            with open(out / f"team-{name}.log", "wb") as log:
                p = subprocess.Popen(argv, stdout=log, stderr=subprocess.STDOUT, start_new_session=True)
            procs.append(p)
            team_procs.append(p)
            deadline = time.monotonic() + 60 + 10 * players
            while b"are up" not in (out / f"team-{name}.log").read_bytes():
                trainer.poll()
                if p.poll() is not None or time.monotonic() > deadline:
                    raise RuntimeError(f"team {name} did not come up: see {out / f'team-{name}.log'}")
            time.sleep(0.2)
        if args.opponent_cmd:  # a real opponent: its own start command, on the same server
            text = args.opponent_cmd.format(team=args.opponent, host="127.0.0.1", port=port)
            with open(out / f"team-{args.opponent}.log", "wb") as log:
                p = subprocess.Popen(shlex.split(text), stdout=log, stderr=subprocess.STDOUT, start_new_session=True)
            procs.append(p)
            deadline = time.monotonic() + 90
            while trainer.players(args.opponent) < args.opponent_players:
                if p.poll() is not None and trainer.players(args.opponent) == 0:
                    raise RuntimeError(
                        f"the opponent exited with {p.returncode}: see {out / f'team-{args.opponent}.log'}"
                    )
                if time.monotonic() > deadline:
                    raise RuntimeError(f"the opponent did not bring {args.opponent_players} players in 90 s")
            summary["opponent"] = args.opponent
        (play or play_match)(args, trainer, server, team_procs, summary)
        # The team leaves on its own once time is over; on a loaded machine (a CI run beside it) its
        # eleven players, their decisions and the ComMAg had not shut down 15 s after.
        end = time.monotonic() + TEAM_EXIT_WAIT
        while any(p.poll() is None for p in team_procs) and time.monotonic() < end:
            trainer.poll()
        summary["team_exit_codes"] = [p.poll() for p in team_procs]
    finally:
        for s in PASSED_ON:  # a second SIGINT or SIGTERM (a Ctrl-C reaches us twice) would cut this short
            signal.signal(s, signal.SIG_IGN)
        for p in reversed(procs):
            if p.poll() is None:
                p.send_signal(signal.SIGINT)
        for p in reversed(procs):
            with contextlib.suppress(subprocess.TimeoutExpired):
                p.wait(timeout=10)
            # Each was started in a session (and process group) of its own; what is left of the group
            # once its leader is gone, or 10 s on, goes too: HELIOS base's start script ends at once
            # and leaves its eleven players running.
            with contextlib.suppress(ProcessLookupError):
                os.killpg(p.pid, signal.SIGKILL)
    summary["server_exit_code"] = server.returncode
    summary["players"] = players = [json.loads(f.read_text()) for f in sorted((out / "stats").glob("*.json"))]
    summary.update(command_counts(players))
    commag_log = out / f"logs-{args.team}" / "commag.log"
    events = commag_log.read_text(errors="replace") if commag_log.exists() else ""
    summary["relaunched"] = relaunched_processes(events)
    summary["agents_relaunched"] = events.count(": relaunched (")
    summary["withdrawn"] = events.count(": withdrawn (")
    return summary


def kick_off(args: argparse.Namespace, trainer: Trainer) -> None:
    """Once everyone is up: give the decisions time to find their providers and move into formation, then kick off."""
    for _ in range(30):
        trainer.poll()
    if args.kick_off == "referee":
        # The referee's kick-off (what a monitor's button sends) gives every player no coach has
        # changed a type; coaches choose theirs before it (HELIOS base's once 10 cycles have stood still).
        for _ in range(40):
            trainer.poll()
        trainer.send("(start)")
    else:
        trainer.send("(change_mode kick_off_l)")


def play_match(
    args: argparse.Namespace, trainer: Trainer, server: subprocess.Popen, team_procs: list, summary: dict
) -> None:
    """Kick off once everyone is up, play until time over, and put our CPU per cycle and the team's exit in ``summary``."""
    t0 = time.monotonic()
    kick_off(args, trainer)
    meter = CpuMeter(team_procs[0].pid)  # our team: its ComMAg, adapters, decisions, relaunches
    meter.start()
    sampled, start_cycle = time.monotonic(), trainer.time
    deadline = time.monotonic() + args.timeout
    kill = tuple(int(v) for v in args.kill.split("@")) if args.kill else None
    half_time_seen = None  # when the second half's before_kick_off began (its kick-off is the trainer's too)
    while trainer.mode != "time_over":
        trainer.poll()
        if trainer.half_time and half_time_seen is None:
            half_time_seen = time.monotonic()
        if half_time_seen and trainer.mode == "before_kick_off" and time.monotonic() - half_time_seen > 2.0:
            trainer.send("(change_mode kick_off_r)")
            half_time_seen = 0.0  # done: a falsy non-None
        if time.monotonic() - sampled > 1.0:
            meter.sample()
            sampled = time.monotonic()
        if kill and trainer.time >= kill[1] and "killed" not in summary:
            summary["killed"] = {
                "number": kill[0],
                "cycle": trainer.time,
                "pid": kill_adapter(args.team, kill[0], team_procs[0].pid),
            }
        if server.poll() is not None:
            raise RuntimeError(f"rcssserver exited with {server.returncode}: see {summary['out']}/server.log")
        if time.monotonic() > deadline:
            raise RuntimeError(f"the match did not end in {args.timeout} s (at cycle {trainer.time})")
    meter.sample()
    cycles = max(1, trainer.time - start_cycle)
    summary["seconds"] = round(time.monotonic() - t0, 1)
    summary["our_cpu_ms_per_cycle"] = round(1000 * meter.used() / cycles, 2)
    summary["our_cpu_ms_per_player_cycle"] = round(1000 * meter.used() / cycles / args.players, 2)


def command_counts(players: list[dict]) -> dict:
    """Body commands our players sent and the server executed, those it did not by kind, and how late any went out."""
    sent = sum(p["body_commands"] for p in players)
    executed = sum(p["executed"] for p in players)
    unexecuted: dict[str, int] = {}
    for p in players:
        for key, n in p.items():
            if key.startswith("unexecuted_") and isinstance(n, int):
                unexecuted[key.removeprefix("unexecuted_")] = unexecuted.get(key.removeprefix("unexecuted_"), 0) + n
    return {
        "sent": sent,
        "executed": executed,
        "executed_share": executed / max(1, sent),
        "unexecuted": unexecuted,
        "acts_after_50ms": sum(p.get("acts_after_50ms", 0) for p in players),
        "act_ms_max": max((p.get("act_ms_max", 0) for p in players), default=0),
    }


def parser(description: str = __doc__.split("\n\n")[0]) -> argparse.ArgumentParser:
    """The options of a match on rcssserver (a drill adds its own)."""
    ap = argparse.ArgumentParser(description=description)
    ap.add_argument("--server", default=os.environ.get("RCSSSERVER", ""), help="rcssserver binary ($RCSSSERVER)")
    ap.add_argument("--team", default="CF")
    ap.add_argument("--opponent", default="CFB")
    ap.add_argument("--players", type=int, default=11)
    ap.add_argument("--opponents", type=int, default=0, help="players of a second instance of our team")
    ap.add_argument("--cycles", type=int, default=300, help="match length (multiple of 10 per half)")
    ap.add_argument(
        "--halves", type=int, default=1, choices=(1, 2), help="halves (the other side kicks off the second)"
    )
    ap.add_argument("--seed", type=int, default=-1, help="the server's seed of heterogeneous player types")
    ap.add_argument("--port", type=int, default=6000)
    ap.add_argument("--realtime", action="store_true", help="real time (100 ms cycles) instead of synch mode")
    ap.add_argument(
        "--layout", choices=("player", "process"), default="player", help="rcss_team's layout (see rcss_team --help)"
    )
    ap.add_argument("--timeout", type=float, default=600.0, help="seconds the match may take")
    ap.add_argument("--out", default="", help="where logs and counters go (default: a new temp dir)")
    ap.add_argument("--kill", default="", help="N@CYCLE: kill -9 our player N's adapter at that cycle")
    ap.add_argument("--no-isolate", action="store_true", help="do not run in a private network namespace")
    ap.add_argument("--game-log", action="store_true", help="let the server write its game log (.rcg) into --out")
    ap.add_argument(
        "--opponent-cmd",
        default="",
        help="start command of another team, {team} {host} {port} filled in (run as argv, no shell), e.g. "
        "'/path/to/helios-base/src/start.sh -t {team} -p {port}'",
    )
    ap.add_argument("--opponent-players", type=int, default=11, help="players the opponent brings")
    ap.add_argument(
        "--kick-off",
        choices=("referee", "trainer"),
        default="referee",
        help="referee: the server's own kick-off, as in a competition (it hands out heterogeneous player types "
        "to the players no coach has changed); trainer: the trainer sets the play mode (everyone keeps the "
        "default type; how series were played before session 25)",
    )
    ap.add_argument("--no-coach", action="store_true", help="our team without its coach (rcss_team --no-coach)")
    ap.add_argument(
        "--talk", choices=("framework", "say"), default="say", help="how our players talk (rcss_team --talk)"
    )
    ap.add_argument(
        "--log-requests", action="store_true", help="our decisions log every new request (rcss_team --log-requests)"
    )
    return ap


def main() -> int:
    ap = parser()
    return launch(ap, ap.parse_args())


def launch(
    ap: argparse.ArgumentParser,
    args: argparse.Namespace,
    play: Play | None = None,
    report: Callable[[dict], None] = lambda summary: print(json.dumps(summary), flush=True),
) -> int:
    """Run ``play`` (a match unless told) in a private network namespace unless --no-isolate (the
    script runs itself again inside it), and ``report`` its summary."""
    if not args.server:
        ap.error("name the rcssserver binary with --server or RCSSSERVER")
    if not args.no_isolate and os.environ.get("CF_RCSS_ISOLATED") != "1":
        if not shutil.which("unshare"):
            ap.error("unshare is missing: install util-linux or pass --no-isolate")
        argv = ["unshare", "-n", "--", sys.executable, *sys.argv]
        return run_passing_on(argv, env={**os.environ, "CF_RCSS_ISOLATED": "1"}).returncode
    if os.environ.get("CF_RCSS_ISOLATED") == "1":
        subprocess.run(["ip", "link", "set", "lo", "up"], check=True)
    signal.signal(signal.SIGTERM, stop)  # as SIGINT does: the finally clauses stop what the match started
    try:
        report(run(args, play))
    finally:
        if os.environ.get("CF_RCSS_ISOLATED") == "1":
            kill_namespace_leftovers()
    return 0


def stop(signum: int, _frame: object) -> None:
    raise SystemExit(128 + signum)


def kill_namespace_leftovers() -> None:
    """Kill every other process in our private network namespace (whatever was relaunched in it)."""
    own = os.readlink("/proc/self/ns/net")
    for entry in Path("/proc").iterdir():
        if not entry.name.isdigit() or int(entry.name) == os.getpid():
            continue
        try:
            if os.readlink(entry / "ns" / "net") == own:
                os.kill(int(entry.name), signal.SIGKILL)
        except OSError:
            continue  # gone already, or not ours to read


if __name__ == "__main__":
    sys.exit(main())
