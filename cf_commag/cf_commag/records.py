"""Component records and the ranked, taxonomy-aware directory search (ROS-free).

The ComMAg's registry and every agent's local lookup cache share this code,
so a lookup gives the same answer wherever it runs.
"""

from __future__ import annotations

import heapq
import re
from dataclasses import asdict, dataclass, field
from enum import IntEnum, StrEnum

from cf_lang.taxonomy import SERVICES, Direction, TaxonomyError


class State(StrEnum):
    HEALTHY = "healthy"
    SUSPECT = "suspect"
    RELAUNCHING = "relaunching"
    WITHDRAWN = "withdrawn"


class EventKind(IntEnum):
    """Registry transitions; the numbers are RegistryEvent.msg's constants."""

    REGISTERED = 0
    RENEWED = 1
    SUSPECT = 2
    RELAUNCHING = 3
    RELAUNCHED = 4
    LAUNCH_FAILED = 5
    WITHDRAWN = 6
    DEREGISTERED = 7


class Transport(StrEnum):
    ROS = "ros"
    TCP = "tcp"


@dataclass(frozen=True)
class Record:
    """What a component tells the ComMAg about itself (paper, Fig. 2)."""

    name: str
    service_class: str
    address: str = ""
    port: int = 0
    launch_command: tuple[str, ...] = ()
    lease_period: float = 0.0
    team: str = ""
    player_number: int = 0
    transport: Transport = Transport.ROS
    languages: tuple[str, ...] = ("cf-lang",)
    ontologies: tuple[str, ...] = ("robocup-soccer",)
    metadata: tuple[tuple[str, str], ...] = ()

    def to_dict(self) -> dict:
        return asdict(self)

    @classmethod
    def from_dict(cls, data: dict) -> Record:
        return cls(
            name=str(data["name"]),
            service_class=str(data["service_class"]),
            address=str(data.get("address", "")),
            port=int(data.get("port", 0)),
            launch_command=tuple(data.get("launch_command", ())),
            lease_period=float(data.get("lease_period", 0.0)),
            team=str(data.get("team", "")),
            player_number=int(data.get("player_number", 0)),
            transport=Transport(data.get("transport", "ros")),
            languages=tuple(data.get("languages", ())),
            ontologies=tuple(data.get("ontologies", ())),
            metadata=tuple((str(k), str(v)) for k, v in data.get("metadata", ())),
        )


@dataclass
class Entry:
    """A record and what the ComMAg knows of its health."""

    record: Record
    state: State = State.HEALTHY
    lease: float = 1.0
    last_renewal: float = 0.0
    failures: int = 0
    launches: int = 0
    next_attempt_at: float = 0.0
    launch_started_at: float = 0.0
    healthy_since: float = 0.0
    history: list[tuple[float, str]] = field(default_factory=list)

    @property
    def name(self) -> str:
        return self.record.name


_STATE_RANK = {State.HEALTHY: 0, State.SUSPECT: 1, State.RELAUNCHING: 2}


@dataclass(frozen=True)
class Query:
    """A lookup: which class, which way in the taxonomy, which filters."""

    service_class: str
    direction: Direction = Direction.GENERAL
    team: str = ""
    player_number: int = 0
    include_suspect: bool = False
    max_results: int = 0


class Directory:
    """Entries indexed by service class, searched by taxonomy distance."""

    def __init__(self) -> None:
        self._entries: dict[str, Entry] = {}
        self._by_class: dict[str, dict[str, Entry]] = {}

    def __len__(self) -> int:
        return len(self._entries)

    def __contains__(self, name: object) -> bool:
        return name in self._entries

    def get(self, name: str) -> Entry | None:
        return self._entries.get(name)

    def entries(self) -> list[Entry]:
        return list(self._entries.values())

    def put(self, entry: Entry) -> None:
        old = self._entries.get(entry.name)
        if old is not None and old.record.service_class != entry.record.service_class:
            self._by_class[old.record.service_class].pop(entry.name, None)
        self._entries[entry.name] = entry
        self._by_class.setdefault(entry.record.service_class, {})[entry.name] = entry

    def remove(self, name: str) -> Entry | None:
        entry = self._entries.pop(name, None)
        if entry is not None:
            self._by_class.get(entry.record.service_class, {}).pop(name, None)
        return entry

    def search(self, query: Query) -> list[tuple[Entry, int]]:
        """Matching entries with their taxonomy distance, best first.

        Order: healthy before suspect (and relaunching); then nearest class
        (exact first, and at equal distance the more specific provider); then
        name. Withdrawn entries never match.
        """
        requested = SERVICES.check(query.service_class)
        classes: list[tuple[str, int]] = [(requested, 0)]
        if query.direction in (Direction.GENERAL, Direction.BOTH):
            classes += [(cls, i + 1) for i, cls in enumerate(SERVICES.ancestors(requested))]
        if query.direction in (Direction.SPECIFIC, Direction.BOTH):
            classes += [
                (cls, -(SERVICES.depth(cls) - SERVICES.depth(requested))) for cls in SERVICES.descendants(requested)
            ]
        ranked = []
        for cls, distance in classes:
            for entry in self._by_class.get(cls, {}).values():
                rank = _STATE_RANK.get(entry.state)
                if rank is None or (rank and not query.include_suspect):
                    continue
                rec = entry.record
                if query.team and rec.team != query.team:
                    continue
                if query.player_number and rec.player_number != query.player_number:
                    continue
                ranked.append(((rank, abs(distance), distance, rec.name), entry, distance))
        if query.max_results and query.max_results < len(ranked):
            best = heapq.nsmallest(query.max_results, ranked, key=lambda item: item[0])
        else:
            best = sorted(ranked, key=lambda item: item[0])
        return [(entry, distance) for _, entry, distance in best]


_NAME_RE = re.compile(r"[A-Za-z][A-Za-z0-9_]{0,99}")


def valid_agent_name(name: str) -> bool:
    """Agent names become ROS topic names (/cf/agents/<name>/inbox)."""
    return isinstance(name, str) and _NAME_RE.fullmatch(name) is not None and "__" not in name


def check_record(record: Record, *, min_lease: float, max_lease: float) -> str | None:
    """Why a record cannot be registered, or None if it can."""
    if not valid_agent_name(record.name):
        return f"name {record.name!r} must match [A-Za-z][A-Za-z0-9_]* (at most 100 characters): it names a ROS topic"
    try:
        SERVICES.check(record.service_class)
    except TaxonomyError as exc:
        return str(exc)
    if record.lease_period and not (min_lease <= record.lease_period <= max_lease):
        return f"lease_period {record.lease_period} s is outside [{min_lease}, {max_lease}]"
    if not 0 <= record.player_number <= 11:
        return "player_number must be 0..11"
    if any(not isinstance(a, str) or "\0" in a for a in record.launch_command):
        return "launch_command must be a list of strings without NUL"
    return None
