"""The match report: one self-contained HTML page with pictures of a match (ROS-free).

From a match log (docs/simulator.md) and, optionally, the ComMAg's registry
events: the score and statistics, an animated replay of the match with the
registry events on its timeline (replay.py), the ball's heat map and path with
shots and goals, every player's trajectory, and a timeline of each component's states.

    python -m cf_sim_backend.embedded.report match.jsonl [registry-events.json] [report.html]
"""

from __future__ import annotations

import html
import json
import sys
from collections import Counter
from pathlib import Path

from cf_lang.ontology import FIELD
from cf_sim_backend.embedded.replay import replay

SCALE = 8.0  # pixels per metre
COLORS = {"l": "#1f5fbf", "r": "#c8302c"}
STATE_COLORS = {
    "healthy": "#3a9d4a",
    "suspect": "#e0b020",
    "relaunching": "#e07b20",
    "withdrawn": "#c8302c",
    "deregistered": "#999999",
}


def read_log(path: Path) -> tuple[dict, list[dict], dict]:
    lines = [json.loads(line) for line in path.read_text(encoding="utf-8").splitlines() if line.strip()]
    header = lines[0] if lines and lines[0].get("format") == "cf-match-log" else {}
    end = lines[-1] if lines and lines[-1].get("end") else {}
    cycles = [x for x in lines if "t" in x]
    return header, cycles, end


def _field(length: float, width: float, body: str, title: str) -> str:
    w, h = (length + 10) * SCALE, (width + 10) * SCALE

    def px(x: float, y: float) -> tuple[float, float]:
        return ((x + length / 2 + 5) * SCALE, (width / 2 + 5 - y) * SCALE)

    x0, y0 = px(-length / 2, width / 2)
    x1, y1 = px(length / 2, -width / 2)
    cx, cy = px(0, 0)
    lines = [
        f'<rect x="0" y="0" width="{w:.0f}" height="{h:.0f}" fill="#2f7d3a"/>',
        f'<rect x="{x0:.1f}" y="{y0:.1f}" width="{x1 - x0:.1f}" height="{y1 - y0:.1f}" fill="none" stroke="white" stroke-width="2"/>',
        f'<line x1="{cx:.1f}" y1="{y0:.1f}" x2="{cx:.1f}" y2="{y1:.1f}" stroke="white" stroke-width="2"/>',
        f'<circle cx="{cx:.1f}" cy="{cy:.1f}" r="{FIELD.centre_circle_radius * SCALE:.1f}" fill="none" stroke="white" stroke-width="2"/>',
    ]
    for sign in (-1, 1):
        goal_x = length / 2 if sign > 0 else -length / 2 - 2
        gx, gy = px(goal_x, FIELD.goal_width / 2)
        lines.append(
            f'<rect x="{gx:.1f}" y="{gy:.1f}" width="{2 * SCALE:.1f}" height="{FIELD.goal_width * SCALE:.1f}" '
            'fill="white" opacity="0.8"/>'
        )
        area_x = length / 2 - FIELD.penalty_area_length if sign > 0 else -length / 2
        ax, ay = px(area_x, FIELD.penalty_area_width / 2)
        lines.append(
            f'<rect x="{ax:.1f}" y="{ay:.1f}" width="{FIELD.penalty_area_length * SCALE:.1f}" '
            f'height="{FIELD.penalty_area_width * SCALE:.1f}" '
            'fill="none" stroke="white" stroke-width="2"/>'
        )
    return (
        f'<figure><svg viewBox="0 0 {w:.0f} {h:.0f}" width="{w:.0f}" height="{h:.0f}" '
        f'xmlns="http://www.w3.org/2000/svg">{"".join(lines)}{body}</svg><figcaption>{html.escape(title)}'
        f"</figcaption></figure>"
    )


def _dimensions(header: dict) -> tuple[float, float]:
    """The field's length and width from the match log's header (the standard field if it has none)."""
    field = header.get("field", {})
    return field.get("length", FIELD.length), field.get("width", FIELD.width)


def _px(length: float, width: float, x: float, y: float) -> tuple[float, float]:
    return ((x + length / 2 + 5) * SCALE, (width / 2 + 5 - y) * SCALE)


def heat_and_path(header: dict, cycles: list[dict]) -> str:
    length, width = _dimensions(header)
    cell = 5.0
    counts: Counter = Counter()
    for c in cycles:
        if c.get("mode") == "play_on":
            bx, by = c["ball"][0], c["ball"][1]
            counts[(int((bx + length / 2) // cell), int((by + width / 2) // cell))] += 1
    peak = max(counts.values(), default=1)
    parts = []
    for (i, j), n in counts.items():
        x, y = _px(length, width, -length / 2 + i * cell, -width / 2 + (j + 1) * cell)
        parts.append(
            f'<rect x="{x:.1f}" y="{y:.1f}" width="{cell * SCALE:.1f}" height="{cell * SCALE:.1f}" '
            f'fill="#ffdd33" opacity="{0.75 * n / peak:.2f}"/>'
        )
    path = " ".join("{:.1f},{:.1f}".format(*_px(length, width, c["ball"][0], c["ball"][1])) for c in cycles[::3])
    parts.append(f'<polyline points="{path}" fill="none" stroke="white" stroke-width="1" opacity="0.45"/>')
    for c in cycles:
        for event in c.get("events", []):
            kind = event.split()
            if len(kind) == 2 and kind[0] in ("shot", "goal"):  # not "goal kick l"
                x, y = _px(length, width, c["ball"][0], c["ball"][1])
                color = COLORS.get(kind[1], "white")
                shape = (
                    f'<circle cx="{x:.1f}" cy="{y:.1f}" r="{7 if kind[0] == "goal" else 4}" fill="{color}" '
                    f'stroke="white" stroke-width="2"><title>{html.escape(event)} at cycle {c["t"]}</title></circle>'
                )
                parts.append(shape)
    return _field(
        length, width, "".join(parts), "Ball: heat map (where it was in play), path, shots (small) and goals (large)"
    )


def trajectories(header: dict, cycles: list[dict]) -> str:
    length, width = _dimensions(header)
    tracks: dict[tuple[str, int], list[str]] = {}
    for c in cycles[::5]:
        for p in c["players"]:
            tracks.setdefault((p[0], p[1]), []).append("{:.1f},{:.1f}".format(*_px(length, width, p[2], p[3])))
    parts = []
    for (side, number), points in sorted(tracks.items()):
        parts.append(
            f'<polyline points="{" ".join(points)}" fill="none" stroke="{COLORS[side]}" stroke-width="1.5" '
            f'opacity="0.6"><title>{side} {number}</title></polyline>'
        )
        last = points[-1].split(",")
        parts.append(f'<text x="{last[0]}" y="{last[1]}" fill="white" font-size="12">{number}</text>')
    teams = header.get("teams", {})
    return _field(
        length,
        width,
        "".join(parts),
        f"Player trajectories: {teams.get('l', 'left')} (blue, attacking right) and {teams.get('r', 'right')} (red)",
    )


def timeline(events: list[dict]) -> str:
    if not events:
        return "<p>No registry events were recorded.</p>"
    names = sorted({e["name"] for e in events})
    t_end = max(e["t"] for e in events) + 1.0
    row, left, width = 18, 190, 760
    parts = []
    for i, name in enumerate(names):
        y = i * row + 20
        parts.append(f'<text x="0" y="{y + 12}" font-size="12">{html.escape(name)}</text>')
        mine = [e for e in events if e["name"] == name]
        for k, e in enumerate(mine):
            start = e["t"]
            stop = mine[k + 1]["t"] if k + 1 < len(mine) else t_end
            state = "deregistered" if e["kind"] == "deregistered" else e["state"] or "healthy"
            x0 = left + width * start / t_end
            x1 = left + width * stop / t_end
            parts.append(
                f'<rect x="{x0:.1f}" y="{y}" width="{max(1.0, x1 - x0):.1f}" height="{row - 4}" '
                f'fill="{STATE_COLORS.get(state, "#777")}"><title>{html.escape(name)}: {state} '
                f"({html.escape(e['kind'])}: {html.escape(e['reason'])}) at {start:.1f} s</title></rect>"
            )
    legend = " ".join(f'<span style="color:{c}">&#9632; {s}</span>' for s, c in STATE_COLORS.items())
    height = len(names) * row + 40
    return (
        f'<figure><svg viewBox="0 0 {left + width + 10} {height}" width="{left + width + 10}" height="{height}" '
        f'xmlns="http://www.w3.org/2000/svg">{"".join(parts)}</svg><figcaption>Registry timeline: each '
        f"component's state over time (seconds). {legend}</figcaption></figure>"
    )


def scored(cycles: list[dict]) -> list[tuple[int, str]]:
    """(cycle, side) of every goal: the events ``goal l`` / ``goal r`` (``goal kick l`` is a restart)."""
    return [
        (c["t"], kind[1])
        for c in cycles
        for kind in map(str.split, c.get("events", []))
        if kind[:1] == ["goal"] and len(kind) == 2
    ]


def write_report(log_path: Path, events: list[dict] | None, out: Path) -> Path:
    header, cycles, end = read_log(log_path)
    teams = header.get("teams", {"l": "left", "r": "right"})
    score = end.get("score") or (cycles[-1]["score"] if cycles else [0, 0])
    stats = end.get("stats", {})
    goals = scored(cycles)

    def stat_row(label: str, key: str, percent: bool = False) -> str:
        values = stats.get(key, {})
        total = max(1, sum(values.values())) if percent else 1
        fmt = (lambda v: f"{v / total:.0%}") if percent else str
        return f"<tr><th>{label}</th><td>{fmt(values.get('l', 0))}</td><td>{fmt(values.get('r', 0))}</td></tr>"

    body = f"""<!doctype html><html lang="en"><head><meta charset="utf-8"><title>Match report</title>
<style>body{{font-family:sans-serif;margin:24px;color:#222}} table{{border-collapse:collapse}}
td,th{{padding:4px 12px;border-bottom:1px solid #ddd;text-align:right}} figure{{margin:24px 0}}
figcaption{{color:#555;font-size:14px}} .score{{font-size:32px;font-weight:bold}}</style></head><body>
<h1>Match report</h1>
<p class="score"><span style="color:{COLORS["l"]}">{html.escape(teams.get("l", "left"))}</span> {score[0]} : {score[1]}
<span style="color:{COLORS["r"]}">{html.escape(teams.get("r", "right"))}</span></p>
<p>{len(cycles)} cycles logged. Goals: {", ".join(f"{html.escape(teams.get(side, side))} at cycle {t}" for t, side in goals) or "none"}.</p>
<table><tr><th></th><th>{html.escape(teams.get("l", "left"))}</th><th>{html.escape(teams.get("r", "right"))}</th></tr>
{stat_row("kicks", "kicks")}{stat_row("shots", "shots")}{stat_row("possession", "possession", True)}</table>
<h2>Replay</h2>
{replay(header, cycles, events or [], field=_dimensions(header), colors=COLORS, state_colors=STATE_COLORS)}
<h2>Pictures</h2>
{heat_and_path(header, cycles)}
{trajectories(header, cycles)}
<h2>Components</h2>
{timeline(events or [])}
</body></html>"""
    out.write_text(body, encoding="utf-8")
    return out


if __name__ == "__main__":
    log = Path(sys.argv[1])
    events = json.loads(Path(sys.argv[2]).read_text()) if len(sys.argv) > 2 else []
    print(write_report(log, events, Path(sys.argv[3] if len(sys.argv) > 3 else "report.html")))
