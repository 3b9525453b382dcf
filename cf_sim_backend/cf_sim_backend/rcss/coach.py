"""Our online coach on rcssserver: it picks each player's heterogeneous type before the kick-off (ROS-free core).

    install/cf_sim_backend/lib/cf_sim_backend/rcss_coach --team CF --port 6002
    (on a full ROS 2 install: ros2 run cf_sim_backend rcss_coach -- --team CF --port 6002)

At the first kick-off the referee gives every player no coach has changed a type of its own, in
shirt-number order (``Team::assignPlayerTypes``): with rcssserver 19's 18 random types, each
allowed once, that left our number 6 at 0.75 m/cycle where the default type runs 1.0. So the
coach, before the kick-off, keeps the default type for the goalkeeper and hands out the fastest
of the other types (each once) in the order ``player_types.ORDER`` gives: the centre forward, the centre backs,
the wide forwards, ... The players read their new type's parameters (kickable area, dash rate,
decay, ...) from the server's ``(change_player_type N T)``, so their skills follow it. The coach
then says ``(bye)``: in synch mode a connected coach must answer every cycle, and it has nothing
more to say.
"""

from __future__ import annotations

import argparse
import socket
import sys
import time

from cf_sim_backend.player_types import PlayerType, choose_types
from cf_sim_backend.rcss.protocol import param_pairs, parse

NEEDED = {"id", "dash_power_rate", "effort_max", "player_decay", "player_speed_max", "stamina_inc_max"}


def player_type(msg: list) -> PlayerType | None:
    """From a parsed ``(player_type (id N) (name value) ...)`` message (None: a value the coach needs
    is missing or not a number)."""
    values = param_values(msg)
    return PlayerType.from_values(values) if values.keys() >= NEEDED else None


def param_values(msg: list) -> dict[str, float]:
    """A parameter message's (name value) pairs whose value is a number."""
    return {name: value for name, value in param_pairs(msg).items() if isinstance(value, float)}


class CoachClient:
    """The online coach's conversation with the server over UDP."""

    def __init__(self, team: str, host: str = "127.0.0.1", port: int = 6002, timeout: float = 5.0):
        self.team, self.timeout = team, timeout
        self.addr = (socket.gethostbyname(host), port)
        self.sock = socket.socket(socket.AF_INET, socket.SOCK_DGRAM)
        self.sock.bind(("127.0.0.1" if self.addr[0].startswith("127.") else "", 0))
        self.sock.settimeout(0.1)
        self.types: dict[int, PlayerType] = {}
        self.pt_max = 1
        self.type_count = 18  # rcssserver 19's player_types, until its player_param says
        self.log: list[str] = []

    def send(self, text: str) -> None:
        self.sock.sendto(text.encode() + b"\0", self.addr)

    def receive(self) -> list | None:
        """One message (None: none came within 0.1 s); answers ``(think)`` with ``(done)``."""
        try:
            data, addr = self.sock.recvfrom(1 << 16)
        except TimeoutError:
            return None
        if addr[0] != self.addr[0]:
            self.log.append(f"dropped a datagram from {addr[0]}, not the server")
            return None
        self.addr = addr  # the server answers from the port it keeps for this client
        try:
            msg = parse(data)
        except ValueError as exc:  # a message we cannot read (LanguageError, bad bytes) is logged, never fatal
            self.log.append(f"unreadable: {exc}")
            return None
        if not isinstance(msg, list):
            self.log.append(f"not a message: {msg!r}")
            return None
        kind = str(msg[0]) if msg else ""
        if kind == "think":
            self.send("(done)")
        elif kind == "player_type":
            offered = player_type(msg)
            if offered is not None:
                self.types[offered.id] = offered
        elif kind == "player_param":
            values = param_values(msg)
            self.pt_max = int(values.get("pt_max", self.pt_max))
            self.type_count = int(values.get("player_types", self.type_count))
        elif kind in ("error", "warning"):
            self.log.append(" ".join(str(x) for x in msg))
        return msg

    def connect(self, version: int = 19) -> str:
        """Join as the team's online coach; returns our side ("l" or "r")."""
        deadline = time.monotonic() + self.timeout
        while time.monotonic() < deadline:
            self.send(f"(init {self.team} (version {version}))")
            end = time.monotonic() + 0.5
            while time.monotonic() < end:
                msg = self.receive()
                if msg and str(msg[0]) == "init" and len(msg) >= 3 and str(msg[2]) == "ok":
                    return str(msg[1])
                if msg and str(msg[0]) == "error":
                    raise RuntimeError(f"the server refused the coach: {msg}")
        raise RuntimeError(f"no answer from the server's coach port {self.addr[1]}")

    def wait_for_types(self) -> None:
        """Read until the server has sent its player types (it does right after init)."""
        deadline = time.monotonic() + self.timeout
        while len(self.types) < self.type_count and time.monotonic() < deadline:
            self.receive()
        if not self.types:
            raise RuntimeError("the server sent no player types")

    def change_types(self, chosen: dict[int, int]) -> dict[int, str]:
        """Ask for each change; returns shirt number -> the server's answer ("ok" or its warning)."""
        answers: dict[int, str] = {}
        for number, type_id in chosen.items():
            self.send(f"(change_player_type {number} {type_id})")
        deadline = time.monotonic() + self.timeout
        while len(answers) < len(chosen) and time.monotonic() < deadline:
            msg = self.receive()
            if not msg:
                continue
            kind = str(msg[0])
            if kind == "ok" and len(msg) >= 3 and str(msg[1]) == "change_player_type":
                answers[int(msg[2])] = "ok"
            elif kind in ("warning", "error"):
                # The server does not say which request a warning answers: give it to the first unanswered.
                pending = [n for n in chosen if n not in answers]
                if pending:
                    answers[pending[0]] = " ".join(str(x) for x in msg[1:])
        return answers

    def close(self) -> None:
        try:
            self.send("(bye)")
        finally:
            self.sock.close()


def run(team: str, host: str, port: int, players: int, timeout: float = 5.0) -> tuple[dict[int, int], dict[int, str]]:
    """Connect, choose the types, ask for them, leave; returns (chosen, answers)."""
    client = CoachClient(team, host, port, timeout)
    try:
        client.connect()
        client.wait_for_types()
        chosen = choose_types(list(client.types.values()), list(range(1, players + 1)), pt_max=client.pt_max)
        return chosen, client.change_types(chosen)
    finally:
        client.close()


def main(argv: list[str] | None = None) -> int:
    """Entry point of ``rcss_coach``."""
    ap = argparse.ArgumentParser(prog="rcss_coach", description=__doc__.split("\n\n")[0])
    ap.add_argument("--team", required=True, help="our team's name on the server")
    ap.add_argument("--host", default="127.0.0.1")
    ap.add_argument("--port", type=int, default=6002, help="the server's online coach port (olcoach_port)")
    ap.add_argument("--players", type=int, default=11)
    ap.add_argument("--timeout", type=float, default=5.0, help="seconds each step may take")
    args = ap.parse_args(argv)
    try:
        chosen, answers = run(args.team, args.host, args.port, args.players, args.timeout)
    except (OSError, RuntimeError) as exc:
        print(f"rcss_coach: {exc}", file=sys.stderr)
        return 1
    for number, type_id in sorted(chosen.items()):
        print(f"player {number}: type {type_id}: {answers.get(number, 'no answer')}", flush=True)
    return 0 if all(answers.get(n) == "ok" for n in chosen) else 1


if __name__ == "__main__":
    sys.exit(main())
