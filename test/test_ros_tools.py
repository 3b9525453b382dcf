"""What the standard ROS 2 tools do, done through rclpy against the installed executables.

The ``ros2`` command is not on PyPI, so CI cannot run it; each test here makes the same calls
``ros2 lifecycle``, ``ros2 node``, ``ros2 param``, ``ros2 topic``, ``ros2 service`` and
``ros2 interface`` make, to the same services and topics, and checks what a user would see.
"""

from __future__ import annotations

import re
import uuid
from pathlib import Path

import pytest
from ament_index_python.packages import get_package_share_directory
from diagnostic_msgs.msg import DiagnosticArray
from lifecycle_msgs.msg import Transition
from lifecycle_msgs.srv import ChangeState, GetAvailableStates, GetState
from rcl_interfaces.msg import ParameterType
from rcl_interfaces.srv import DescribeParameters, GetParameters, ListParameters
from std_msgs.msg import String

from cf_commag.transport.qos import INBOX_QOS
from cf_interfaces.msg import Registry
from cf_interfaces.srv import Lookup
from cf_system import Probe, Processes, executable, start_commag

RCLPY_OWN = {"use_sim_time", "start_type_description_service"}  # declared by rclpy itself


@pytest.fixture(scope="module")
def system(tmp_path_factory):
    """A ComMAg (not autostarted), a gateway, a simulator, one player's three components, an rcss adapter,
    and another player's three components hosted in one process (the players container)."""
    tag = "t" + uuid.uuid4().hex[:8]
    tmp = tmp_path_factory.mktemp("ros_tools")
    procs, probe = Processes(tag, tmp), Probe(f"/commag_{tag}", tag)
    commag = f"/commag_{tag}"
    team = f"{tag}team"
    start_commag(procs, tag, tmp, "autostart:=false")
    common = ["-p", f"commag:={commag}"]
    player = ["-p", "side:=l", "-p", "number:=7", "-p", f"team:={team}", "-p", f"sim:=sim_{tag}", *common]
    procs.start([executable("cf_sim_backend", "perception"), "--ros-args", *player], "perception")
    procs.start([executable("cf_sim_backend", "action"), "--ros-args", *player], "action")
    decision = ["-p", "number:=7", "-p", f"team:={team}", *common]
    procs.start([executable("cf_decision", "decision"), "--ros-args", *decision], "decision")
    gateway = ["-r", f"__node:=gateway_{tag}", "-p", "port:=0", *common]
    procs.start([executable("cf_commag", "gateway"), "--ros-args", *gateway], "gateway")
    sim = ["-r", f"__node:=sim_{tag}", "-p", f"sim:=sim_{tag}", "-p", "left_size:=7", "-p", "right_size:=0"]
    procs.start([executable("cf_sim_backend", "sim"), "--ros-args", *sim, *common], "sim")
    rcss = ["-p", f"team:={team}", "-p", "number:=3", "-p", "port:=9", "-p", "server_timeout:=600.0", *common]
    procs.start([executable("cf_sim_backend", "rcss_player"), "--ros-args", *rcss], "rcss_player")
    hosted = ["-p", "side:=l", "-p", "numbers:=[8]", "-p", f"team:={team}", "-p", f"sim:=sim_{tag}", *common]
    procs.start([executable("cf_sim_backend", "players"), "--ros-args", *hosted], "players")
    yield {"tag": tag, "team": team, "commag": commag, "procs": procs, "probe": probe}
    probe.close()
    procs.kill_all()


def test_ros2_lifecycle_get_set_list_on_the_running_commag(system):
    probe, base = system["probe"], system["commag"]
    node = probe.node
    get_state = node.create_client(GetState, f"{base}/get_state")
    change = node.create_client(ChangeState, f"{base}/change_state")
    states = node.create_client(GetAvailableStates, f"{base}/get_available_states")
    assert probe.call(get_state, GetState.Request()).current_state.label == "unconfigured"
    labels = [s.label for s in probe.call(states, GetAvailableStates.Request()).available_states]
    assert {"unconfigured", "inactive", "active", "finalized"} <= set(labels)
    for transition, label in (
        (Transition.TRANSITION_CONFIGURE, "inactive"),
        (Transition.TRANSITION_ACTIVATE, "active"),
    ):
        assert probe.call(change, ChangeState.Request(transition=Transition(id=transition))).success
        assert probe.call(get_state, GetState.Request()).current_state.label == label
    # Active now: the components register, and `ros2 service call .../lookup` finds them.
    team = system["team"]
    everything = {"direction": Lookup.Request.SPECIFIC, "team": team}
    seven = {f"{team}_7_perception", f"{team}_7_action", f"{team}_7_decision"}
    probe.spin_until(
        lambda: seven <= set(probe.lookup("Service", **everything)), 90, "player 7's components registered"
    )
    answer = probe.call(probe.lookup_client, Lookup.Request(service_class="Kick", team=team, player_number=7))
    assert answer.ok and [p.name for p in answer.providers] == [f"{team}_7_action"]


def _bring_up(system) -> None:
    """Configure and activate the ComMAg through its lifecycle services, unless that was done already."""
    probe, base = system["probe"], system["commag"]
    get_state = probe.node.create_client(GetState, f"{base}/get_state")
    if probe.call(get_state, GetState.Request()).current_state.label == "unconfigured":
        test_ros2_lifecycle_get_set_list_on_the_running_commag(system)


def test_ros2_node_list_shows_each_component_under_its_agent_name(system):
    _bring_up(system)
    team = system["team"]
    wanted = {f"{team}_7_perception", f"{team}_7_action", f"{team}_7_decision", f"{team}_3_rcss_player"}
    # Components hosted in one process (the players container) are nodes of their own, named alike.
    wanted |= {f"{team}_players", f"{team}_8_perception", f"{team}_8_action", f"{team}_8_decision"}
    probe = system["probe"]
    probe.spin_until(lambda: wanted <= set(probe.node.get_node_names()), 60, f"nodes {wanted}")


def test_ros2_param_list_describe_get_on_every_node(system):
    _bring_up(system)
    tag, team, probe = system["tag"], system["team"], system["probe"]
    nodes = [
        f"commag_{tag}",
        f"gateway_{tag}",
        f"sim_{tag}",
        f"{team}_7_perception",
        f"{team}_7_action",
        f"{team}_7_decision",
        f"{team}_3_rcss_player",
        f"{team}_players",
        f"{team}_8_perception",
        f"{team}_8_decision",
    ]
    for name in nodes:
        listed = probe.call(
            probe.node.create_client(ListParameters, f"/{name}/list_parameters"), ListParameters.Request()
        )
        names = [n for n in listed.result.names if n not in RCLPY_OWN]
        assert len(names) >= 3, (name, names)
        described = probe.call(
            probe.node.create_client(DescribeParameters, f"/{name}/describe_parameters"),
            DescribeParameters.Request(names=names),
        ).descriptors
        missing = [d.name for d in described if not d.description.strip() or d.type == ParameterType.PARAMETER_NOT_SET]
        assert not missing, f"{name}: parameters without a description or a type: {missing}"
        values = probe.call(
            probe.node.create_client(GetParameters, f"/{name}/get_parameters"), GetParameters.Request(names=names)
        ).values
        assert len(values) == len(names) and all(v.type != ParameterType.PARAMETER_NOT_SET for v in values), name
    number = probe.call(
        probe.node.create_client(GetParameters, f"/{team}_7_decision/get_parameters"),
        GetParameters.Request(names=["number", "team"]),
    ).values
    assert (number[0].integer_value, number[1].string_value) == (7, team)
    number = probe.call(
        probe.node.create_client(GetParameters, f"/{team}_8_decision/get_parameters"),
        GetParameters.Request(names=["number", "team"]),
    ).values
    assert (number[0].integer_value, number[1].string_value) == (8, team)  # a hosted node's own parameters


def test_ros2_topic_echo_of_events_registry_diagnostics_and_an_inbox(system):
    _bring_up(system)
    probe, team, base = system["probe"], system["team"], system["commag"]
    node = probe.node
    assert probe.spin_until(lambda: [e for e in probe.events if e.kind_name == "registered"], 30, "an event")
    assert probe.spin_until(lambda: probe.snapshot and len(probe.snapshot.records) >= 4, 30, "the registry")
    diagnostics: list[DiagnosticArray] = []
    node.create_subscription(DiagnosticArray, "/diagnostics", diagnostics.append, 10)
    mine = f"commag: {team}_7_perception"
    probe.spin_until(lambda: any(s.name == mine for a in diagnostics for s in a.status), 30, "diagnostics")
    assert isinstance(probe.snapshot, Registry)

    # `ros2 topic pub` a FIPA query to the perception's inbox; `ros2 topic echo` our own inbox.
    me = f"{system['tag']}_cli"
    answers: list[str] = []
    node.create_subscription(String, f"/cf/agents/{me}/inbox", lambda m: answers.append(m.data), INBOX_QOS)
    inbox = node.create_publisher(String, f"/cf/agents/{team}_7_perception/inbox", INBOX_QOS)
    probe.spin_until(lambda: inbox.get_subscription_count() > 0, 30, "the perception's inbox")
    query = (
        f"(query-ref :sender (agent-identifier :name {me}) :receiver (set (agent-identifier :name {team}_7_perception))"
        ' :content "(val Game time)" :protocol fipa-query :conversation-id q1)'
    )

    def ask():
        if not answers:
            inbox.publish(String(data=query))
            probe.spin_for(0.5)
        return answers

    probe.spin_until(ask, 60, "the perception's answer")
    assert re.match(r"\((inform|failure) :sender \(agent-identifier :name \w+_7_perception\)", answers[0]), answers[0]
    assert ":conversation-id q1" in answers[0]
    assert base  # the ComMAg is not in this path: agents talk directly


def test_ros2_interface_show_of_every_cf_interfaces_type():
    """`ros2 interface show` prints the installed .msg/.srv: each opens with a comment saying who uses it."""
    share = Path(get_package_share_directory("cf_interfaces"))
    files = sorted([*share.glob("msg/*.msg"), *share.glob("srv/*.srv")])
    assert {f.stem for f in files} >= {"ComponentRecord", "KeyValue", "Registry", "RegistryEvent", "Register", "Lookup"}
    for f in files:
        assert f.read_text().startswith("#"), f"{f.name} has no opening comment"
        module = __import__(f"cf_interfaces.{f.parent.name}", fromlist=[f.stem])
        assert hasattr(module, f.stem), f.stem  # the type support is built and importable
