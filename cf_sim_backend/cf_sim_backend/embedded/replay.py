"""The animated replay of a match in the report: a canvas, its controls and the page's own script (ROS-free).

Every logged cycle becomes a frame (ball, players with their numbers and the direction they face,
score, play mode); the ComMAg's registry events sit on the same timeline, so one sees a component
go suspect, be relaunched and come back while the match plays on. Play, pause, step, scrub and
speed; no network, no library. ``#selftest`` in the page's address makes it step and play by
itself and record what it drew (the tests read that back from headless Chromium).
"""

from __future__ import annotations

import json


def frames(cycles: list[dict]) -> tuple[list[str], list[list]]:
    """The play modes, and per cycle [t, mode index, score l, score r, ball x, ball y, players]."""
    modes: list[str] = []
    out = []
    for c in cycles:
        if c["mode"] not in modes:
            modes.append(c["mode"])
        players = [
            [0 if side == "l" else 1, number, round(x, 1), round(y, 1), round(body), 1 if goalie else 0]
            for side, number, x, y, _vx, _vy, body, _neck, _stamina, goalie, *_type in c["players"]
        ]
        b = c["ball"]
        out.append(
            [c["t"], modes.index(c["mode"]), c["score"][0], c["score"][1], round(b[0], 2), round(b[1], 2), players]
        )
    return modes, out


def timeline_events(events: list[dict], cycle_seconds: float) -> list[list]:
    """[cycle, name, kind, reason] of the registry events worth seeing (renewals are not)."""
    out = []
    for e in events:
        if e["kind"] == "renewed":
            continue
        cycle = e.get("cycle")
        if cycle is None:  # events from before the demo gave cycles: seconds on the match clock
            cycle = round(e["t"] / cycle_seconds)
        out.append([int(cycle), e["name"], e["kind"], e.get("reason", "")])
    return out


def replay(
    header: dict,
    cycles: list[dict],
    events: list[dict],
    *,
    field: tuple[float, float],
    colors: dict,
    state_colors: dict,
) -> str:
    """The replay's HTML: canvas, controls, data and script. ``field`` is (length, width) in metres."""
    if not cycles:
        return "<p>No cycles logged: nothing to replay.</p>"
    length, width = field
    modes, data = frames(cycles)
    teams = header.get("teams", {"l": "left", "r": "right"})
    payload = {
        "length": length,
        "width": width,
        "goal": header.get("field", {}).get("goal_width", 14.02),
        "cycleSeconds": header.get("cycle_seconds", 0.1),
        "teams": [teams.get("l", "left"), teams.get("r", "right")],
        "colors": [colors["l"], colors["r"]],
        "stateColors": state_colors,
        "modes": modes,
        "frames": data,
        "events": timeline_events(events, header.get("cycle_seconds", 0.1)),
    }
    # </script> must not end the data block early.
    blob = json.dumps(payload, separators=(",", ":")).replace("</", "<\\/")
    return (
        _HTML.replace("__LAST__", str(len(data) - 1))
        + f'<script type="application/json" id="replay-data">{blob}</script>'
        f"<script>{_SCRIPT}</script>"
    )


_HTML = """<div id="replay-box">
<canvas id="replay" width="920" height="600" aria-label="match replay"></canvas>
<div class="controls">
<button id="replay-back" title="one cycle back">&#9664;&#9664;</button>
<button id="replay-play" title="play or pause">play</button>
<button id="replay-step" title="one cycle on">&#9654;&#9654;</button>
<input id="replay-scrub" type="range" min="0" max="__LAST__" value="0" style="width:520px">
<select id="replay-speed" title="speed"><option value="0.5">0.5x</option><option value="1" selected>1x</option>
<option value="2">2x</option><option value="4">4x</option><option value="8">8x</option></select>
<span id="replay-clock"></span></div>
<div id="replay-marks" style="position:relative;height:14px;width:920px;background:#eee"></div>
<div id="replay-events" style="font-size:13px;color:#333;min-height:8em;font-family:monospace"></div>
</div>"""

_SCRIPT = r"""
(function () {
  var errors = [];
  window.addEventListener("error", function (e) {
    errors.push(String(e.message));
    document.body.dataset.replayErrors = errors.join("; ");
  });
  var D = JSON.parse(document.getElementById("replay-data").textContent);
  var canvas = document.getElementById("replay"), ctx = canvas.getContext("2d");
  var scrub = document.getElementById("replay-scrub"), clock = document.getElementById("replay-clock");
  var playButton = document.getElementById("replay-play"), list = document.getElementById("replay-events");
  var S = canvas.width / (D.length + 10), last = D.frames.length - 1;
  var frame = 0, timer = null, carry = 0;
  function px(x, y) { return [(x + D.length / 2 + 5) * S, (D.width / 2 + 5 - y) * S]; }
  function field() {
    ctx.fillStyle = "#2f7d3a"; ctx.fillRect(0, 0, canvas.width, canvas.height);
    ctx.strokeStyle = "white"; ctx.lineWidth = 2;
    var a = px(-D.length / 2, D.width / 2), b = px(D.length / 2, -D.width / 2), c = px(0, 0);
    ctx.strokeRect(a[0], a[1], b[0] - a[0], b[1] - a[1]);
    ctx.beginPath(); ctx.moveTo(c[0], a[1]); ctx.lineTo(c[0], b[1]); ctx.stroke();
    ctx.beginPath(); ctx.arc(c[0], c[1], 9.15 * S, 0, 2 * Math.PI); ctx.stroke();
    ctx.fillStyle = "rgba(255,255,255,0.8)";
    [-1, 1].forEach(function (side) {
      var g = px(side > 0 ? D.length / 2 : -D.length / 2 - 2, D.goal / 2);
      ctx.fillRect(g[0], g[1], 2 * S, D.goal * S);
    });
  }
  function eventsAt(f) {  // the events up to this frame's cycle, newest last
    var t = D.frames[f][0];
    return D.events.filter(function (e) { return e[0] <= t; });
  }
  function draw() {
    var f = D.frames[frame];
    field();
    f[6].forEach(function (p) {
      var q = px(p[2], p[3]), r = 0.9 * S, a = p[4] * Math.PI / 180;
      ctx.fillStyle = D.colors[p[0]];
      ctx.beginPath(); ctx.arc(q[0], q[1], r, 0, 2 * Math.PI); ctx.fill();
      if (p[5]) { ctx.strokeStyle = "#ffe14d"; ctx.lineWidth = 2; ctx.stroke(); }
      ctx.strokeStyle = "white"; ctx.lineWidth = 2;
      ctx.beginPath(); ctx.moveTo(q[0], q[1]); ctx.lineTo(q[0] + 1.8 * r * Math.cos(a), q[1] - 1.8 * r * Math.sin(a)); ctx.stroke();
      ctx.fillStyle = "white"; ctx.font = "bold 11px sans-serif"; ctx.textAlign = "center"; ctx.textBaseline = "middle";
      ctx.fillText(String(p[1]), q[0], q[1]);
    });
    var b = px(f[4], f[5]);
    ctx.fillStyle = "white"; ctx.strokeStyle = "black"; ctx.lineWidth = 1;
    ctx.beginPath(); ctx.arc(b[0], b[1], 0.6 * S, 0, 2 * Math.PI); ctx.fill(); ctx.stroke();
    ctx.fillStyle = "rgba(0,0,0,0.55)"; ctx.fillRect(0, 0, canvas.width, 26);
    ctx.fillStyle = "white"; ctx.font = "bold 15px sans-serif"; ctx.textAlign = "left"; ctx.textBaseline = "middle";
    ctx.fillText(D.teams[0] + " " + f[2] + " : " + f[3] + " " + D.teams[1] + "    cycle " + f[0] + "    " + D.modes[f[1]], 10, 13);
    var seen = eventsAt(frame);
    list.innerHTML = "";
    seen.slice(-8).forEach(function (e) {
      var div = document.createElement("div");
      var state = e[2] === "relaunched" || e[2] === "registered" ? "healthy" : e[2];
      div.style.color = D.stateColors[state] || "#333";
      div.textContent = "cycle " + e[0] + "  " + e[1] + "  " + e[2] + (e[3] ? "  (" + e[3] + ")" : "");
      list.appendChild(div);
    });
    scrub.value = frame;
    clock.textContent = " frame " + frame + " / " + last;
  }
  function go(f) { frame = Math.max(0, Math.min(last, f)); draw(); }
  function pause() { if (timer) { clearInterval(timer); timer = null; } playButton.textContent = "play"; }
  function play() {
    if (timer) return;
    if (frame >= last) go(0);
    playButton.textContent = "pause"; carry = 0;
    var period = 40;
    timer = setInterval(function () {  // frames per tick follow the chosen speed
      carry += period / 1000 / D.cycleSeconds * Number(document.getElementById("replay-speed").value);
      var n = Math.floor(carry);
      if (n > 0) { carry -= n; go(frame + n); }
      if (frame >= last) pause();
    }, period);
  }
  playButton.onclick = function () { if (timer) pause(); else play(); };
  document.getElementById("replay-step").onclick = function () { pause(); go(frame + 1); };
  document.getElementById("replay-back").onclick = function () { pause(); go(frame - 1); };
  scrub.oninput = function () { pause(); go(Number(scrub.value)); };
  var marks = document.getElementById("replay-marks"), t0 = D.frames[0][0], t1 = Math.max(t0 + 1, D.frames[last][0]);
  D.events.forEach(function (e) {  // the registry events on the match's timeline
    if (e[2] === "registered" && e[0] <= t0) return;
    var m = document.createElement("span"), state = e[2] === "relaunched" ? "healthy" : e[2];
    m.title = "cycle " + e[0] + ": " + e[1] + " " + e[2];
    m.style.cssText = "position:absolute;top:0;height:14px;width:3px;left:" +
      (100 * (e[0] - t0) / (t1 - t0)) + "%;background:" + (D.stateColors[state] || "#555");
    marks.appendChild(m);
  });
  function checksum() {
    var px = ctx.getImageData(0, 0, canvas.width, canvas.height).data, sum = 0;
    for (var i = 0; i < px.length; i += 97) sum = (sum * 31 + px[i]) % 1000000007;
    return sum;
  }
  window.cfReplay = { go: go, play: play, pause: pause, checksum: checksum, frame: function () { return frame; } };
  draw();
  if (location.hash === "#selftest") {
    var report = { first: checksum() };
    document.getElementById("replay-step").click();
    for (var k = 0; k < 40; k++) document.getElementById("replay-step").click();
    report.stepped = checksum(); report.afterSteps = frame;
    document.getElementById("replay-speed").value = "8";
    play();
    setTimeout(function () {
      pause();
      report.played = checksum(); report.afterPlay = frame; report.events = list.children.length;
      document.body.dataset.replaySelftest = JSON.stringify(report);
    }, 1500);
  }
})();
"""
