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
let ladder = null;        // the last diagnosis' ladder (its held-out errors join the numbers)
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
function signed(x) {
  if (x === null || x === undefined || !isFinite(x)) return "–";
  const t = (100 * x).toFixed(1);
  return t === "0.0" || t === "-0.0" ? "0.0 %" : `${x > 0 ? "+" : ""}${t} %`;
}

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
  if (ladder && ladder.length) {
    // The diagnosis' held-out error: before any effect, and after its last rung.
    items.push(["held out, before the ladder", ladder[0].kfold_rms, null, pct, false]);
    items.push(["held out, after it", ladder[ladder.length - 1].kfold_rms, null, pct, false]);
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
    small.textContent = label;
    if (abs) d.title = `over ${s.accuracy.points} points: ${s.accuracy.measure}`;
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
  const tables = [], series = [{ label: pick.xlabel }], bands = [], kinds = ["x"];
  const groups = pick.groups(s);
  groups.forEach((g, k) => {
    const color = COLORS[k % COLORS.length];
    if (pick.model && g.rows.length) {
      const r = g.rows.filter((row) => row[pick.y] !== null);
      tables.push([r.map((x) => x.x), r.map((x) => x[pick.y])]);
      series.push({ label: `${g.label} model`, stroke: color, width: 2, spanGaps: true, points: { show: false } });
      kinds.push("line");
      // The band on its own (coarser) grid, where the figure is of a coefficient.
      const b = (g.band || []).filter((row) => row[pick.y + "_lo"] !== undefined);
      if (b.length) {
        tables.push([b.map((x) => x.x), b.map((x) => x[pick.y + "_lo"]), b.map((x) => x[pick.y + "_hi"])]);
        const lo = series.length;
        series.push({ label: "band", stroke: "transparent", spanGaps: true, points: { show: false } });
        series.push({ label: "band", stroke: "transparent", spanGaps: true, points: { show: false } });
        kinds.push("band", "band");
        bands.push({ series: [lo + 1, lo], fill: color + "22" });
      }
    }
    const m = g.points.filter((p) => p.y !== null && p.y !== undefined && isFinite(p.y));
    if (m.length) {
      const sorted = m.slice().sort((a, b) => a.x - b.x);
      tables.push([sorted.map((p) => p.x), sorted.map((p) => p.y)]);
      series.push({ label: `${g.label} measured`, stroke: color, paths: () => null, points: { show: true, size: 6, fill: color } });
      kinds.push("points");
    }
  });
  if (pinned && pick.model) {
    pick.groups(pinned).forEach((g) => {
      const r = g.rows.filter((row) => row[pick.y] !== null);
      if (!r.length) return;
      tables.push([r.map((x) => x.x), r.map((x) => x[pick.y])]);
      series.push({ label: `${g.label} pinned`, stroke: "#888", dash: [6, 4], width: 1.5, spanGaps: true, points: { show: false } });
      kinds.push("pinned");
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
  // What the SVG export draws, kept as given (uPlot turns colours into functions).
  const drawn = { bands: bands.map((b) => ({ series: b.series.slice(), fill: b.fill })), kinds, colors: series.map((x) => x.stroke) };
  plots[id] = new uPlot(opts, data, el);
  plots[id].propbet = drawn;
}

function groupsByRpm(s, y, model) {
  // The model's figures show every measured point; the error figures those validate scores.
  const sweeps = s.curves.j_sweeps;
  return sweeps.map((sw) => {
    const near = (p) => !p.static && Math.abs(p.rpm - sw.rpm) < 0.08 * sw.rpm;
    return {
      label: `${Math.round(sw.rpm / 100) * 100} rpm`,
      rows: model ? sw.rows : [],
      band: model ? sw.band : [],
      points: s.points_measured.filter((p) => near(p) && (model || p.scored)).map((p) => ({ x: p.j, y: y(p) })),
    };
  });
}

function staticGroups(s, y, model) {
  const st = s.curves.statics;
  return [{ label: "static", rows: st ? st.rows : [], band: [], points: s.points_measured.filter((p) => p.static && (model || p.scored)).map((p) => ({ x: p.rpm, y: y(p) })) }];
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
  // Per figure: caption, y label, the quantity, and whether it draws the model.
  const x = sweeps ? "J" : "RPM";
  const groups = sweeps ? groupsByRpm : staticGroups;
  const specs = sweeps
    ? [["CT", "ct", (p) => p.ct, true], ["CP", "cp", (p) => p.cp, true]]
    : [["Thrust [N]", "thrust", (p) => p.thrust, true], ["Torque [N m]", "torque", (p) => p.torque, true]];
  specs.push(["CT error [%]", "ct", err("ct_error"), false], ["CP error [%]", "cp", err("cp_error"), false]);
  specs.forEach(([label, y, value, model], k) => {
    const id = "abcd"[k];
    $(`cap-${id}`).firstChild.textContent = `${label} against ${x}`;
    figure(`fig-${id}`, s, { xlabel: x, ylabel: label, y, model, groups: (d) => groups(d, value, model) });
  });
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
  ladder = d.ladder;
  if (last) numbers(last);
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

async function exportSim() {
  const name = `${$("save-name").value.trim()}_export`;
  try {
    const r = await api("/api/export", { state: currentState(), name });
    say(`exported to ${r.folder}: ${r.files.map((f) => f.split(":")[0]).join(", ")}`);
  } catch (e) { say(e.message, true); }
}

// A figure as SVG: its series, band and points drawn from the uPlot instance's own scales,
// with round ticks on each axis.
function svgOf(u, title) {
  const W = u.width, H = u.height, L = 70, T = 24, R = 16, B = 46;
  const w = W - L - R, h = H - T - B;
  const sx = u.scales.x, sy = u.scales.y;
  const X = (v) => L + (w * (v - sx.min)) / (sx.max - sx.min);
  const Y = (v) => T + h - (h * (v - sy.min)) / (sy.max - sy.min);
  const inside = (v) => v !== null && v !== undefined && isFinite(v) && v >= sy.min && v <= sy.max;
  const esc = (t) => String(t).replace(/&/g, "&amp;").replace(/</g, "&lt;");
  const parts = [`<svg xmlns="http://www.w3.org/2000/svg" width="${W}" height="${H}" font-family="sans-serif" font-size="12">`,
    `<rect width="${W}" height="${H}" fill="white"/>`, `<text x="${L}" y="16" font-weight="bold">${esc(title)}</text>`];
  // Ticks at 1, 2 or 5 times a power of ten, four to ten of them.
  const ticks = (min, max) => {
    const raw = (max - min) / 5, p = Math.pow(10, Math.floor(Math.log10(raw)));
    const step = [1, 2, 5, 10].map((m) => m * p).find((st) => (max - min) / st <= 6) || 10 * p;
    const out = [];
    for (let v = Math.ceil(min / step) * step; v <= max + 1e-9 * step; v += step) out.push(Math.abs(v) < 1e-12 * step ? 0 : v);
    return out;
  };
  for (const v of ticks(sx.min, sx.max)) parts.push(`<line x1="${X(v)}" x2="${X(v)}" y1="${T}" y2="${T + h}" stroke="#e5e5e5"/><text x="${X(v)}" y="${T + h + 16}" text-anchor="middle">${Number(v.toPrecision(3))}</text>`);
  for (const v of ticks(sy.min, sy.max)) parts.push(`<line x1="${L}" x2="${L + w}" y1="${Y(v)}" y2="${Y(v)}" stroke="#e5e5e5"/><text x="${L - 6}" y="${Y(v) + 4}" text-anchor="end">${Number(v.toPrecision(3))}</text>`);
  parts.push(`<text x="${L + w / 2}" y="${H - 8}" text-anchor="middle">${esc(u.axes[0].label)}</text>`);
  parts.push(`<text transform="translate(14 ${T + h / 2}) rotate(-90)" text-anchor="middle">${esc(u.axes[1].label)}</text>`);
  const xs = u.data[0];
  const own = u.propbet;
  for (const b of own.bands) {
    const [hi, lo] = b.series;
    const up = [], down = [];
    xs.forEach((x, i) => { if (inside(u.data[hi][i]) && inside(u.data[lo][i])) { up.push(`${X(x)},${Y(u.data[hi][i])}`); down.unshift(`${X(x)},${Y(u.data[lo][i])}`); } });
    if (up.length) parts.push(`<polygon points="${up.concat(down).join(" ")}" fill="${b.fill.slice(0, 7)}" fill-opacity="0.13"/>`);
  }
  u.series.forEach((s, k) => {
    const kind = own.kinds[k];
    if (kind === "x" || kind === "band" || !u.data[k]) return;
    const color = own.colors[k];
    const pts = xs.map((x, i) => [x, u.data[k][i]]).filter(([, y]) => inside(y));
    if (kind === "points") {
      for (const [x, y] of pts) parts.push(`<circle cx="${X(x)}" cy="${Y(y)}" r="3" fill="${color}"/>`);
    } else if (pts.length) {
      const dash = kind === "pinned" ? ` stroke-dasharray="6 4"` : "";
      parts.push(`<polyline points="${pts.map(([x, y]) => `${X(x)},${Y(y)}`).join(" ")}" fill="none" stroke="${color}" stroke-width="${kind === "pinned" ? 1.5 : 2}"${dash}/>`);
    }
  });
  // The legend: each group's colour, beside the title.
  let lx = L + 12 + 8 * title.length;
  u.series.forEach((s, k) => {
    if (own.kinds[k] !== "points" && own.kinds[k] !== "line") return;
    const label = String(s.label).replace(/ (model|measured)$/, "");
    if (parts.some((p) => p.includes(`data-legend="${label}"`))) return;
    parts.push(`<text data-legend="${esc(label)}" x="${lx}" y="16" fill="${own.colors[k]}">● ${esc(label)}</text>`);
    lx += 14 + 7 * label.length;
  });
  parts.push(`<rect x="${L}" y="${T}" width="${w}" height="${h}" fill="none" stroke="#999"/></svg>`);
  return parts.join("\n");
}

function downloads() {
  for (const id of ["a", "b", "c", "d"]) {
    const name = () => $(`cap-${id}`).firstChild.textContent.trim().replace(/[^A-Za-z0-9]+/g, "_");
    const save = (href, ext) => {
      const link = document.createElement("a");
      link.download = `${name()}.${ext}`;
      link.href = href;
      link.click();
    };
    const png = document.createElement("a");
    png.href = "#";
    png.textContent = "PNG";
    png.addEventListener("click", (e) => {
      e.preventDefault();
      const canvas = $(`fig-${id}`).querySelector("canvas");
      if (canvas) save(canvas.toDataURL("image/png"), "png");
    });
    const svg = document.createElement("a");
    svg.href = "#";
    svg.textContent = "SVG";
    svg.addEventListener("click", (e) => {
      e.preventDefault();
      const u = plots[`fig-${id}`];
      if (!u) return;
      const blob = new Blob([svgOf(u, $(`cap-${id}`).firstChild.textContent.trim())], { type: "image/svg+xml" });
      save(URL.createObjectURL(blob), "svg");
    });
    const note = document.createElement("small");
    note.id = `note-${id}`;
    note.className = "note";
    $(`cap-${id}`).append(png, svg, note);
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
    $("export").addEventListener("click", exportSim);
    if (!s.can_save) {
      // Started from compare's flags: no case folder to write from.
      $("save").disabled = true;
      $("save").title = "Save writes a case folder: start `propbet serve CASE_DIR` to save";
    }
    // Redrawn when the figures' area changes size (the window, the header's numbers wrapping).
    let resize, size = "";
    new ResizeObserver(() => {
      const r = $("figures").getBoundingClientRect(), now = `${Math.round(r.width)}x${Math.round(r.height)}`;
      if (now === size) return;
      size = now;
      clearTimeout(resize);
      resize = setTimeout(() => last && draw(last), 100);
    }).observe($("figures"));
    await changed();
  } catch (e) { say(e.message, true); }
}

main();
