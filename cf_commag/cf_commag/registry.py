"""The ComMAg's registry: leases, relaunch, back-off and withdrawal (paper, 3.1). ROS-free.

States of a component::

    healthy --lease missed--> suspect --launch started--> relaunching --re-registered--> healthy
                                 ^                            |
                                 +----launch failed (back-off)+--N failures--> withdrawn

A launch fails if the launcher refuses or cannot start it, if the process
exits, or if it does not re-register within the start-up grace (or, while the
process it started still runs, within the start-up grace plus ``alive_grace``).

A component whose process still runs (``alive(record)`` says so: same machine, see
process.py) is starved or hung rather than dead: it stays suspect (lookups pass it over,
so its twins take over) and is relaunched only once it has been silent ``alive_grace``
seconds beyond its lease. Agents hosted in one process (``host`` metadata) are relaunched
together: the first one found silent starts the host's launch command, the others join that
launch instead of starting one each. Attempts back
off exponentially (capped); the failure count resets once a component has
stayed healthy for the stable period. A component without a launch command is
withdrawn once it has been silent for ``max_failures`` more leases. Withdrawn
components stay visible in the registry (and can come back by registering) but
are never returned by lookups.

Time is passed in as ``now`` (seconds, monotonic); side effects go through
the injected ``launch`` callable.
"""

from __future__ import annotations

from collections import OrderedDict
from collections.abc import Callable
from dataclasses import dataclass

from .process import HOST_KEY
from .records import Directory, Entry, EventKind, Query, Record, State, check_record

HISTORY_LIMIT = 50
CLOSED_INCARNATIONS = 10_000
INCARNATION_KEY = "incarnation"


SUPERSEDED = "superseded: a newer process of this component has registered"


def _remember(bounded: OrderedDict, key: str) -> None:
    bounded[key] = None
    while len(bounded) > CLOSED_INCARNATIONS:
        bounded.popitem(last=False)


def incarnation(record: Record) -> str:
    """The process incarnation a record's metadata names ("" if none)."""
    return next((v for k, v in record.metadata if k == INCARNATION_KEY), "")


def host_of(record: Record) -> str:
    """The host process a record's metadata names ("" for a component alone in its process)."""
    return next((v for k, v in record.metadata if k == HOST_KEY), "")


def launch_key(record: Record) -> str:
    """What a launch starts: ``host-<name>`` for a hosted agent (one process for all), else the component's name."""
    host = host_of(record)
    return f"host-{host}" if host else record.name


class LaunchError(Exception):
    """The launcher could not (or would not) start a component."""


@dataclass(frozen=True)
class RegistryConfig:
    default_lease: float = 1.0
    min_lease: float = 0.05
    max_lease: float = 300.0
    startup_grace: float = 5.0
    max_failures: int = 3
    backoff_initial: float = 0.5
    backoff_max: float = 8.0
    # A withdrawn component without a launch command cannot come back but by registering again:
    # forget it after this many seconds (0: never), so that agents that vanish (TCP clients,
    # above all) do not make every tick, save and registry snapshot bigger for ever.
    forget_after: float = 60.0
    # A silent component whose process still runs (starved or hung) is relaunched only after
    # this many seconds beyond its lease: on a loaded machine, relaunching a starved process
    # adds a process start (a second of CPU) to the load that starved it.
    alive_grace: float = 10.0
    stable_period: float = 30.0
    max_components: int = 100_000


@dataclass(frozen=True)
class Event:
    kind: EventKind
    record: Record
    state: State
    failures: int
    reason: str
    at: float


@dataclass(frozen=True)
class Result:
    accepted: bool
    reason: str
    lease: float = 0.0


class Registry:
    """Registration, renewal, lookup and fault management of components."""

    def __init__(
        self,
        config: RegistryConfig | None = None,
        *,
        launch: Callable[[Record], None] | None = None,
        check_launch: Callable[[Record], str | None] | None = None,
        cancel_launch: Callable[[str], None] | None = None,
        alive: Callable[[Record], bool | None] | None = None,
        launch_running: Callable[[str], bool] | None = None,
    ):
        """``alive(record)``: the registered process still runs (None: cannot tell);
        ``launch_running(key)``: the process started for that launch key still runs."""
        self.config = config or RegistryConfig()
        self._alive = alive
        self._launch_running = launch_running
        self._launch = launch
        self._check_launch = check_launch
        self._cancel_launch = cancel_launch
        # Incarnations replaced by a newer process of the same component: fenced off, so
        # that two processes never serve under one name (their clients shut down when refused).
        self._superseded: OrderedDict[str, None] = OrderedDict()
        self.directory = Directory()
        # Incarnations that deregistered: a renewal of theirs still in flight must
        # not bring them back. A restarted process has a new incarnation.
        self._closed: OrderedDict[str, None] = OrderedDict()
        self.changed = False
        """True after a change worth persisting; the owner clears it after saving."""

    # ---- registration -------------------------------------------------------

    def register(self, record: Record, *, now: float) -> tuple[Result, list[Event]]:
        """Register or renew; a repeat with the same name is a renewal."""
        cfg = self.config
        reason = check_record(record, min_lease=cfg.min_lease, max_lease=cfg.max_lease)
        if reason is None and record.launch_command and self._check_launch is not None:
            refused = self._check_launch(record)
            if refused:
                reason = f"launch command refused: {refused}"
        if reason is None and incarnation(record) in self._closed:
            reason = "this incarnation has deregistered; a new process registers under a new incarnation"
        if reason is None and incarnation(record) in self._superseded:
            reason = SUPERSEDED
        if reason is not None:
            return Result(False, reason), []
        lease = record.lease_period or cfg.default_lease
        entry = self.directory.get(record.name)
        if entry is None:
            if len(self.directory) >= cfg.max_components:
                return Result(False, f"registry full ({cfg.max_components} components)"), []
            entry = Entry(record=record, lease=lease, last_renewal=now, healthy_since=now, state_since=now)
            self.directory.put(entry)
            self.changed = True
            return Result(True, "registered", lease), [self._event(entry, EventKind.REGISTERED, "registered", now)]

        old, new = incarnation(entry.record), incarnation(record)
        if entry.record != record:  # a renewal may change any field: index it anew
            entry.record = record
            self.directory.put(entry)
            self.changed = True
        if entry.state is State.RELAUNCHING and old and new == old:
            # Only late, not dead: keep it, and stop the process we launched in its place.
            if self._cancel_launch is not None:
                self._cancel_launch(launch_key(record))
            entry.last_renewal = now
            self._set(entry, State.HEALTHY, now)
            entry.healthy_since = now
            reason = "was only late: the process launched in its place is stopped"
            return Result(True, "renewed", lease), [self._event(entry, EventKind.RENEWED, reason, now)]
        if old and new and old != new:
            _remember(self._superseded, old)
        entry.lease = lease
        entry.last_renewal = now
        previous = entry.state
        if previous is State.HEALTHY:
            if entry.failures and now - entry.healthy_since >= cfg.stable_period:
                entry.failures = 0
                self.changed = True
            return Result(True, "renewed", lease), [self._event(entry, EventKind.RENEWED, "renewed", now, log=False)]
        self._set(entry, State.HEALTHY, now)
        entry.healthy_since = now
        if previous is State.RELAUNCHING:
            took = now - entry.launch_started_at
            return Result(True, "renewed", lease), [
                self._event(entry, EventKind.RELAUNCHED, f"relaunched and re-registered after {took:.2f} s", now)
            ]
        if previous is State.WITHDRAWN:
            entry.failures = 0
            return Result(True, "registered", lease), [
                self._event(entry, EventKind.REGISTERED, "came back after withdrawal", now)
            ]
        return Result(True, "renewed", lease), [self._event(entry, EventKind.RENEWED, "renewed while suspect", now)]

    def deregister(self, name: str, *, now: float) -> tuple[Result, list[Event]]:
        entry = self.directory.remove(name)
        if entry is None:
            return Result(False, f"no component named {name!r}"), []
        self.changed = True
        closed = incarnation(entry.record)
        if closed:
            _remember(self._closed, closed)
        return Result(True, "deregistered"), [self._event(entry, EventKind.DEREGISTERED, "deregistered", now)]

    def lookup(self, query: Query) -> list[Entry]:
        """Providers for a query, best first (see Directory.search)."""
        return [entry for entry, _ in self.directory.search(query)]

    # ---- fault management ---------------------------------------------------

    def pause(self, seconds: float) -> None:
        """The ComMAg itself could not run for ``seconds``: renewals that came meanwhile are still queued.

        Every lease and start-up grace is extended by that time, so that components are not blamed
        (and relaunched) for the ComMAg's own stall.
        """
        for entry in self.directory.entries():
            entry.last_renewal += seconds
            entry.launch_started_at += seconds

    def tick(self, now: float) -> list[Event]:
        """Advance every component's state to time ``now``."""
        events: list[Event] = []
        forget = self.config.forget_after
        for entry in self.directory.entries():
            state = entry.state
            if state is State.WITHDRAWN:
                if forget and not entry.record.launch_command and now - entry.state_since > forget:
                    self.directory.remove(entry.name)
                    self.changed = True
                    reason = f"forgotten: withdrawn {now - entry.state_since:.0f} s ago, no launch command"
                    events.append(self._event(entry, EventKind.DEREGISTERED, reason, now))
                continue
            if state is State.HEALTHY:
                silent = now - entry.last_renewal
                if silent > entry.lease:
                    self._set(entry, State.SUSPECT, now)
                    entry.next_attempt_at = now
                    reason = f"missed its lease ({silent:.2f} s silent)"
                    if self._still_running(entry):
                        reason += f"; its process still runs (starved or hung): {self.config.alive_grace:.0f} s more"
                    events.append(self._event(entry, EventKind.SUSPECT, reason, now))
                    state = State.SUSPECT
            if state is State.SUSPECT:
                silent = now - entry.last_renewal
                grace = self.config.alive_grace if self._still_running(entry) else 0.0
                if entry.record.launch_command:
                    if now >= entry.next_attempt_at and (entry.failures or silent > entry.lease + grace):
                        events += self._relaunch(entry, now)
                elif silent > entry.lease * (1 + self.config.max_failures) + grace:
                    events.append(self._withdraw(entry, "silent and has no launch command", now))
            elif state is State.RELAUNCHING and now - entry.launch_started_at > self.config.startup_grace:
                starting = now - entry.launch_started_at <= self.config.startup_grace + self.config.alive_grace
                if not (starting and self._launched_still_runs(entry)):
                    grace = self.config.startup_grace
                    events += self._failed(entry, f"did not re-register within {grace:.1f} s", now)
        return events

    def _still_running(self, entry: Entry) -> bool:
        return self._alive is not None and self._alive(entry.record) is True

    def _launched_still_runs(self, entry: Entry) -> bool:
        """The process launched for ``entry`` runs yet: slow to start (a loaded machine), not failed.

        Killing it at the start-up grace and starting another would add a second start to the load
        that made the first one slow.
        """
        return self._launch_running is not None and self._launch_running(launch_key(entry.record))

    def launch_exited(self, key: str, returncode: int, *, now: float, reason: str = "") -> list[Event]:
        """A process we started (for ``launch_key`` ``key``) exited, or (``reason``) was never started."""
        why = reason or f"relaunched process exited with code {returncode}"
        events = []
        for entry in self.directory.entries():
            if entry.state is State.RELAUNCHING and launch_key(entry.record) == key:
                events += self._failed(entry, why, now)
        return events

    def _relaunch(self, entry: Entry, now: float) -> list[Event]:
        if self._launch is None:
            return self._failed(entry, "this ComMAg has no launcher", now)
        host = host_of(entry.record)
        if host:
            started = self._host_launch(entry, host, now)
            if started is not None:  # one process for all the host's agents: join the launch under way
                self._set(entry, State.RELAUNCHING, now)
                entry.launch_started_at = started.launch_started_at
                reason = f"launch attempt {entry.failures + 1}: with its host {host} (started for {started.name})"
                return [self._event(entry, EventKind.RELAUNCHING, reason, now)]
        entry.launches += 1
        try:
            self._launch(entry.record)
        except LaunchError as exc:
            return self._failed(entry, str(exc), now)
        self._set(entry, State.RELAUNCHING, now)
        entry.launch_started_at = now
        attempt = entry.failures + 1
        return [self._event(entry, EventKind.RELAUNCHING, f"launch attempt {attempt}", now)]

    def _host_launch(self, entry: Entry, host: str, now: float) -> Entry | None:
        """Another agent of ``host`` whose launch (of the same command) is under way, if any."""
        for other in self.directory.entries():
            if (
                other is not entry
                and other.state is State.RELAUNCHING
                and host_of(other.record) == host
                and other.record.launch_command == entry.record.launch_command
                and now - other.launch_started_at <= self.config.startup_grace
            ):
                return other
        return None

    def _failed(self, entry: Entry, reason: str, now: float) -> list[Event]:
        entry.failures += 1
        self.changed = True
        cfg = self.config
        if entry.failures >= cfg.max_failures:
            self._set(entry, State.SUSPECT, now)
            failed = self._event(entry, EventKind.LAUNCH_FAILED, reason, now)
            return [failed, self._withdraw(entry, f"{entry.failures} consecutive failed launches", now)]
        delay = min(cfg.backoff_max, cfg.backoff_initial * 2 ** (entry.failures - 1))
        entry.next_attempt_at = now + delay
        self._set(entry, State.SUSPECT, now)
        return [self._event(entry, EventKind.LAUNCH_FAILED, f"{reason}; next attempt in {delay:.2f} s", now)]

    def _withdraw(self, entry: Entry, reason: str, now: float) -> Event:
        self._set(entry, State.WITHDRAWN, now)
        return self._event(entry, EventKind.WITHDRAWN, reason, now)

    def _set(self, entry: Entry, state: State, now: float) -> None:
        if entry.state is not state:
            entry.state = state
            entry.state_since = now
            self.changed = True

    def _event(self, entry: Entry, kind: EventKind, reason: str, now: float, *, log: bool = True) -> Event:
        if log:
            entry.history.append((now, kind.name.lower()))
            del entry.history[:-HISTORY_LIMIT]
        return Event(kind, entry.record, entry.state, entry.failures, reason, now)

    # ---- persistence --------------------------------------------------------

    def dump(self) -> list[dict]:
        """The state worth keeping across a restart (times are not: they restart)."""
        return [
            {"record": e.record.to_dict(), "state": e.state.value, "failures": e.failures, "lease": e.lease}
            for e in self.directory.entries()
        ]

    def restore(self, data: list[dict], *, now: float) -> int:
        """Load dumped state. Every restored component gets a fresh lease from ``now``
        plus the start-up grace: its client needs a moment to find the new ComMAg.

        A component that was relaunching is suspect again (its launch was lost
        with the old process); healthy ones keep renewing and stay healthy.
        """
        count = 0
        for item in data:
            record = Record.from_dict(item["record"])
            state = State(item.get("state", "healthy"))
            if state is State.RELAUNCHING:
                state = State.SUSPECT
            entry = Entry(
                record=record,
                state=state,
                lease=float(item.get("lease", self.config.default_lease)),
                last_renewal=now + self.config.startup_grace,
                failures=int(item.get("failures", 0)),
                next_attempt_at=now + self.config.startup_grace,
                healthy_since=now,
                state_since=now,
            )
            self.directory.put(entry)
            count += 1
        return count
