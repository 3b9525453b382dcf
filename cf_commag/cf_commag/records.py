"""Component records and the ranked, taxonomy-aware directory search (ROS-free).

The ComMAg's registry and every agent's local lookup cache share this code,
so a lookup gives the same answer wherever it runs.
"""

from __future__ import annotations

import bisect
import math
import re
from dataclasses import asdict, dataclass, field
from enum import IntEnum, StrEnum
from functools import cache

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
    state_since: float = 0.0  # when it entered its current state
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


@cache
def _class_order(requested: str, direction: Direction) -> tuple[tuple[str, int], ...]:
    """Classes that match a request, in ranking order: nearest first, more specific first at a tie."""
    found = [(requested, 0)]
    if direction in (Direction.GENERAL, Direction.BOTH):
        found += [(cls, i + 1) for i, cls in enumerate(SERVICES.ancestors(requested))]
    if direction in (Direction.SPECIFIC, Direction.BOTH):
        base = SERVICES.depth(requested)
        found += [(cls, base - SERVICES.depth(cls)) for cls in SERVICES.descendants(requested)]
    return tuple(sorted(found, key=lambda item: (abs(item[1]), item[1])))


class Directory:
    """Entries indexed by service class (names kept sorted) and by team/player."""

    def __init__(self) -> None:
        self._entries: dict[str, Entry] = {}
        self._names: dict[str, list[str]] = {}  # class -> sorted names
        self._by_owner: dict[tuple[str, int], set[str]] = {}  # (team, player) -> names
        # name -> (class, owner) it is indexed under: an entry's record may be replaced before
        # it is put again, so the old keys are remembered here, not read from the entry.
        self._keys: dict[str, tuple[str, tuple[str, int]]] = {}

    def __len__(self) -> int:
        return len(self._entries)

    def __contains__(self, name: object) -> bool:
        return name in self._entries

    def get(self, name: str) -> Entry | None:
        return self._entries.get(name)

    def entries(self) -> list[Entry]:
        return list(self._entries.values())

    def put(self, entry: Entry) -> None:
        """Add an entry, or index it anew after its record changed (class, team or player)."""
        self._unindex(entry.name)
        self._entries[entry.name] = entry
        cls, owner = entry.record.service_class, (entry.record.team, entry.record.player_number)
        bisect.insort(self._names.setdefault(cls, []), entry.name)
        self._by_owner.setdefault(owner, set()).add(entry.name)
        self._keys[entry.name] = (cls, owner)

    def remove(self, name: str) -> Entry | None:
        entry = self._entries.pop(name, None)
        self._unindex(name)
        return entry

    def _unindex(self, name: str) -> None:
        keys = self._keys.pop(name, None)
        if keys is None:
            return
        cls, owner = keys
        names = self._names.get(cls, [])
        i = bisect.bisect_left(names, name)
        if i < len(names) and names[i] == name:
            del names[i]
        if not names:
            self._names.pop(cls, None)
        owned = self._by_owner.get(owner)
        if owned is not None:
            owned.discard(name)
            if not owned:  # no empty sets left behind by agents that came and went
                del self._by_owner[owner]

    def check(self) -> None:
        """Raise AssertionError unless the indexes hold exactly the entries (for tests)."""
        by_class = {n for names in self._names.values() for n in names}
        by_owner = {n for names in self._by_owner.values() for n in names}
        assert by_class == by_owner == set(self._entries) == set(self._keys), "index and entries differ"
        for name, entry in self._entries.items():
            cls, owner = self._keys[name]
            assert (cls, owner) == (entry.record.service_class, (entry.record.team, entry.record.player_number))
            assert name in self._names[cls] and name in self._by_owner[owner]
        for names in self._names.values():
            assert names == sorted(names) and names

    def search(self, query: Query) -> list[tuple[Entry, int]]:
        """Matching entries with their taxonomy distance, best first.

        Order: healthy before suspect (and relaunching); then nearest class
        (exact first, and at equal distance the more specific provider); then
        name. Withdrawn entries never match.
        """
        order = _class_order(SERVICES.check(query.service_class), Direction(query.direction))
        if query.team or query.player_number:
            return self._search_owned(query, order)
        limit = query.max_results
        healthy: list[tuple[Entry, int]] = []
        others: list[tuple[int, Entry, int]] = []
        entries = self._entries
        for cls, distance in order:
            for name in self._names.get(cls, ()):
                entry = entries[name]
                rank = _STATE_RANK.get(entry.state)
                if rank == 0:
                    healthy.append((entry, distance))
                    if limit and len(healthy) >= limit:
                        return healthy
                elif rank is not None and query.include_suspect:
                    others.append((rank, entry, distance))
        others.sort(key=lambda item: item[0])  # stable: keeps the class/name order within a state
        found = healthy + [(entry, distance) for _, entry, distance in others]
        return found[:limit] if limit else found

    def _search_owned(self, query: Query, order: tuple[tuple[str, int], ...]) -> list[tuple[Entry, int]]:
        """A team/player filter selects few entries: rank those directly."""
        if query.team and query.player_number:
            names = self._by_owner.get((query.team, query.player_number), set())
        else:
            names = {
                n
                for (team, player), owned in self._by_owner.items()
                if (not query.team or team == query.team) and (not query.player_number or player == query.player_number)
                for n in owned
            }
        distance_of = dict(order)
        ranked = []
        for name in names:
            entry = self._entries[name]
            distance = distance_of.get(entry.record.service_class)
            rank = _STATE_RANK.get(entry.state)
            if distance is None or rank is None or (rank and not query.include_suspect):
                continue
            ranked.append(((rank, abs(distance), distance, name), entry, distance))
        ranked.sort(key=lambda item: item[0])
        if query.max_results:
            ranked = ranked[: query.max_results]
        return [(entry, distance) for _, entry, distance in ranked]


_NAME_RE = re.compile(r"[A-Za-z][A-Za-z0-9_]{0,99}")


def valid_agent_name(name: str) -> bool:
    """Agent names become ROS topic names (/cf/agents/<name>/inbox)."""
    return isinstance(name, str) and _NAME_RE.fullmatch(name) is not None and "__" not in name


MAX_TEXT = 1024  # characters of a name-like string field (team, address, class, metadata)
_UINT16, _INT16, _UINT32 = (0, 2**16 - 1), (-(2**15), 2**15 - 1), (0, 2**32 - 1)


def _text_problem(field: str, value: object, limit: int = MAX_TEXT) -> str | None:
    """Why ``value`` cannot travel in a ROS ``string`` field, or None."""
    if not isinstance(value, str):
        return f"{field} must be a string, not {type(value).__name__}"
    if len(value) > limit:
        return f"{field} is longer than {limit} characters"
    if "\0" in value:
        return f"{field} must not contain NUL (a ROS string ends at it)"
    try:
        value.encode("utf-8")
    except UnicodeEncodeError:
        return f"{field} is not valid Unicode (a lone surrogate)"
    return None


def _int_problem(field: str, value: object, bounds: tuple[int, int]) -> str | None:
    if type(value) is not int:
        return f"{field} must be an integer, not {type(value).__name__}"
    if not bounds[0] <= value <= bounds[1]:
        return f"{field} must be in {bounds[0]}..{bounds[1]}"
    return None


def record_field_problem(record: Record) -> str | None:
    """Why a record's fields cannot be carried by a ComponentRecord message, or None."""
    for name in ("name", "address", "service_class", "team"):
        problem = _text_problem(name, getattr(record, name))
        if problem:
            return problem
    for name, value in (("port", record.port), ("player_number", record.player_number)):
        problem = _int_problem(name, value, _UINT16 if name == "port" else _INT16)
        if problem:
            return problem
    if type(record.lease_period) not in (int, float) or not math.isfinite(record.lease_period):
        return "lease_period must be a finite number of seconds"
    lists = {
        "launch_command": record.launch_command,
        "languages": record.languages,
        "ontologies": record.ontologies,
        "metadata": [x for kv in record.metadata for x in kv],
    }
    for name, values in lists.items():
        for value in values:
            problem = _text_problem(f"an item of {name}", value, 4096)
            if problem:
                return problem
    return None


def query_field_problem(query: Query) -> str | None:
    """Why a query's fields cannot be carried by a Lookup request, or None."""
    return (
        _text_problem("service_class", query.service_class)
        or _text_problem("team", query.team)
        or _int_problem("player_number", query.player_number, _INT16)
        or _int_problem("max_results", query.max_results, _UINT32)
        or (None if type(query.include_suspect) is bool else "include_suspect must be true or false")
    )


def check_record(record: Record, *, min_lease: float, max_lease: float) -> str | None:
    """Why a record cannot be registered, or None if it can."""
    problem = record_field_problem(record)
    if problem:
        return problem
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
    return None
