"""The registry's indexes stay consistent under any sequence of calls (hypothesis state machine).

Found from outside: register x1 (team a, player 1), renew it with team b, player 2, deregister,
look up team a player 1 -> KeyError, and the ComMAg process exited.
"""

from __future__ import annotations

from hypothesis import HealthCheck, settings
from hypothesis import strategies as st
from hypothesis.stateful import RuleBasedStateMachine, invariant, rule

from cf_commag.records import Query, Record, State
from cf_commag.registry import INCARNATION_KEY, Registry, RegistryConfig
from cf_lang.taxonomy import Direction

NAMES = st.sampled_from(["x1", "x2", "x3", "blue_1_kick"])
CLASSES = st.sampled_from(["Service", "Action", "Kick", "Shoot", "WorldModel", "PlayerDecision", "Nope"])
TEAMS = st.sampled_from(["", "a", "b"])
PLAYERS = st.integers(0, 3)
INCARNATIONS = st.sampled_from(["", "p1", "p2", "p3"])


class RegistryMachine(RuleBasedStateMachine):
    def __init__(self):
        super().__init__()
        self.launched: list[str] = []
        self.registry = Registry(
            RegistryConfig(default_lease=1.0, startup_grace=2.0, max_failures=2, backoff_initial=0.1),
            launch=lambda record: self.launched.append(record.name),
        )
        self.now = 0.0

    @rule(name=NAMES, cls=CLASSES, team=TEAMS, player=PLAYERS, inc=INCARNATIONS, relaunchable=st.booleans())
    def register(self, name, cls, team, player, inc, relaunchable):
        record = Record(
            name=name,
            service_class=cls,
            team=team,
            player_number=player,
            launch_command=("/bin/true",) if relaunchable else (),
            metadata=((INCARNATION_KEY, inc),) if inc else (),
        )
        result, _ = self.registry.register(record, now=self.now)
        if result.accepted:
            assert self.registry.directory.get(name).record == record
        else:
            assert result.reason

    @rule(name=NAMES)
    def deregister(self, name):
        known = name in self.registry.directory
        result, _ = self.registry.deregister(name, now=self.now)
        assert result.accepted == known and name not in self.registry.directory

    @rule(seconds=st.floats(0.0, 5.0))
    def tick(self, seconds):
        self.now += seconds
        self.registry.tick(self.now)

    @rule(name=NAMES, code=st.integers(-9, 3))
    def launch_exited(self, name, code):
        self.registry.launch_exited(name, code, now=self.now)

    @rule(
        cls=CLASSES.filter(lambda c: c != "Nope"),
        direction=st.sampled_from(list(Direction)),
        team=TEAMS,
        player=PLAYERS,
        suspect=st.booleans(),
        limit=st.integers(0, 3),
    )
    def lookup(self, cls, direction, team, player, suspect, limit):
        found = self.registry.lookup(Query(cls, direction, team, player, suspect, limit))
        for entry in found:
            assert entry.name in self.registry.directory
            assert not team or entry.record.team == team
            assert not player or entry.record.player_number == player
            assert entry.state is not State.WITHDRAWN
            assert suspect or entry.state is State.HEALTHY
        assert not limit or len(found) <= limit
        assert len({e.name for e in found}) == len(found)

    @rule()
    def restore_from_dump(self):
        dump = self.registry.dump()
        fresh = Registry(self.registry.config, launch=lambda record: self.launched.append(record.name))
        fresh.restore(dump, now=self.now)
        assert sorted(e.name for e in fresh.directory.entries()) == sorted(
            e.name for e in self.registry.directory.entries()
        )
        self.registry = fresh

    @invariant()
    def indexes_hold_exactly_the_entries(self):
        self.registry.directory.check()


RegistryMachine.TestCase.settings = settings(
    max_examples=300, stateful_step_count=40, deadline=None, suppress_health_check=[HealthCheck.too_slow]
)
TestRegistryIndexes = RegistryMachine.TestCase


def test_a_renewal_that_changes_team_and_player_then_a_deregistration_leaves_no_trace():
    """The sequence found from outside, kept as a plain example."""
    registry = Registry()
    registry.register(Record(name="x1", service_class="Kick", team="a", player_number=1), now=0.0)
    registry.register(Record(name="x1", service_class="Kick", team="b", player_number=2), now=0.1)
    registry.deregister("x1", now=0.2)
    assert registry.lookup(Query("Kick", team="a", player_number=1)) == []
    assert registry.lookup(Query("Kick", team="a")) == []
    registry.directory.check()
