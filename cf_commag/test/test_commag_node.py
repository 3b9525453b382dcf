"""The ComMAg lifecycle node in-process: lifecycle gating, services, events, snapshot, diagnostics."""

from __future__ import annotations

import json
import time

from diagnostic_msgs.msg import DiagnosticArray, DiagnosticStatus
from rclpy.lifecycle import TransitionCallbackReturn
from rclpy.parameter import Parameter

from cf_commag.commag_node import CommagNode
from cf_commag.transport.qos import EVENTS_QOS, SNAPSHOT_QOS
from cf_interfaces.msg import ComponentRecord, Registry, RegistryEvent
from cf_interfaces.srv import Deregister, Lookup, Register


def make_commag(ros, unique, tmp_path, **params):
    overrides = {"autostart": False, "persistence_path": str(tmp_path / "registry.json"), "diagnostics_period": 0.2}
    overrides.update(params)
    node = CommagNode(
        node_name=f"commag_{unique}",
        context=ros.context,
        parameter_overrides=[Parameter(k, value=v) for k, v in overrides.items()],
    )
    return ros.add(node)


def record(name, cls="Kick", **kw):
    return ComponentRecord(name=name, service_class=cls, lease_period=5.0, **kw)


def test_lifecycle_gates_the_services(ros, unique, tmp_path):
    commag = make_commag(ros, unique, tmp_path)
    probe = ros.node(f"probe_{unique}")
    register = probe.create_client(Register, f"/commag_{unique}/register")
    assert commag.trigger_configure() == TransitionCallbackReturn.SUCCESS
    res = ros.call(register, Register.Request(component=record("blue_1_kick")))
    assert not res.accepted and res.reason == "ComMAg is not active"
    assert commag.trigger_activate() == TransitionCallbackReturn.SUCCESS
    res = ros.call(register, Register.Request(component=record("blue_1_kick")))
    assert res.accepted and res.reason == "registered" and res.lease_period == 5.0
    assert commag.trigger_deactivate() == TransitionCallbackReturn.SUCCESS
    res = ros.call(register, Register.Request(component=record("blue_1_kick")))
    assert not res.accepted
    assert commag.trigger_cleanup() == TransitionCallbackReturn.SUCCESS
    # It was saved on the way down.
    saved = json.loads((tmp_path / "registry.json").read_text())
    assert [c["record"]["name"] for c in saved["components"]] == ["blue_1_kick"]


def test_invalid_parameters_fail_configure(ros, unique, tmp_path):
    commag = make_commag(ros, unique, tmp_path, max_failures=0)
    assert commag.trigger_configure() == TransitionCallbackReturn.FAILURE


def test_register_lookup_deregister_events_snapshot_diagnostics(ros, unique, tmp_path):
    commag = make_commag(ros, unique, tmp_path)
    commag.trigger_configure()
    commag.trigger_activate()
    probe = ros.node(f"probe_{unique}")
    events: list[RegistryEvent] = []
    probe.create_subscription(RegistryEvent, f"/commag_{unique}/events", events.append, EVENTS_QOS)
    diags: list[DiagnosticArray] = []
    probe.create_subscription(DiagnosticArray, "/diagnostics", diags.append, 10)
    register = probe.create_client(Register, f"/commag_{unique}/register")
    lookup = probe.create_client(Lookup, f"/commag_{unique}/lookup")
    ros.spin_until(lambda: probe.count_publishers(f"/commag_{unique}/events") > 0, what="events publisher")
    ros.spin_for(0.3)  # let the events subscription match before the first event

    for name, cls, team in [
        ("blue_1_action", "Action", "blue"),
        ("blue_1_kick", "Kick", "blue"),
        ("blue_1_shoot", "Shoot", "blue"),
        ("red_1_kick", "Kick", "red"),
    ]:
        assert ros.call(register, Register.Request(component=record(name, cls, team=team, player_number=1))).accepted
    bad = ros.call(register, Register.Request(component=record("x", "Juggle")))
    assert not bad.accepted and "unknown service class" in bad.reason

    res = ros.call(lookup, Lookup.Request(service_class="Kick", team="blue"))
    assert res.ok and [p.name for p in res.providers] == ["blue_1_kick", "blue_1_action"]
    assert all(p.state == "healthy" for p in res.providers)
    res = ros.call(lookup, Lookup.Request(service_class="Kick", direction=Lookup.Request.SPECIFIC, team="blue"))
    assert [p.name for p in res.providers] == ["blue_1_kick", "blue_1_shoot"]
    res = ros.call(lookup, Lookup.Request(service_class="Kick", direction=Lookup.Request.BOTH, max_results=1))
    assert [p.name for p in res.providers] == ["blue_1_kick"]
    res = ros.call(lookup, Lookup.Request(service_class="Nope"))
    assert not res.ok and "unknown service class" in res.reason
    res = ros.call(lookup, Lookup.Request(service_class="Kick", direction=9))
    assert not res.ok

    dereg = probe.create_client(Deregister, f"/commag_{unique}/deregister")
    assert ros.call(dereg, Deregister.Request(name="red_1_kick")).accepted
    assert not ros.call(dereg, Deregister.Request(name="red_1_kick")).accepted
    deregistered_at = time.time()  # diagnostics carry wall-clock stamps

    ros.spin_until(lambda: len(events) >= 5, what="5 events")
    assert [e.kind_name for e in events] == ["registered"] * 4 + ["deregistered"]
    assert events[0].record.name == "blue_1_action" and events[0].kind == RegistryEvent.REGISTERED

    # A late joiner gets the latest registry at once (transient local).
    late = ros.node(f"late_{unique}")
    snapshots: list[Registry] = []
    late.create_subscription(Registry, f"/commag_{unique}/registry", snapshots.append, SNAPSHOT_QOS)
    ros.spin_until(lambda: snapshots, what="registry snapshot")
    assert sorted(r.name for r in snapshots[-1].records) == ["blue_1_action", "blue_1_kick", "blue_1_shoot"]

    def component_statuses():
        # Only arrays published after the deregistration (an earlier one may still arrive late).
        mine = [
            a
            for a in diags
            if any(s.name == "commag: blue_1_kick" for s in a.status)
            and a.header.stamp.sec + a.header.stamp.nanosec * 1e-9 > deregistered_at
        ]
        return mine[-1].status if mine else None

    ros.spin_until(component_statuses, what="diagnostics")
    statuses = {s.name: s for s in component_statuses()}
    assert statuses["commag: blue_1_kick"].level == DiagnosticStatus.OK
    assert statuses["commag: blue_1_kick"].message == "healthy"
    assert "3 healthy" in statuses["commag"].message


def test_missed_lease_is_seen_as_events(ros, unique, tmp_path):
    commag = make_commag(ros, unique, tmp_path, max_failures=1)
    commag.trigger_configure()
    commag.trigger_activate()
    probe = ros.node(f"probe_{unique}")
    events: list[RegistryEvent] = []
    probe.create_subscription(RegistryEvent, f"/commag_{unique}/events", events.append, EVENTS_QOS)
    ros.spin_until(lambda: probe.count_publishers(f"/commag_{unique}/events") > 0, what="events publisher")
    ros.spin_for(0.3)
    register = probe.create_client(Register, f"/commag_{unique}/register")
    short = ComponentRecord(name="blue_2_dash", service_class="Dash", lease_period=0.2)
    assert ros.call(register, Register.Request(component=short)).accepted
    # No launch command: suspect, then withdrawn after (1 + max_failures) silent leases.
    ros.spin_until(lambda: [e.kind_name for e in events][-1:] == ["withdrawn"], what="withdrawal")
    assert [e.kind_name for e in events] == ["registered", "suspect", "withdrawn"]
    assert events[-1].record.state == "withdrawn"


def test_lifecycle_services_answer_as_ros2_lifecycle_uses_them(ros, unique, tmp_path):
    """get_state / get_available_states / get_available_transitions / change_state, the way `ros2 lifecycle` asks."""
    from lifecycle_msgs.msg import State, Transition
    from lifecycle_msgs.srv import ChangeState, GetAvailableStates, GetAvailableTransitions, GetState

    make_commag(ros, unique, tmp_path)
    cli = ros.node(f"cli_{unique}")
    base = f"/commag_{unique}"
    get_state = cli.create_client(GetState, f"{base}/get_state")
    states = cli.create_client(GetAvailableStates, f"{base}/get_available_states")
    transitions = cli.create_client(GetAvailableTransitions, f"{base}/get_available_transitions")
    change = cli.create_client(ChangeState, f"{base}/change_state")
    register = cli.create_client(Register, f"{base}/register")

    assert ros.call(get_state, GetState.Request()).current_state.label == "unconfigured"
    labels = {s.label for s in ros.call(states, GetAvailableStates.Request()).available_states}
    assert {"unconfigured", "inactive", "active", "finalized"} <= labels

    def step(transition_id: int, expect: str) -> None:
        assert ros.call(change, ChangeState.Request(transition=Transition(id=transition_id))).success
        assert ros.call(get_state, GetState.Request()).current_state.label == expect

    step(Transition.TRANSITION_CONFIGURE, "inactive")
    step(Transition.TRANSITION_ACTIVATE, "active")
    # The ComMAg's own services answer after transitions driven from outside.
    assert ros.call(register, Register.Request(component=record("blue_1_kick"))).accepted
    offered = [
        t.transition.label for t in ros.call(transitions, GetAvailableTransitions.Request()).available_transitions
    ]
    assert "deactivate" in offered
    step(Transition.TRANSITION_DEACTIVATE, "inactive")
    assert not ros.call(register, Register.Request(component=record("blue_1_kick"))).accepted
    step(Transition.TRANSITION_ACTIVATE, "active")  # timers and services come back
    assert ros.call(register, Register.Request(component=record("blue_2_kick"))).accepted
    step(Transition.TRANSITION_DEACTIVATE, "inactive")
    step(Transition.TRANSITION_CLEANUP, "unconfigured")
    step(Transition.TRANSITION_CONFIGURE, "inactive")  # configure again after cleanup
    step(Transition.TRANSITION_INACTIVE_SHUTDOWN, "finalized")
    assert ros.call(get_state, GetState.Request()).current_state.id == State.PRIMARY_STATE_FINALIZED
