"""Each cf_interfaces service type is served and called, each message type published and received."""

from __future__ import annotations

from builtin_interfaces.msg import Time

from cf_interfaces.msg import ComponentRecord, KeyValue, Registry, RegistryEvent
from cf_interfaces.srv import Deregister, Lookup, Register


def test_services_round_trip(ros, unique):
    server = ros.node(f"iface_server_{unique}")
    client_node = ros.node(f"iface_client_{unique}")
    seen = {}

    def register(req, res):
        seen["register"] = req.component
        res.accepted, res.reason, res.lease_period = True, "registered", 2.5
        return res

    def deregister(req, res):
        seen["deregister"] = req.name
        res.accepted, res.reason = True, "deregistered"
        return res

    def lookup(req, res):
        seen["lookup"] = (req.service_class, req.direction, req.team, req.player_number, req.max_results)
        res.ok, res.providers = True, [ComponentRecord(name="p1", service_class=req.service_class, state="healthy")]
        return res

    server.create_service(Register, f"/{unique}/register", register)
    server.create_service(Deregister, f"/{unique}/deregister", deregister)
    server.create_service(Lookup, f"/{unique}/lookup", lookup)

    record = ComponentRecord(
        name="blue_1_kick",
        service_class="Kick",
        launch_command=["/opt/x/bin/kick", "--fast"],
        lease_period=2.5,
        team="blue",
        player_number=1,
        transport=ComponentRecord.TRANSPORT_TCP,
        languages=["cf-lang"],
        metadata=[KeyValue(key="version", value="3")],
    )
    res = ros.call(client_node.create_client(Register, f"/{unique}/register"), Register.Request(component=record))
    assert res.accepted and res.lease_period == 2.5 and seen["register"] == record
    res = ros.call(client_node.create_client(Deregister, f"/{unique}/deregister"), Deregister.Request(name="x"))
    assert res.accepted and seen["deregister"] == "x"
    req = Lookup.Request(
        service_class="Kick", direction=Lookup.Request.BOTH, team="blue", player_number=1, max_results=3
    )
    res = ros.call(client_node.create_client(Lookup, f"/{unique}/lookup"), req)
    assert res.ok and res.providers[0].name == "p1" and seen["lookup"] == ("Kick", 2, "blue", 1, 3)


def test_messages_round_trip(ros, unique):
    pub_node = ros.node(f"iface_pub_{unique}")
    sub_node = ros.node(f"iface_sub_{unique}")
    got = {}
    sub_node.create_subscription(RegistryEvent, f"/{unique}/events", lambda m: got.setdefault("event", m), 10)
    sub_node.create_subscription(Registry, f"/{unique}/registry", lambda m: got.setdefault("registry", m), 10)
    event_pub = pub_node.create_publisher(RegistryEvent, f"/{unique}/events", 10)
    registry_pub = pub_node.create_publisher(Registry, f"/{unique}/registry", 10)
    event = RegistryEvent(
        kind=RegistryEvent.WITHDRAWN,
        kind_name="withdrawn",
        record=ComponentRecord(name="c", state=ComponentRecord.STATE_WITHDRAWN, failures=3),
        reason="3 failed launches",
        stamp=Time(sec=5),
    )
    snapshot = Registry(stamp=Time(sec=6), records=[ComponentRecord(name="a"), ComponentRecord(name="b")])

    def publish_until_seen():
        event_pub.publish(event)
        registry_pub.publish(snapshot)
        return "event" in got and "registry" in got

    ros.spin_until(publish_until_seen, what="both messages")
    assert got["event"] == event and got["registry"] == snapshot
