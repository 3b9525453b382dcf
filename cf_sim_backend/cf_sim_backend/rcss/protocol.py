"""Reading the RoboCup Soccer Simulation server's (rcssserver 19) messages, and its field's landmarks (ROS-free).

The server speaks S-expressions, so cf_lang's reader parses every message. Coordinates here are the
server's own: x towards the right goal, y towards the bottom ("b") side line, angles in degrees,
positive clockwise on the field as drawn (that is, counter-clockwise in x-right/y-down axes).
This is the first piece of the rcssserver adapter (issue #8).
"""

from __future__ import annotations

import re
from dataclasses import dataclass, field

from cf_lang.sexp import Limits, loads

# rcssserver messages can be long (server_param has ~200 entries); they are still small.
RCSS_LIMITS = Limits(max_bytes=1 << 16, max_depth=16, max_atoms=20_000)


def parse(text: str | bytes) -> list:
    """One server message as an S-expression (a trailing NUL, as sent over UDP, is ignored)."""
    text = text.rstrip(b"\x00") if isinstance(text, bytes) else text.rstrip("\x00")
    return loads(text, limits=RCSS_LIMITS)


def param_pairs(msg: list) -> dict[str, float | str]:
    """A parameter message's ``(name value)`` pairs (server_param, player_param, player_type):
    numbers as floats, anything else as its text."""
    return {
        str(item[0]): float(item[1]) if isinstance(item[1], (int, float)) else str(item[1])
        for item in msg[1:]
        if isinstance(item, list) and len(item) == 2
    }


def _flags() -> dict[str, tuple[float, float]]:
    """rcssserver's landmarks: field corners, centre, goals, penalty areas, and the flags 5 m outside."""
    out = {
        "f c": (0.0, 0.0),
        "f c t": (0.0, -34.0),
        "f c b": (0.0, 34.0),
        "f l t": (-52.5, -34.0),
        "f l b": (-52.5, 34.0),
        "f r t": (52.5, -34.0),
        "f r b": (52.5, 34.0),
        "g l": (-52.5, 0.0),
        "g r": (52.5, 0.0),
        "f g l t": (-52.5, -7.01),
        "f g l b": (-52.5, 7.01),
        "f g r t": (52.5, -7.01),
        "f g r b": (52.5, 7.01),
        "f p l t": (-36.0, -20.16),
        "f p l c": (-36.0, 0.0),
        "f p l b": (-36.0, 20.16),
        "f p r t": (36.0, -20.16),
        "f p r c": (36.0, 0.0),
        "f p r b": (36.0, 20.16),
        "f t 0": (0.0, -39.0),
        "f b 0": (0.0, 39.0),
        "f l 0": (-57.5, 0.0),
        "f r 0": (57.5, 0.0),
    }
    for n in (10, 20, 30, 40, 50):
        out[f"f t l {n}"], out[f"f t r {n}"] = (-float(n), -39.0), (float(n), -39.0)
        out[f"f b l {n}"], out[f"f b r {n}"] = (-float(n), 39.0), (float(n), 39.0)
    for n in (10, 20, 30):
        out[f"f l t {n}"], out[f"f l b {n}"] = (-57.5, -float(n)), (-57.5, float(n))
        out[f"f r t {n}"], out[f"f r b {n}"] = (57.5, -float(n)), (57.5, float(n))
    return out


FLAGS = _flags()


@dataclass
class Seen:
    """One object in a see message: its name (e.g. "f c t", "b", "p PyTest 3") and what was measured."""

    name: str
    distance: float | None
    direction: float
    extra: list = field(default_factory=list)


@dataclass
class See:
    time: int
    objects: list[Seen]

    def flags(self) -> list[tuple[tuple[float, float], float, float]]:
        """(known position, distance, direction) of every landmark seen with a distance."""
        return [
            (FLAGS[o.name], o.distance, o.direction) for o in self.objects if o.name in FLAGS and o.distance is not None
        ]


def read_see(msg: list) -> See:
    """A parsed ``(see T ((f c) 12.8 -39) ((b) 3.1 10 0 0) ...)``."""
    if not msg or str(msg[0]) != "see":
        raise ValueError("not a see message")
    objects = []
    for item in msg[2:]:
        name = " ".join(str(x) for x in item[0])
        values = [float(v) for v in item[1:] if isinstance(v, (int, float))]
        marks = [str(v) for v in item[1:] if not isinstance(v, (int, float))]  # e.g. k (kicking), t (tackling)
        if len(values) == 1:  # too far for a distance: only the direction
            objects.append(Seen(name, None, values[0], marks))
        else:
            objects.append(Seen(name, values[0], values[1], [*values[2:], *marks]))
    return See(int(msg[1]), objects)


# What rcssserver 19 takes from a player, one pattern per command (numbers as it reads them).
_NUM = r"-?\d+(\.\d+)?"
COMMAND_GRAMMAR = {
    "move": rf"\(move {_NUM} {_NUM}\)",
    "dash": rf"\(dash {_NUM}( {_NUM})?\)",
    "turn": rf"\(turn {_NUM}\)",
    "kick": rf"\(kick {_NUM} {_NUM}\)",
    "turn_neck": rf"\(turn_neck {_NUM}\)",
    "catch": rf"\(catch {_NUM}\)",
    "change_view": r"\(change_view (narrow|normal|wide)\)",
    "tackle": rf"\(tackle {_NUM}\)",
    "say": r'\(say "[A-Za-z0-9 ().+*/?<>_-]{1,10}"\)',
    "done": r"\(done\)",
    "bye": r"\(bye\)",
    "init": r"\(init \S+ \(version \d+\)( \(goalie\))?\)",
    "reconnect": r"\(reconnect \S+ \d+\)",
}
_RANGES = {"dash": (-100, 100), "turn": (-180, 180), "kick": (0, 100), "turn_neck": (-180, 180), "catch": (-180, 180)}
BODY_COMMANDS = frozenset({"move", "dash", "turn", "kick", "catch", "tackle"})  # one per cycle; extras ignored


def command_name(text: str) -> str:
    return text[1:].split(" ", 1)[0].rstrip(")")


def well_formed(text: str) -> bool:
    """Whether rcssserver would take this player command as it is (form and ranges)."""
    name = command_name(text)
    if name not in COMMAND_GRAMMAR or not re.fullmatch(COMMAND_GRAMMAR[name], text):
        return False
    if name in _RANGES:
        low, high = _RANGES[name]
        values = [float(v) for v in text[1:-1].split()[1:]]
        return low <= values[0] <= high and all(-180 <= v <= 180 for v in values[1:])
    return True
