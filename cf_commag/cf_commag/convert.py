"""Converts between cf_interfaces messages and the ROS-free records and events."""

from __future__ import annotations

from cf_interfaces.msg import ComponentRecord, KeyValue, RegistryEvent
from cf_interfaces.srv import Lookup
from cf_lang.taxonomy import Direction

from .records import Directory, Entry, Query, Record, Transport
from .registry import Event


def to_record(msg: ComponentRecord) -> Record:
    """A Record from a message; raises ValueError on a bad transport."""
    transport = msg.transport or "ros"
    if transport not in ("ros", "tcp"):
        raise ValueError(f"transport must be 'ros' or 'tcp', not {transport!r}")
    return Record(
        name=msg.name,
        service_class=msg.service_class,
        address=msg.address,
        port=msg.port,
        launch_command=tuple(msg.launch_command),
        lease_period=msg.lease_period,
        team=msg.team,
        player_number=msg.player_number,
        transport=Transport(transport),
        languages=tuple(msg.languages),
        ontologies=tuple(msg.ontologies),
        metadata=tuple((kv.key, kv.value) for kv in msg.metadata),
    )


def to_msg(record: Record, entry: Entry | None = None) -> ComponentRecord:
    msg = ComponentRecord(
        name=record.name,
        address=record.address,
        port=record.port,
        service_class=record.service_class,
        launch_command=list(record.launch_command),
        lease_period=float(entry.lease if entry else record.lease_period),
        team=record.team,
        player_number=record.player_number,
        transport=record.transport.value,
        languages=list(record.languages),
        ontologies=list(record.ontologies),
        metadata=[KeyValue(key=k, value=v) for k, v in record.metadata],
    )
    if entry is not None:
        msg.state = entry.state.value
        msg.failures = entry.failures
    return msg


def event_to_msg(event: Event, stamp) -> RegistryEvent:
    record = to_msg(event.record)
    record.state = event.state.value
    record.failures = event.failures
    return RegistryEvent(
        kind=int(event.kind), kind_name=event.kind.name.lower(), record=record, reason=event.reason, stamp=stamp
    )


def to_query(request: Lookup.Request) -> Query:
    """A Query from a Lookup request; raises ValueError on a bad direction."""
    return Query(
        service_class=request.service_class,
        direction=Direction(request.direction),
        team=request.team,
        player_number=request.player_number,
        include_suspect=request.include_suspect,
        max_results=request.max_results,
    )


def query_to_request(query: Query) -> Lookup.Request:
    return Lookup.Request(
        service_class=query.service_class,
        direction=int(query.direction),
        team=query.team,
        player_number=query.player_number,
        include_suspect=query.include_suspect,
        max_results=query.max_results,
    )


def directory_from_msg(msg) -> Directory:
    """A lookup cache from the ComMAg's registry snapshot (records it cannot read are left out)."""
    directory = Directory()
    for rec in msg.records:
        try:
            directory.put(entry_from_msg(rec))
        except ValueError:
            continue
    return directory


def entry_from_msg(msg: ComponentRecord) -> Entry:
    """An Entry (record and health) as seen by an agent's lookup cache."""
    from .records import State

    return Entry(
        record=to_record(msg), state=State(msg.state or "healthy"), lease=msg.lease_period, failures=msg.failures
    )
