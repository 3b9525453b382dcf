"""Agents in C++, Java, Prolog and Python join through the installed gateway and talk with ROS agents.

Needs `g++` and `cmake`, `java` (JDK 17) and `swipl` (Debian g++ cmake openjdk-17-jdk-headless
swi-prolog-nox). .ci/run installs them and sets CF_REQUIRE_FOREIGN_CLIENTS=1, so in CI these
tests fail rather than skip when one is missing.
"""

from __future__ import annotations

import os
import random
import shutil
import signal
import socket
import subprocess
import time
from pathlib import Path

import pytest

from cf_commag.client import Agent
from cf_commag.gateway_client import GatewayClient
from cf_lang.acl import AclMessage, AgentId, Performative
from cf_lang.sexp import Keyword, SexpError, Symbol, dumps, loads, quote
from cf_system import start_commag, start_component, start_gateway

ROOT = Path(__file__).resolve().parent.parent


def need(tool: str) -> str:
    path = shutil.which(tool)
    if path is None:
        if os.environ.get("CF_REQUIRE_FOREIGN_CLIENTS") == "1":
            pytest.fail(f"{tool} is required here (CF_REQUIRE_FOREIGN_CLIENTS=1) but not installed")
        package = {"java": "openjdk-17-jdk-headless", "swipl": "swi-prolog-nox"}.get(tool, tool)
        pytest.skip(f"{tool} is not installed (Debian: {package})")
    return path


@pytest.fixture
def framework(procs, probe, tag, tmp_path):
    """ComMAg + gateway + a ROS Kick provider; returns the gateway's port."""
    start_commag(procs, tag, tmp_path)
    port_file = tmp_path / "gateway.port"
    start_gateway(procs, tag, port_file)
    start_component(procs, tag, f"kick_{tag}", "--service-class", "Kick", "--team", "blue")
    probe.wait_kind(f"kick_{tag}", "registered")
    probe.spin_until(lambda: port_file.exists() and port_file.read_text().strip(), what="gateway port")
    return int(port_file.read_text())


def run_foreign_agent(procs, probe, tag, argv, log_name, agent_name):
    """The foreign agent asks the ROS Kick provider, then a ROS agent asks it; both answers are checked."""
    proc = procs.start(argv, log_name)
    probe.spin_until(
        lambda: "SERVING" in procs.log(log_name) or proc.poll() is not None, timeout=60, what=f"{log_name} to serve"
    )
    log = procs.log(log_name)
    assert "REGISTERED" in log and f"PROVIDERS [kick_{tag}]" in log, log
    assert "ANSWER inform (done 1)" in log, log
    # It registered through the gateway: the ComMAg knows it as a TCP component.
    assert probe.lookup("PlayerDecision", team="blue") == [agent_name]
    # Now a ROS agent runs a fipa-request with it.
    asker = Agent(probe.node, name=f"asker_{tag}", service_class="Monitoring", commag=f"/commag_{tag}")
    probe.spin_until(lambda: asker.registered, what="asker registered")
    future = asker.request(
        agent_name, "(exec Player kick :playerNumber 9 :whichTeam our :power 50 :direction 0)", timeout=20.0
    )
    probe.spin_until(future.done, timeout=30, what="answer from the foreign agent")
    reply = future.result()
    asker.close()
    assert reply.ok, (reply, procs.log(log_name))
    assert proc.wait(timeout=30) == 0, procs.log(log_name)
    assert f"SERVED asker_{tag}" in procs.log(log_name) and "BYE" in procs.log(log_name)
    return reply


def test_java_agent(framework, procs, probe, tag):
    java = need("java")
    name = f"java_{tag}"
    argv = [java, str(ROOT / "clients/java/CfGatewayClient.java"), "127.0.0.1", str(framework), name]
    reply = run_foreign_agent(procs, probe, tag, argv, "java", name)
    assert reply.content.startswith("(done-by-java")
    probe.wait_kind(name, "deregistered")  # (bye) deregisters


def test_prolog_agent(framework, procs, probe, tag):
    swipl = need("swipl")
    name = f"prolog_{tag}"
    argv = [swipl, str(ROOT / "clients/prolog/cf_gateway_client.pl"), "127.0.0.1", str(framework), name]
    reply = run_foreign_agent(procs, probe, tag, argv, "prolog", name)
    assert reply.content == "(done-by-prolog)"


def test_python_agent_and_lease_kept_by_its_own_messages(framework, procs, probe, tag):
    name = f"py_{tag}"
    with GatewayClient("127.0.0.1", framework, name=name) as gw:
        # A lease of 1.5 s against pings 0.2 s apart: a 0.6 s lease was once missed on a loaded machine.
        assert gw.register("WorldModel", team="blue", player=2, lease=1.5) == 1.5
        assert [p["name"] for p in gw.lookup("Kick", team="blue")] == [f"kick_{tag}"]
        answer = gw.request(f"kick_{tag}", "(val Game time)", protocol="fipa-query")
        assert answer.performative.value == "inform" and answer.content.startswith("(Game :time")
        for _ in range(15):  # pings keep the lease alive, two leases long
            gw.ping()
            probe.spin_for(0.2)
        assert "suspect" not in probe.kinds(name)
        # A hung agent (connected, silent) is detected like any other component, and withdrawn:
        # it has no launch command, and a TCP agent can never get one.
        probe.wait_kind(name, "suspect", timeout=20)
        probe.wait_kind(name, "withdrawn", timeout=20)
        assert probe.lookup("WorldModel") == []


def test_vanished_agent_is_withdrawn(framework, procs, probe, tag):
    name = f"gone_{tag}"
    gw = GatewayClient("127.0.0.1", framework, name=name)
    gw.register("Hearing", lease=0.5)
    probe.wait_kind(name, "registered")
    gw.sock.close()  # no bye: it just vanishes
    probe.wait_kind(name, "withdrawn", timeout=20)
    time.sleep(0.1)


def test_a_hung_ros_agent_stalls_nobody_and_loses_nothing(framework, procs, probe, tag):
    """A ROS agent that takes nothing (stopped) fills its queue in DDS, after which every publish
    to it would block and fail. The gateway holds its messages instead, goes on serving everyone
    (the flooding client included), and delivers them all once the agent runs again."""
    hung = f"hung_{tag}"
    proc = start_component(procs, tag, hung, "--service-class", "Hearing", "--lease", "120")
    probe.wait_kind(hung, "registered")
    line = '(inform :receiver (set (agent-identifier :name {})) :content "x" :reply-with r{})\n'
    with GatewayClient("127.0.0.1", framework, name=f"flood_{tag}", timeout=60) as flood:
        # A lookup names it: the gateway relays to it even before its registry snapshot shows it.
        assert [p["name"] for p in flood.lookup("Hearing")] == [hung]
        flood.send_line(line.format(hung, 0).strip())
        assert flood.receive().performative is Performative.NOT_UNDERSTOOD
        os.kill(proc.pid, signal.SIGSTOP)
        try:
            # One DDS sample per message (a ping after each, so that no two are read in one
            # go and relayed together), more than DDS queues for a reader that takes nothing
            # (5000 here): the client's own connection is served all along...
            n = 6000
            for i in range(1, n + 1):
                flood.file.write(line.format(hung, i).encode())
                flood.ping()
            with GatewayClient("127.0.0.1", framework, name=f"other_{tag}") as other:  # ...and everyone else
                reply = other.request(f"kick_{tag}", "(exec Player kick :playerNumber 9 :whichTeam our :power 50)")
                assert reply.performative is Performative.INFORM
        finally:
            os.kill(proc.pid, signal.SIGCONT)
        answered = {flood.receive().in_reply_to for _ in range(n)}  # each one answered: none lost
        assert answered == {f"r{i}" for i in range(1, n + 1)}


# ---- C++ ---------------------------------------------------------------------------------------


@pytest.fixture(scope="module")
def cpp(tmp_path_factory):
    """clients/cpp built with CMake, as a team would: the example agent and the reader check."""
    need("g++")
    cmake = need("cmake")
    build = tmp_path_factory.mktemp("cpp-build")
    subprocess.run([cmake, "-S", str(ROOT / "clients/cpp"), "-B", str(build)], check=True, capture_output=True)
    done = subprocess.run([cmake, "--build", str(build)], capture_output=True, text=True)
    assert done.returncode == 0, done.stdout + done.stderr
    assert "warning" not in done.stdout + done.stderr, done.stdout + done.stderr
    return build


def test_cpp_agent(framework, procs, probe, tag, cpp):
    name = f"cpp_{tag}"
    argv = [str(cpp / "cf_example"), "127.0.0.1", str(framework), name]
    reply = run_foreign_agent(procs, probe, tag, argv, "cpp", name)
    assert reply.content.startswith("(done-by-cpp exec ")  # it read the request's content as an expression
    probe.wait_kind(name, "deregistered")  # (bye) deregisters


@pytest.fixture(scope="module")
def java_build(tmp_path_factory):
    """clients/java compiled (the example's classes and the checks)."""
    need("java")
    javac = need("javac")
    out = tmp_path_factory.mktemp("java-build")
    sources = [str(p) for p in sorted((ROOT / "clients/java").glob("*.java"))]
    done = subprocess.run([javac, "-d", str(out), *sources], capture_output=True, text=True)
    assert done.returncode == 0, done.stdout + done.stderr
    return out


def _request_check(request, language: str) -> list[str]:
    """The command line of a client's request check, before its HOST PORT NAME MUTE arguments."""
    if language == "cpp":
        return [str(request.getfixturevalue("cpp") / "cf_request_check")]
    if language == "java":
        return [need("java"), "-cp", str(request.getfixturevalue("java_build")), "RequestCheck"]
    check = ROOT / "clients/prolog/request_check.pl"
    return [
        need("swipl"),
        "-g",
        f"consult('{check}')",
        "-g",
        "request_check",
        "-t",
        "halt",
        str(ROOT / "clients/prolog/cf_gateway_client.pl"),
    ]


@pytest.mark.parametrize("language", ["cpp", "java", "prolog"])
def test_a_foreign_request_ends_on_the_gateways_failure_and_at_its_reply_by(
    request, language, framework, procs, probe, tag
):
    """A request to a name nobody registered ends with the gateway's failure instead of waiting
    for ever; one that nobody answers ends at its timeout, which the receiver reads as the
    request's :reply-by on the wall clock; a message of another conversation that came while
    the client waited is kept for it."""
    argv = _request_check(request, language)
    mute = f"mute_{tag}"
    with GatewayClient("127.0.0.1", framework, name=mute, timeout=60) as gw:
        gw.register("Hearing", lease=30)
        proc = procs.start([*argv, "127.0.0.1", str(framework), f"rc_{tag}", mute], "request_check")
        asked = gw.receive()  # taken, never answered...
        received = time.time()
        # ...but a message of another conversation comes while the client waits: it must keep it.
        assert [p["name"] for p in gw.lookup("Monitoring", direction="exact")] == [f"rc_{tag}"]
        gw.send(
            AclMessage(Performative.INFORM, receivers=(AgentId(f"rc_{tag}"),), content="(kept)", conversation_id="x")
        )
        assert proc.wait(timeout=60) == 0, procs.log("request_check")
    lines = procs.log("request_check").splitlines()
    unknown = next(line for line in lines if line.startswith("UNKNOWN"))
    timeout = next(line for line in lines if line.startswith("TIMEOUT"))
    assert "unknown receiver nobody_registered_this" in unknown, lines
    assert mute in timeout and "ANSWERED" not in timeout, lines
    assert "KEPT (kept)" in lines, lines
    assert asked.performative is Performative.REQUEST and asked.reply_by is not None
    assert received - 10 < asked.reply_by < received + 10  # wall-clock seconds, not a monotonic clock


def test_a_java_request_timing_out_in_the_middle_of_a_line_loses_nothing(request, procs):
    """A slow network may cut a line anywhere; a request's timeout may come in the cut. The real
    gateway writes whole lines on loopback, so here a scripted peer on a real socket speaks for
    it: the welcome, then half a message of another conversation, and the rest 3 s later."""
    argv = [need("java"), "-cp", str(request.getfixturevalue("java_build")), "SplitLineCheck"]
    message = '(inform :sender (agent-identifier :name slow_peer) :receiver (set (agent-identifier :name sl)) :content "(kept whole)" :conversation-id other)'
    with socket.create_server(("127.0.0.1", 0)) as server:
        server.settimeout(60)
        proc = procs.start([*argv, "127.0.0.1", str(server.getsockname()[1]), "sl"], "split_line_check")
        conn, _ = server.accept()
        with conn, conn.makefile("rb") as lines:
            conn.settimeout(60)
            assert lines.readline().startswith(b"(hello :name sl")
            conn.sendall(b"(welcome :name sl)\n")
            assert lines.readline().startswith(b"(request ")
            half = len(message) // 2
            conn.sendall(message[:half].encode())
            time.sleep(3.0)  # the request's 1 s timeout comes while half the line has been read
            conn.sendall(message[half:].encode() + b"\n")
            assert lines.readline() == b"(bye)\n"
            conn.sendall(b"(bye)\n")
    assert proc.wait(timeout=60) == 0, procs.log("split_line_check")
    log = procs.log("split_line_check").splitlines()
    assert any(line.startswith("TIMEOUT no answer from slow_peer") for line in log), log
    assert "KEPT (kept whole)" in log, log


def _form(value) -> str:
    """What cf_sexp_check prints for a value the reference reader gave."""
    if isinstance(value, list):
        return "(" + " ".join(_form(v) for v in value) + ")"
    if isinstance(value, Keyword):
        return f"K:{value.name}"
    if isinstance(value, Symbol):
        return f"Y:{value.name}"
    if isinstance(value, bool):
        raise AssertionError("the reader gives no booleans")
    if isinstance(value, int):
        return f"I:{value}"
    if isinstance(value, float):
        return f"F:{format(value, '.17g')}"
    return f"S:{quote(value)}"


def _random_text(rng: random.Random, depth: int = 0) -> str:
    atoms = [
        "a",
        "-",
        "x1",
        ":k",
        ":player-number",
        "0",
        "-0",
        "+007",
        "12",
        "-3.5",
        ".5",
        "5.",
        "1e3",
        "2E-2",
        "1e",
        "inf",
        "nan",
        "1_000",
        '""',
        '"a b"',
        '"q\\"uote"',
        '"line\\nbreak"',
        '"tab\\t"',
        "é",
        "T10:20",
    ]
    if depth > 4 or rng.random() < 0.4:
        return rng.choice(atoms)
    items = [_random_text(rng, depth + 1) for _ in range(rng.randint(0, 4))]
    return "(" + rng.choice([" ", "  ", "\t", "\n", " ; note\n"]).join(items) + ")"


def _mutate(rng: random.Random, text: str) -> str:
    pos = rng.randint(0, len(text))
    return text[:pos] + rng.choice(['"', "(", ")", "\\", ";", ":", "\n", " ", "\\q", ""]) + text[pos + 1 :]


def test_cpp_reader_reads_what_the_reference_reader_reads(cpp):
    """docs/language.md section 1: the same texts give the same expressions, or both an error."""
    rng = random.Random(20261122)
    texts = [
        "(exec Player kick :playerNumber 9 :whichTeam our :power 70.5 :direction -0.2)",
        '(inform :sender (agent-identifier :name a) :content "(done 1)" :reply-with "r\\"1")',
        "(a ; a comment\n b)",
        "(a ;c)",
        '(a"b")',
        '("\\q")',
        "(a)b",
        ":",
        "1e999",
        "(" * 64 + ")" * 64,
        "(" * 65 + ")" * 65,
        "1" * 4000,
        "1" * 4001,
        "",
        "   ",
        ")",
        '"unclosed',
        "(unclosed",
    ]
    for _ in range(1500):
        text = _random_text(rng)
        texts.append(text)
        texts.append(_mutate(rng, text))
    texts += [dumps(loads(t)) for t in texts[:200] if _reads(t)]  # what the writer writes reads back
    done = subprocess.run(
        [str(cpp / "cf_sexp_check")], input="\0".join(texts).encode(), capture_output=True, timeout=60
    )
    lines = done.stdout.decode().splitlines()
    assert len(lines) == len(texts)
    for text, line in zip(texts, lines, strict=True):
        try:
            expected = "OK " + _form(loads(text))
        except SexpError:
            assert line.startswith("ERROR "), (text, line)
            continue
        assert line == expected, (text, line)


def _reads(text: str) -> bool:
    try:
        loads(text)
    except SexpError:
        return False
    return True
