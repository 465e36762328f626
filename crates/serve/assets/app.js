// propbet workbench: the page's state is one JSON document ({"effects": [...]}, a case file's
// keys); every change posts it to /api/evaluate and redraws from compare's summary.json.
"use strict";

const token = new URLSearchParams(location.search).get("token") || "";
const $ = (id) => document.getElementById(id);
const COLORS = ["#1f6fb2", "#d1495b", "#2e933c", "#8f5bb5", "#e08e0b", "#00798c", "#6b4226", "#444"];

let offers = [];          // the effects the page offers, with their parameters
let startState = { effects: [] };
let pinned = null;        // the pinned evaluation
let last = null;          // the last evaluation
let plots = {};
let busy = false, again = false;

async function api(path, body) {
  const r = await fetch(path, {
    method: body === undefined ? "GET" : "POST",
    headers: { "X-Propbet-Token": token, "Content-Type": "application/json" },
    body: body === undefined ? undefined : JSON.stringify(body),
  });
  const data = await r.json().catch(() => ({ error: `answer ${r.status} is not JSON` }));
  if (!r.ok) throw new Error(data.error || `answer ${r.status}`);
  return data;
}

function say(text, error) {
  const m = $("message");
  m.textContent = text || "";
  m.className = error ? "error" : "";
}

// ---- the effects panel ---------------------------------------------------------------

function fmt(v) {
  if (v === 0) return "0";
  const a = Math.abs(v);
  if (a >= 1e-3 && a < 1e5) return String(Number(v.toPrecision(4)));
  return v.toExponential(3);
}

function specOf(offer) {
  const box = document.querySelector(`.effect[data-id="${offer.id}"]`);
  const vals = offer.params.map((p) => `${p.name}=${fmt(Number(box.querySelector(`input[data-param="${p.name}"]`).value))}`);
  return vals.length ? `${offer.id}:${vals.join(",")}` : offer.id;
}

function currentState() {
  const effects = [];
  for (const o of offers) {
    const box = document.querySelector(`.effect[data-id="${o.id}"]`);
    if (box.querySelector("input[type=checkbox]").checked) effects.push(specOf(o));
  }
  return { effects };
}

function parseSpec(spec) {
  const [id, rest] = spec.split(/:(.*)/s);
  const values = {};
  if (rest) for (const kv of rest.split(",")) { const [k, v] = kv.split("="); values[k.trim()] = Number(v); }
  return { id: id.trim(), values };
}

function setState(state) {
  const on = new Map(state.effects.map((s) => { const p = parseSpec(s); return [p.id, p.values]; }));
  for (const o of offers) {
    const box = document.querySelector(`.effect[data-id="${o.id}"]`);
    const values = on.get(o.id);
    box.querySelector("input[type=checkbox]").checked = !!values;
    box.classList.toggle("off", !values);
    for (const p of o.params) {
      const v = values && values[p.name] !== undefined ? values[p.name] : (p.neutral ?? p.start);
      const input = box.querySelector(`input[data-param="${p.name}"]`);
      input.value = v;
      box.querySelector(`output[data-param="${p.name}"]`).textContent = fmt(Number(input.value));
    }
  }
}

function buildPanel() {
  const root = $("effects");
  root.innerHTML = "";
  for (const o of offers) {
    const box = document.createElement("div");
    box.className = "effect off";
    box.dataset.id = o.id;
    const label = document.createElement("label");
    const check = document.createElement("input");
    check.type = "checkbox";
    check.addEventListener("change", () => { box.classList.toggle("off", !check.checked); changed(); });
    const fit = document.createElement("button");
    fit.className = "fit";
    fit.textContent = "Fit";
    fit.title = "Fit this effect's parameters as the diagnosis does, on top of the others switched on";
    fit.addEventListener("click", (e) => { e.preventDefault(); fitEffect(o.id); });
    label.append(check, document.createTextNode(o.id), fit);
    box.append(label);
    const why = document.createElement("p");
    why.className = "why";
    why.textContent = o.explanation.split(". ")[0];
    why.title = o.explanation;
    box.append(why);
    for (const p of o.params) {
      const row = document.createElement("div");
      row.className = "param";
      const name = document.createElement("span");
      name.textContent = `${p.name} [${p.unit}]`;
      name.title = p.doc;
      const input = document.createElement("input");
      input.type = "range";
      input.min = p.lower; input.max = p.upper;
      input.step = (p.upper - p.lower) / 1000;
      input.dataset.param = p.name;
      input.setAttribute("aria-label", `${o.id} ${p.name}`);
      // The physically expected range, marked on the track.
      const [lo, hi] = p.expected || [p.lower, p.upper];
      const a = (100 * (lo - p.lower)) / (p.upper - p.lower), b = (100 * (hi - p.lower)) / (p.upper - p.lower);
      input.style.background = `linear-gradient(to right, #eee ${a}%, #cfe3f5 ${a}%, #cfe3f5 ${b}%, #eee ${b}%)`;
      input.title = `bounds ${fmt(p.lower)} to ${fmt(p.upper)}; physically expected ${fmt(lo)} to ${fmt(hi)} (shaded)`;
      const out = document.createElement("output");
      out.dataset.param = p.name;
      input.addEventListener("input", () => {
        out.textContent = fmt(Number(input.value));
        if (!check.checked) { check.checked = true; box.classList.remove("off"); }
        changed();
      });
      row.append(name, input, out);
      box.append(row);
    }
    root.append(box);
  }
}

// ---- evaluating and drawing ------------------------------------------------------------

async function changed() {
  if (busy) { again = true; return; }
  busy = true;
  try {
    do {
      again = false;
      const state = currentState();
      const t0 = performance.now();
      last = await api("/api/evaluate", state);
      draw(last);
      say(`${state.effects.length ? state.effects.join(" + ") : "baseline"} · ${Math.round(performance.now() - t0)} ms`);
    } while (again);
  } catch (e) {
    say(e.message, true);
  } finally {
    busy = false;
  }
}

function pct(x) { return x === null || x === undefined || !isFinite(x) ? "–" : `${(100 * x).toFixed(1)} %`; }
function signed(x) { return x === null || x === undefined || !isFinite(x) ? "–" : `${x >= 0 ? "+" : ""}${(100 * x).toFixed(1)} %`; }

function numbers(s) {
  const items = [
    ["CT median |error|", s.accuracy.ct_median_error, pinned && pinned.accuracy.ct_median_error, pct, true],
    ["CP median |error|", s.accuracy.cp_median_error, pinned && pinned.accuracy.cp_median_error, pct, true],
  ];
  for (const g of s.headline) {
    const pg = pinned && pinned.headline.find((x) => x.points === g.points);
    for (const q of ["thrust", "torque"]) {
      if (!g.errors[q]) continue;
      const where = g.points.startsWith("forward") ? "forward" : g.points;
      items.push([`${where} ${q}, mean error`, g.errors[q].mean_error, pg && pg.errors[q] && pg.errors[q].mean_error, signed, false]);
    }
  }
  $("numbers").innerHTML = "";
  for (const [label, v, p, f, abs] of items) {
    const d = document.createElement("div");
    d.className = "num";
    const b = document.createElement("b");
    b.textContent = f(v);
    b.dataset.name = label;
    if (p !== null && p !== undefined && isFinite(v) && isFinite(p)) {
      const better = Math.abs(v) < Math.abs(p) - 1e-4, worse = Math.abs(v) > Math.abs(p) + 1e-4;
      b.className = better ? "better" : worse ? "worse" : "";
    }
    const small = document.createElement("small");
    small.textContent = label + (abs ? ` (${s.accuracy.points} points)` : "");
    d.append(b, small);
    if (p !== null && p !== undefined) {
      const pin = document.createElement("span");
      pin.className = "pinned";
      pin.textContent = `pinned ${f(p)}`;
      d.append(pin);
    }
    $("numbers").append(d);
  }
}

// One figure's uPlot data: the model's curves (each with its band), the measured points, the
// pinned curves, joined on one x axis.
function figure(id, s, pick) {
  const tables = [], series = [{ label: pick.xlabel }], bands = [];
  const groups = pick.groups(s);
  groups.forEach((g, k) => {
    const color = COLORS[k % COLORS.length];
    if (pick.model && g.rows.length) {
      const r = g.rows.filter((row) => row[pick.y] !== null);
      tables.push([r.map((x) => x.x), r.map((x) => x[pick.y]), r.map((x) => x[pick.y + "_lo"]), r.map((x) => x[pick.y + "_hi"])]);
      const base = series.length;
      series.push({ label: `${g.label} model`, stroke: color, width: 2, spanGaps: true, points: { show: false } });
      series.push({ label: "band", stroke: "transparent", spanGaps: true, points: { show: false } });
      series.push({ label: "band", stroke: "transparent", spanGaps: true, points: { show: false } });
      bands.push({ series: [base + 2, base + 1], fill: color + "22" });
    }
    const m = g.points.filter((p) => p.y !== null && p.y !== undefined && isFinite(p.y));
    if (m.length) {
      const sorted = m.slice().sort((a, b) => a.x - b.x);
      tables.push([sorted.map((p) => p.x), sorted.map((p) => p.y)]);
      series.push({ label: `${g.label} measured`, stroke: color, paths: () => null, points: { show: true, size: 6, fill: color } });
    }
  });
  if (pinned && pick.model) {
    pick.groups(pinned).forEach((g) => {
      const r = g.rows.filter((row) => row[pick.y] !== null);
      if (!r.length) return;
      tables.push([r.map((x) => x.x), r.map((x) => x[pick.y])]);
      series.push({ label: `${g.label} pinned`, stroke: "#888", dash: [6, 4], width: 1.5, spanGaps: true, points: { show: false } });
    });
  }
  if (!tables.length) return;
  const data = uPlot.join(tables);
  // An error figure's axis holds the bulk of the points: a few near zero thrust, where a
  // relative error grows without bound, are counted in the caption instead of squeezing it.
  let yRange;
  const note = $(`note-${id.slice(-1)}`);
  if (note) note.textContent = "";
  if (!pick.model) {
    const ys = groups.flatMap((g) => g.points.map((p) => p.y)).filter((y) => isFinite(y)).sort((a, b) => a - b);
    if (ys.length) {
      const q = (f) => ys[Math.min(ys.length - 1, Math.floor(f * ys.length))];
      const lo = Math.min(-5, q(0.05) - 0.5 * Math.abs(q(0.05))), hi = Math.max(5, q(0.95) + 0.5 * Math.abs(q(0.95)));
      const out = ys.filter((y) => y < lo || y > hi).length;
      yRange = [lo, hi];
      if (note && out) note.textContent = `${out} point${out > 1 ? "s" : ""} beyond the axis`;
    }
  }
  const el = $(id);
  const rect = el.parentElement.getBoundingClientRect();
  const opts = {
    width: Math.max(300, Math.floor(rect.width)),
    height: Math.max(160, Math.floor(rect.height - 24)),
    series, bands,
    legend: { show: false },
    cursor: { drag: { x: false, y: false } },
    scales: { x: { time: false }, y: yRange ? { range: () => yRange } : {} },
    axes: [{ label: pick.xlabel, size: 36, labelSize: 18 }, { label: pick.ylabel, size: 60, labelSize: 18 }],
  };
  if (plots[id]) plots[id].destroy();
  el.innerHTML = "";
  plots[id] = new uPlot(opts, data, el);
}

function groupsByRpm(s, y, model) {
  // The model's figures show every measured point; the error figures those validate scores.
  const sweeps = s.curves.j_sweeps;
  return sweeps.map((sw) => {
    const near = (p) => !p.static && Math.abs(p.rpm - sw.rpm) < 0.08 * sw.rpm;
    return {
      label: `${Math.round(sw.rpm / 100) * 100} rpm`,
      rows: model ? sw.rows : [],
      points: s.points_measured.filter((p) => near(p) && (model || p.scored)).map((p) => ({ x: p.j, y: y(p) })),
    };
  });
}

function staticGroups(s, y, model) {
  const st = s.curves.statics;
  return [{ label: "static", rows: st ? st.rows : [], points: s.points_measured.filter((p) => p.static && (model || p.scored)).map((p) => ({ x: p.rpm, y: y(p) })) }];
}

// The colours of the RPM groups, in the first figure's caption.
function legend(labels) {
  const el = $("legend");
  el.innerHTML = "";
  labels.forEach((l, k) => {
    const span = document.createElement("span");
    span.style.color = COLORS[k % COLORS.length];
    span.textContent = `● ${l}`;
    el.append(span);
  });
}

function draw(s) {
  numbers(s);
  const sweeps = s.curves.j_sweeps.length > 0;
  const err = (k) => (p) => (p[k] === null ? null : 100 * p[k]);
  legend(sweeps ? groupsByRpm(s, () => null, false).map((g) => g.label) : ["static"]);
  if (sweeps) {
    $("cap-a").firstChild.textContent = "CT against J";
    $("cap-b").firstChild.textContent = "CP against J";
    $("cap-c").firstChild.textContent = "CT error [%] against J";
    $("cap-d").firstChild.textContent = "CP error [%] against J";
    figure("fig-a", s, { xlabel: "J", ylabel: "CT", y: "ct", model: true, groups: (d) => groupsByRpm(d, (p) => p.ct, true) });
    figure("fig-b", s, { xlabel: "J", ylabel: "CP", y: "cp", model: true, groups: (d) => groupsByRpm(d, (p) => p.cp, true) });
    figure("fig-c", s, { xlabel: "J", ylabel: "CT error [%]", y: "ct", model: false, groups: (d) => groupsByRpm(d, err("ct_error"), false) });
    figure("fig-d", s, { xlabel: "J", ylabel: "CP error [%]", y: "cp", model: false, groups: (d) => groupsByRpm(d, err("cp_error"), false) });
  } else {
    $("cap-a").firstChild.textContent = "Thrust [N] against RPM";
    $("cap-b").firstChild.textContent = "Torque [N m] against RPM";
    $("cap-c").firstChild.textContent = "CT error [%] against RPM";
    $("cap-d").firstChild.textContent = "CP error [%] against RPM";
    figure("fig-a", s, { xlabel: "RPM", ylabel: "thrust [N]", y: "thrust", model: true, groups: (d) => staticGroups(d, (p) => p.thrust, true) });
    figure("fig-b", s, { xlabel: "RPM", ylabel: "torque [N m]", y: "torque", model: true, groups: (d) => staticGroups(d, (p) => p.torque, true) });
    figure("fig-c", s, { xlabel: "RPM", ylabel: "CT error [%]", y: "ct", model: false, groups: (d) => staticGroups(d, err("ct_error"), false) });
    figure("fig-d", s, { xlabel: "RPM", ylabel: "CP error [%]", y: "cp", model: false, groups: (d) => staticGroups(d, err("cp_error"), false) });
  }
}

// ---- fit, diagnose, pin, save -----------------------------------------------------------

async function fitEffect(id) {
  say(`fitting ${id} …`);
  try {
    const r = await api("/api/fit", { state: currentState(), effect: id });
    setState(r.state);
    await changed();
    say(`fitted: ${r.effect}`);
  } catch (e) { say(e.message, true); }
}

function stackOf(rung) {
  return rung.stack === "baseline" ? [] : rung.stack.split(" + ");
}

async function diagnose() {
  const button = $("diagnose");
  button.disabled = true;
  const t0 = performance.now();
  const tick = setInterval(() => say(`running the ladder … ${Math.round((performance.now() - t0) / 1000)} s`), 500);
  try {
    const base = currentState();
    const d = await api("/api/diagnose", base);
    clearInterval(tick);
    showLadder(d, base);
    say(`the ladder took ${((performance.now() - t0) / 1000).toFixed(1)} s: step through it below`);
  } catch (e) { clearInterval(tick); say(e.message, true); }
  finally { button.disabled = false; }
}

function showLadder(d, base) {
  const root = $("ladder");
  root.innerHTML = "<h2>The ladder</h2>";
  const ol = document.createElement("ol");
  ol.start = 0;
  d.ladder.forEach((rung, k) => {
    const li = document.createElement("li");
    li.textContent = `${rung.added || "baseline"} · RMS ${(100 * rung.rms).toFixed(2)} %, held out ${(100 * rung.kfold_rms).toFixed(2)} %`;
    li.title = rung.stack;
    li.addEventListener("click", async () => {
      ol.querySelectorAll("li").forEach((x) => x.classList.remove("at"));
      li.classList.add("at");
      setState({ effects: base.effects.concat(stackOf(rung)) });
      await changed();
    });
    ol.append(li);
  });
  root.append(ol);
  const v = document.createElement("div");
  v.className = "verdict";
  const answers = d.verdict.answers.map((a) => {
    if (a.kind === "found") return `${a.effect}: found physics`;
    if (a.kind === "calibration") return `${a.effect}: a calibration factor (outside its physically expected range)`;
    if (a.kind === "group") return `${a.effect}: one of ${a.group.join(", ")} (these data cannot tell them apart${a.tell_apart ? "; " + a.tell_apart + " would" : ""})`;
    return `${a.effect}: below what these data detect`;
  });
  v.textContent = "Verdict: " + (answers.length ? answers.join("; ") : "no effect needed") + ". " + (d.verdict.within_model_error || "");
  root.append(v);
}

function pin() {
  if (!last) return;
  pinned = last;
  draw(last);
  say("pinned: the next states are drawn and numbered against this one");
}

async function save() {
  const name = $("save-name").value.trim();
  try {
    const r = await api("/api/save", { state: currentState(), name });
    say(`saved: ${r.folder} (propbet run ${r.folder} gives these numbers)`);
  } catch (e) { say(e.message, true); }
}

function downloads() {
  for (const id of ["a", "b", "c", "d"]) {
    const a = document.createElement("a");
    a.href = "#";
    a.textContent = "PNG";
    a.addEventListener("click", (e) => {
      e.preventDefault();
      const canvas = $(`fig-${id}`).querySelector("canvas");
      if (!canvas) return;
      const link = document.createElement("a");
      link.download = `${$(`cap-${id}`).firstChild.textContent.replace(/[^A-Za-z0-9]+/g, "_")}.png`;
      link.href = canvas.toDataURL("image/png");
      link.click();
    });
    const note = document.createElement("small");
    note.id = `note-${id}`;
    note.className = "note";
    $(`cap-${id}`).append(a, note);
  }
}

async function main() {
  try {
    const s = await api("/api/session");
    $("case").textContent = s.name;
    document.title = `propbet workbench · ${s.name}`;
    offers = s.effects;
    startState = s.start;
    buildPanel();
    setState(startState);
    downloads();
    $("diagnose").addEventListener("click", diagnose);
    $("pin").addEventListener("click", pin);
    $("reset").addEventListener("click", () => { setState(startState); changed(); });
    $("save").addEventListener("click", save);
    let resize;
    window.addEventListener("resize", () => { clearTimeout(resize); resize = setTimeout(() => last && draw(last), 150); });
    await changed();
  } catch (e) { say(e.message, true); }
}

main();
