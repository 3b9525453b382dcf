"""The registry core with a fake clock and a fake launcher: no ROS, no processes."""

from __future__ import annotations

import pytest

from cf_commag.records import EventKind, Query, Record, State
from cf_commag.registry import LaunchError, Registry, RegistryConfig
from cf_lang.taxonomy import Direction

CFG = RegistryConfig(
    default_lease=1.0, startup_grace=2.0, max_failures=3, backoff_initial=0.5, backoff_max=1.5, stable_period=10.0
)


class FakeLauncher:
    """Records launches; fails them when told to."""

    def __init__(self):
        self.launched: list[str] = []
        self.fail = False

    def __call__(self, record: Record) -> None:
        self.launched.append(record.name)
        if self.fail:
            raise LaunchError("exec failed (fake)")


def rec(name="blue_1_kick", cls="Kick", **kw) -> Record:
    kw.setdefault("launch_command", ("/ws/install/cf_commag/lib/cf_commag/demo_component",))
    return Record(name=name, service_class=cls, **kw)


@pytest.fixture
def launcher():
    return FakeLauncher()


@pytest.fixture
def reg(launcher):
    return Registry(CFG, launch=launcher)


def kinds(events):
    return [e.kind for e in events]


def test_register_then_repeat_is_renewal(reg):
    result, events = reg.register(rec(), now=0.0)
    assert result.accepted and result.reason == "registered" and result.lease == 1.0
    assert kinds(events) == [EventKind.REGISTERED]
    result, events = reg.register(rec(), now=0.5)
    assert result.reason == "renewed" and kinds(events) == [EventKind.RENEWED]
    assert len(reg.directory) == 1


@pytest.mark.parametrize(
    ("record", "words"),
    [
        (rec(name="bad name"), "must match"),
        (rec(name="9lives"), "must match"),
        (rec(cls="Juggle"), "unknown service class"),
        (rec(lease_period=1000.0), "outside"),
        (rec(player_number=12), "0..11"),
    ],
)
def test_bad_records_are_refused_with_a_reason(reg, record, words):
    result, events = reg.register(record, now=0.0)
    assert not result.accepted and words in result.reason and events == []


def test_launch_command_outside_allowlist_is_refused():
    reg = Registry(
        CFG,
        check_launch=lambda r: None if r.launch_command[0].startswith("/ws/") else f"{r.launch_command[0]} not allowed",
    )
    assert reg.register(rec(), now=0)[0].accepted
    result, _ = reg.register(rec(name="evil", launch_command=("/bin/sh", "-c", "rm -rf /")), now=0)
    assert not result.accepted and result.reason == "launch command refused: /bin/sh not allowed"


def test_missed_lease_suspect_relaunch_healthy(reg, launcher):
    reg.register(rec(), now=0.0)
    assert reg.tick(0.9) == []
    events = reg.tick(1.1)
    assert kinds(events) == [EventKind.SUSPECT, EventKind.RELAUNCHING]
    assert launcher.launched == ["blue_1_kick"]
    assert reg.directory.get("blue_1_kick").state is State.RELAUNCHING
    _result, events = reg.register(rec(), now=1.6)
    assert kinds(events) == [EventKind.RELAUNCHED] and "0.50 s" in events[0].reason
    assert reg.directory.get("blue_1_kick").state is State.HEALTHY


def test_failed_launches_back_off_then_withdraw_and_lookup_reroutes(reg, launcher):
    reg.register(rec("blue_1_kick"), now=0.0)
    reg.register(rec("blue_1_kick_twin"), now=0.0)
    launcher.fail = True
    seen = []
    t = 0.0
    while t < 20.0:
        reg.register(rec("blue_1_kick_twin"), now=t)  # the twin keeps renewing
        seen += [(round(t, 2), e.kind) for e in reg.tick(t) if e.record.name == "blue_1_kick"]
        t = round(t + 0.05, 2)
    attempts = [t for t, k in seen if k is EventKind.LAUNCH_FAILED]
    assert len(attempts) == 3
    # Back-off doubles: 0.5 s after the first failure, 1.0 s after the second.
    assert attempts[1] - attempts[0] == pytest.approx(0.5, abs=0.06)
    assert attempts[2] - attempts[1] == pytest.approx(1.0, abs=0.06)
    assert seen[-1][1] is EventKind.WITHDRAWN
    entry = reg.directory.get("blue_1_kick")
    assert entry.state is State.WITHDRAWN and entry.failures == 3
    assert [e.name for e in reg.lookup(Query("Kick"))] == ["blue_1_kick_twin"]
    assert [e.name for e in reg.lookup(Query("Kick", include_suspect=True))] == ["blue_1_kick_twin"]


def test_launch_that_never_registers_fails_after_grace(reg, launcher):
    reg.register(rec(), now=0.0)
    reg.tick(1.1)
    assert reg.tick(3.0) == []
    events = reg.tick(3.2)
    assert kinds(events) == [EventKind.LAUNCH_FAILED] and "within 2.0 s" in events[0].reason


def test_a_launched_process_still_starting_gets_alive_grace_more_to_register(launcher):
    running = {"blue_1_kick": True}
    cfg = RegistryConfig(default_lease=1.0, startup_grace=2.0, alive_grace=3.0, max_failures=3)
    reg = Registry(cfg, launch=launcher, launch_running=lambda key: running.get(key, False))
    reg.register(rec(), now=0.0)
    reg.tick(1.5)
    assert reg.directory.get("blue_1_kick").state is State.RELAUNCHING and launcher.launched == ["blue_1_kick"]
    assert reg.tick(4.0) == [] and reg.tick(6.0) == []  # past the start-up grace, but its process runs
    assert reg.directory.get("blue_1_kick").state is State.RELAUNCHING
    result, _ = reg.register(rec(), now=6.2)  # a slow start, not a failed one
    assert result.accepted and reg.directory.get("blue_1_kick").state is State.HEALTHY
    assert reg.directory.get("blue_1_kick").failures == 0 and launcher.launched == ["blue_1_kick"]
    # A launch whose process runs but never registers fails after both graces.
    reg.tick(7.5)
    assert launcher.launched == ["blue_1_kick", "blue_1_kick"]
    assert reg.tick(12.0) == []
    assert kinds(reg.tick(12.6)) == [EventKind.LAUNCH_FAILED]
    # Without a process of its own running (it exited, or another machine started it): the
    # start-up grace alone.
    running["blue_1_kick"] = False
    reg.tick(13.2)
    assert launcher.launched == ["blue_1_kick"] * 3
    assert kinds(reg.tick(15.3)) == [EventKind.LAUNCH_FAILED]


def test_process_exit_fails_the_launch(reg):
    reg.register(rec(), now=0.0)
    reg.tick(1.1)
    events = reg.launch_exited("blue_1_kick", 3, now=1.3)
    assert kinds(events) == [EventKind.LAUNCH_FAILED] and "code 3" in events[0].reason
    assert reg.launch_exited("nobody", 1, now=1.3) == []


def test_failure_count_resets_after_stable_period(reg, launcher):
    reg.register(rec(), now=0.0)
    reg.tick(1.1)
    reg.launch_exited("blue_1_kick", 1, now=1.2)
    reg.tick(1.8)  # second attempt after 0.5 s back-off
    reg.register(rec(), now=2.0)
    entry = reg.directory.get("blue_1_kick")
    assert entry.state is State.HEALTHY and entry.failures == 1
    for t in range(3, 13):
        reg.register(rec(), now=float(t))
    assert entry.failures == 0


def test_component_without_launch_command_is_withdrawn_when_silent(reg):
    reg.register(rec(launch_command=()), now=0.0)
    assert kinds(reg.tick(1.1)) == [EventKind.SUSPECT]
    assert reg.tick(3.9) == []
    assert kinds(reg.tick(4.1)) == [EventKind.WITHDRAWN]


def test_withdrawn_component_can_come_back(reg, launcher):
    launcher.fail = True
    reg.register(rec(), now=0.0)
    t = 0.0
    while reg.directory.get("blue_1_kick").state is not State.WITHDRAWN:
        t += 0.1
        reg.tick(t)
    _result, events = reg.register(rec(), now=t + 1)
    assert kinds(events) == [EventKind.REGISTERED] and reg.directory.get("blue_1_kick").failures == 0


def test_deregistered_incarnation_cannot_renew_but_a_new_one_can(reg):
    old = rec(metadata=(("incarnation", "pid1-a"),))
    reg.register(old, now=0.0)
    assert kinds(reg.deregister("blue_1_kick", now=0.1)[1]) == [EventKind.DEREGISTERED]
    result, _ = reg.register(old, now=0.2)
    assert not result.accepted and "deregistered" in result.reason
    assert reg.register(rec(metadata=(("incarnation", "pid2-b"),)), now=0.3)[0].accepted
    assert not reg.deregister("nobody", now=0.4)[0].accepted


def test_lookup_ranking_and_directions(reg):
    reg.register(rec("a_action", "Action"), now=0)
    reg.register(rec("b_ball", "BallAction"), now=0)
    reg.register(rec("c_kick", "Kick"), now=0)
    reg.register(rec("d_shoot", "Shoot"), now=0)
    reg.register(rec("e_pass", "Pass"), now=0)
    reg.register(rec("f_percept", "Perception"), now=0)
    names = lambda q: [e.name for e in reg.lookup(q)]  # noqa: E731
    assert names(Query("Kick")) == ["c_kick", "b_ball", "a_action"]
    assert names(Query("Kick", Direction.SPECIFIC)) == ["c_kick", "d_shoot", "e_pass"]
    assert names(Query("Kick", Direction.BOTH)) == ["c_kick", "d_shoot", "e_pass", "b_ball", "a_action"]
    assert names(Query("Kick", Direction.EXACT)) == ["c_kick"]
    assert names(Query("Kick", Direction.BOTH, max_results=2)) == ["c_kick", "d_shoot"]
    assert names(Query("Perception", Direction.SPECIFIC)) == ["f_percept"]


def test_lookup_filters_and_health_order(reg):
    reg.register(rec("blue_7_action", "Action", team="blue", player_number=7), now=0)
    reg.register(rec("blue_7_action_b", "Action", team="blue", player_number=7), now=0.5)
    reg.register(rec("blue_8_action", "Action", team="blue", player_number=8), now=0.5)
    reg.register(rec("red_7_action", "Action", team="red", player_number=7), now=0.5)
    reg.tick(1.2)  # blue_7_action missed its lease: suspect, relaunching
    q = Query("Action", team="blue", player_number=7)
    assert [e.name for e in reg.lookup(q)] == ["blue_7_action_b"]
    q = Query("Action", team="blue", player_number=7, include_suspect=True)
    assert [e.name for e in reg.lookup(q)] == ["blue_7_action_b", "blue_7_action"]


def test_dump_and_restore_keep_every_registration(reg, launcher):
    reg.register(rec("a_action", "Action", team="blue"), now=0)
    reg.register(rec("b_kick"), now=0)
    launcher.fail = True
    reg.tick(1.1)  # both suspect, launches failing
    data = reg.dump()
    fresh = Registry(CFG, launch=launcher)
    assert fresh.restore(data, now=100.0) == 2
    a = fresh.directory.get("a_action")
    assert a.record == reg.directory.get("a_action").record and a.failures == 1
    # Restored components get a full lease from the restore time: no relaunch storm.
    launcher.launched.clear()
    fresh.register(rec("a_action", "Action", team="blue"), now=100.5)
    fresh.register(rec("b_kick"), now=100.5)
    assert fresh.tick(101.0) == [] and launcher.launched == []


def test_a_late_component_is_kept_and_the_launch_in_its_place_stopped():
    cancelled = []
    launcher = FakeLauncher()
    reg = Registry(CFG, launch=launcher, cancel_launch=cancelled.append)
    old = rec(metadata=(("incarnation", "pid1-a"),))
    reg.register(old, now=0.0)
    reg.tick(1.2)  # missed its lease: relaunching
    assert launcher.launched == ["blue_1_kick"]
    _, events = reg.register(old, now=1.3)  # the old process was only slow
    assert kinds(events) == [EventKind.RENEWED] and "only late" in events[0].reason
    assert cancelled == ["blue_1_kick"] and reg.directory.get("blue_1_kick").state is State.HEALTHY


def test_a_newer_process_fences_off_the_older_one():
    reg = Registry(CFG)
    reg.register(rec(metadata=(("incarnation", "pid1-a"),)), now=0.0)
    assert reg.register(rec(metadata=(("incarnation", "pid2-b"),)), now=0.5)[0].accepted
    result, _ = reg.register(rec(metadata=(("incarnation", "pid1-a"),)), now=0.6)
    assert not result.accepted and result.reason.startswith("superseded")


def test_a_stall_of_the_commag_itself_costs_nobody_its_lease(reg):
    reg.register(rec("blue_7_kick", lease_period=1.0), now=0.0)
    assert reg.tick(0.9) == []
    # The ComMAg was not scheduled from 0.9 to 2.5 s: a renewal sent at 1.2 s is still queued.
    reg.pause(1.6)
    assert reg.tick(2.5) == []
    result, _ = reg.register(rec("blue_7_kick", lease_period=1.0), now=2.51)  # the queued renewal, read now
    assert result.reason == "renewed"
    assert kinds(reg.tick(3.6)) == [EventKind.SUSPECT, EventKind.RELAUNCHING]  # really silent now


def test_a_withdrawn_component_without_launch_command_is_forgotten_after_a_while():
    """Agents that vanish (TCP clients) must not make every tick, save and snapshot bigger for ever."""
    registry = Registry(RegistryConfig(default_lease=1.0, max_failures=1, forget_after=10.0))
    registry.register(Record(name="gone", service_class="Kick"), now=0.0)
    registry.register(Record(name="kept", service_class="Kick", launch_command=("/bin/false",)), now=0.0)
    events = [e for t in range(0, 40) for e in registry.tick(float(t))]
    withdrawn = next(e for e in events if e.record.name == "gone" and e.kind is EventKind.WITHDRAWN)
    forgotten = [e for e in events if e.record.name == "gone" and e.kind is EventKind.DEREGISTERED]
    assert len(forgotten) == 1 and forgotten[0].at - withdrawn.at > 10.0 and "forgotten" in forgotten[0].reason
    assert "gone" not in registry.directory and registry.directory.get("kept") is not None
    registry.directory.check()
    # It may come back by registering again.
    assert registry.register(Record(name="gone", service_class="Kick"), now=41.0)[0].accepted


def hosted(name: str, host: str = "blue_players", pid: str = "4242") -> Record:
    return rec(name=name, metadata=(("host", host), ("pid", pid), ("incarnation", f"{pid}-x")))


def test_the_agents_of_a_dead_host_get_one_launch_between_them(reg, launcher):
    names = [f"blue_{n}_kick" for n in range(1, 6)]
    for i, name in enumerate(names):
        reg.register(hosted(name), now=i * 0.1)  # leases run out one after the other, as they do
    events = []
    for step in range(15):  # within the start-up grace
        events += reg.tick(1.0 + step * 0.1)
    assert launcher.launched == [names[0]]  # the first one found silent starts the host ...
    relaunching = [e for e in events if e.kind is EventKind.RELAUNCHING]
    assert [e.record.name for e in relaunching] == names  # ... the others join that launch
    assert all("with its host blue_players" in e.reason for e in relaunching[1:])
    for name in names:  # the new process registers every agent again
        reg.register(hosted(name, pid="5151"), now=4.0)
    assert all(reg.directory.get(n).state is State.HEALTHY for n in names)


def test_a_host_that_exits_at_once_fails_every_agent_it_was_launched_for():
    seen = []
    reg = Registry(CFG, launch=lambda record: seen.append(record.name))
    for name in ("blue_1_kick", "blue_2_kick"):
        reg.register(hosted(name), now=0.0)
    reg.tick(1.5)
    assert len(seen) == 1
    events = reg.launch_exited("host-blue_players", 3, now=1.6)
    assert sorted(e.record.name for e in events) == ["blue_1_kick", "blue_2_kick"]
    assert all(e.kind is EventKind.LAUNCH_FAILED for e in events)


def test_hosts_of_another_name_launch_separately(reg, launcher):
    reg.register(hosted("blue_1_kick", host="blue_players"), now=0.0)
    reg.register(hosted("red_1_kick", host="red_players"), now=0.0)
    reg.tick(1.5)
    assert sorted(launcher.launched) == ["blue_1_kick", "red_1_kick"]


def test_a_silent_component_whose_process_still_runs_is_given_time_then_relaunched(launcher):
    alive = {"blue_1_kick": True}
    reg = Registry(CFG, launch=launcher, alive=lambda record: alive.get(record.name))
    reg.register(rec(), now=0.0)
    events = reg.tick(1.5)
    assert kinds(events) == [EventKind.SUSPECT] and "still runs (starved or hung)" in events[0].reason
    assert reg.lookup(Query("Kick", Direction.GENERAL)) == []  # passed over meanwhile: its twins serve
    for step in range(80):  # starved: it renews again within the grace, and was never relaunched
        reg.tick(1.5 + step * 0.1)
    assert launcher.launched == []
    reg.register(rec(), now=9.6)
    assert reg.directory.get("blue_1_kick").state is State.HEALTHY
    reg.tick(11.0)
    events = [e for t in range(120) for e in reg.tick(11.0 + t * 0.1)]  # hung: silent beyond the grace
    assert launcher.launched == ["blue_1_kick"]
    assert EventKind.RELAUNCHING in kinds(events)


def test_a_silent_component_whose_process_is_gone_is_relaunched_at_once(launcher):
    reg = Registry(CFG, launch=launcher, alive=lambda record: False)
    reg.register(rec(), now=0.0)
    reg.tick(1.5)
    assert launcher.launched == ["blue_1_kick"]
