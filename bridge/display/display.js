// kelvin bridge display: reads the state stream (/stream, server-sent
// events), draws the own-ship track on a local grid in metres (north up) and
// the conning values, and sends helm orders while this page holds the helm.
//
// For scripted use (headless browsers, tests), the address may carry
//   ?updates=N  stop watching after N updates (the page then stays as it is)
//   ?helm=D     take the helm at the first update and order D deg of rudder
'use strict';

const DEG = 180 / Math.PI;
const KNOT = 1852 / 3600;
const PHASES = { approach: 'approach', execute: 'execute', steady: 'steady', finished: 'finished', free: 'helm' };

const track = [];            // [x north, y east] in m
let latest = null;           // the last update
let token = null;            // helm token while this page holds the helm
const order = { rudder: 0, rps: 0 };
let headingChange = null;    // deg, unwrapped, since the maneuver's start
let lastHeading = null;
const marks = [];            // heading-change marks passed (90, 180, ...)

const $ = (id) => document.getElementById(id);
const fixed = (v, n) => (v === null || v === undefined ? '-' : v.toFixed(n));
const wrap360 = (d) => ((d % 360) + 360) % 360;

function setValue(id, value, digits) {
  const e = $(id);
  e.textContent = fixed(value, digits);
  e.dataset.value = value === null || value === undefined ? '' : String(value);
}

function updateHeadingChange(s, events) {
  const start = events.find((e) => e.kind === 'start');
  const h = s.heading * DEG;
  if (start && headingChange === null) {
    // From the start heading, the shorter way round (a page that opens
    // after a turn of more than 180 deg cannot know it).
    const d0 = start.heading === null ? 0 : h - start.heading * DEG;
    headingChange = d0 - 360 * Math.round(d0 / 360);
  } else if (headingChange !== null && lastHeading !== null) {
    let d = h - lastHeading;
    d -= 360 * Math.round(d / 360);
    headingChange += d;
  }
  lastHeading = h;
  if (headingChange === null) return;
  const passed = Math.floor(Math.abs(headingChange) / 90) * 90;
  for (let m = 90; m <= passed; m += 90) {
    if (!marks.some((k) => k.mark === m)) marks.push({ mark: m, t: s.t });
  }
}

function showEvents(events) {
  const items = events.map((e) => {
    let text = `t ${fixed(e.t, 1)} s  ${e.kind} ${e.index}`;
    if (e.kind === 'overshoot') text += `  overshoot ${fixed(e.overshoot * DEG, 2)} deg`;
    if (e.heading_change !== null) text += `  heading change ${fixed(e.heading_change * DEG, 1)} deg`;
    return { t: e.t, text };
  });
  for (const m of marks) items.push({ t: m.t, text: `t ${fixed(m.t, 1)} s  heading change ${m.mark} deg mark` });
  items.sort((a, b) => a.t - b.t);
  const list = $('events');
  list.replaceChildren(...items.map((i) => {
    const li = document.createElement('li');
    li.textContent = i.text;
    return li;
  }));
}

function showHeader(u) {
  $('ship').textContent = `kelvin bridge: ${u.ship}`;
  $('script').textContent = u.script ? `script ${u.script}` : 'helm commands steer';
  const d = $('derivatives');
  d.textContent = u.derivatives.checked ? `checked: ${u.derivatives.message}`
    : `NOT CHECKED against free-running CFD: ${u.derivatives.message}`;
  d.className = `badge ${u.derivatives.checked ? 'checked' : 'unchecked'}`;
}

function showHelm(u) {
  const h = u.helm;
  const p = u.page;
  $('helm-stats').textContent =
    `received ${h.received}, accepted ${h.accepted} (clamped ${h.clamped}), rejected ${h.rejected}: ` +
    `malformed ${h.malformed}, not finite ${h.not_finite}, out of range ${h.out_of_range}, stale ${h.stale}, ` +
    `future ${h.future}, unknown source ${h.unknown_source}. Page: queued ${p.helm_queued}, ` +
    `not holder ${p.not_holder}, malformed ${p.malformed}, oversized ${p.oversized}, bad ${p.bad_requests}; ` +
    `${p.streams_open} page(s) watching`;
  if (!token) $('claim').disabled = h.held;
}

function showBar(s) {
  const scale = 130 / 35;  // px per deg, +-35 deg across the bar
  const a = Math.max(-35, Math.min(35, s.rudder_angle * DEG)) * scale;
  const bar = $('rudder-bar');
  bar.style.left = `${130 + Math.min(0, a)}px`;
  bar.style.width = `${Math.abs(a)}px`;
  $('order-bar').style.left = `${130 + Math.max(-35, Math.min(35, s.rudder_order * DEG)) * scale - 1}px`;
}

function show(u) {
  latest = u;
  showHeader(u);
  showHelm(u);
  const s = u.state;
  if (!s) return;
  setValue('seq', s.seq, 0);
  setValue('heading', wrap360(s.heading * DEG), 1);
  setValue('cog', wrap360(s.course_over_ground * DEG), 1);
  setValue('sog', s.speed_over_ground / KNOT, 2);
  setValue('rot', s.r * DEG * 60, 1);
  setValue('drift', s.drift_angle * DEG, 2);
  setValue('rudder-angle', s.rudder_angle * DEG, 1);
  setValue('rudder-order', s.rudder_order * DEG, 1);
  setValue('rps', s.propeller_rps, 2);
  setValue('rps-order', s.propeller_rps_order, 2);
  setValue('time', s.t, 1);
  $('phase').textContent = PHASES[s.phase] || s.phase;
  $('position').textContent = `${fixed(s.latitude, 5)}, ${fixed(s.longitude, 5)} (${fixed(s.x, 0)} m N, ${fixed(s.y, 0)} m E)`;
  updateHeadingChange(s, u.events);
  setValue('heading-change', headingChange, 1);
  showEvents(u.events);
  showBar(s);
  const lastPoint = track[track.length - 1];
  if (!lastPoint || Math.hypot(lastPoint[0] - s.x, lastPoint[1] - s.y) > 1) track.push([s.x, s.y]);
  const rpsInput = $('rps-input');
  if (Number(rpsInput.max) < 2 * s.propeller_rps_order) rpsInput.max = (2 * s.propeller_rps_order).toFixed(2);
  if (!token) {
    order.rudder = s.rudder_order * DEG;
    order.rps = s.propeller_rps_order;
    showOrder();
  }
  draw();
}

// A grid step of 1, 2 or 5 x 10^n m giving about six lines across `span`.
function gridStep(span) {
  const raw = span / 6;
  const p = 10 ** Math.floor(Math.log10(raw));
  return [1, 2, 5, 10].map((k) => k * p).find((k) => k >= raw);
}

function draw() {
  const c = $('track');
  const g = c.getContext('2d');
  g.clearRect(0, 0, c.width, c.height);
  if (!latest || !latest.state) return;
  const s = latest.state;
  const pts = track.concat([[s.x, s.y]]);
  let minN = Math.min(...pts.map((p) => p[0])), maxN = Math.max(...pts.map((p) => p[0]));
  let minE = Math.min(...pts.map((p) => p[1])), maxE = Math.max(...pts.map((p) => p[1]));
  const span = Math.max(maxN - minN, maxE - minE, 50) * 1.15;
  const cN = (minN + maxN) / 2, cE = (minE + maxE) / 2;
  const px = c.width / span;
  const toX = (e) => c.width / 2 + (e - cE) * px;
  const toY = (n) => c.height / 2 - (n - cN) * px;
  const step = gridStep(span);
  g.strokeStyle = '#1f2d38';
  g.fillStyle = '#5d7080';
  g.font = '11px sans-serif';
  g.lineWidth = 1;
  for (let e = Math.ceil((cE - span / 2) / step) * step; e <= cE + span / 2; e += step) {
    g.beginPath(); g.moveTo(toX(e), 0); g.lineTo(toX(e), c.height); g.stroke();
    g.fillText(`${e.toFixed(0)} E`, toX(e) + 2, c.height - 4);
  }
  for (let n = Math.ceil((cN - span / 2) / step) * step; n <= cN + span / 2; n += step) {
    g.beginPath(); g.moveTo(0, toY(n)); g.lineTo(c.width, toY(n)); g.stroke();
    g.fillText(`${n.toFixed(0)} N`, 2, toY(n) - 2);
  }
  $('grid-note').textContent = `north up; grid ${step} m; origin ${latest.origin[0]}, ${latest.origin[1]} deg`;
  g.strokeStyle = '#3fa7e0';
  g.lineWidth = 2;
  g.beginPath();
  pts.forEach((p, i) => (i ? g.lineTo(toX(p[1]), toY(p[0])) : g.moveTo(toX(p[1]), toY(p[0]))));
  g.stroke();
  // Own ship: a triangle along the heading, 14 px long.
  const x = toX(s.y), y = toY(s.x), h = s.heading;
  const ahead = [Math.sin(h), -Math.cos(h)], beam = [Math.cos(h), Math.sin(h)];
  g.fillStyle = '#f0b030';
  g.beginPath();
  g.moveTo(x + 10 * ahead[0], y + 10 * ahead[1]);
  g.lineTo(x - 6 * ahead[0] + 5 * beam[0], y - 6 * ahead[1] + 5 * beam[1]);
  g.lineTo(x - 6 * ahead[0] - 5 * beam[0], y - 6 * ahead[1] - 5 * beam[1]);
  g.closePath();
  g.fill();
}

function showOrder() {
  $('rudder-set').textContent = order.rudder.toFixed(0);
  $('rps-set').textContent = order.rps.toFixed(2);
  $('rudder-input').value = order.rudder;
  $('rps-input').value = order.rps;
}

async function post(path, fields) {
  const body = new URLSearchParams(fields);
  const r = await fetch(path, { method: 'POST', body });
  return { status: r.status, json: await r.json().catch(() => ({})) };
}

function setHolding(holding, text) {
  $('claim').disabled = holding;
  $('release').disabled = !holding;
  $('rudder-input').disabled = !holding;
  $('rps-input').disabled = !holding;
  $('helm-status').textContent = text;
}

async function sendOrder() {
  if (!token) return;
  showOrder();
  const r = await post('/helm', { token, rudder: order.rudder, rps: order.rps });
  if (r.status === 403) {
    token = null;
    setHolding(false, 'lost the helm (another page took it, or it lapsed)');
  } else if (r.status !== 200) {
    $('helm-status').textContent = `order not taken: ${r.json.error || r.status}`;
  } else {
    $('helm-status').textContent = `this page holds the helm; order ${order.rudder.toFixed(0)} deg taken`;
  }
}

async function claim() {
  const r = await post('/helm/claim', {});
  if (r.status === 200) {
    token = r.json.token;
    setHolding(true, 'this page holds the helm');
  } else {
    $('helm-status').textContent = r.json.error || `cannot take the helm (${r.status})`;
  }
}

async function release() {
  if (token) await post('/helm/release', { token });
  token = null;
  setHolding(false, 'released; watching');
}

function onKey(ev) {
  if (!token) return;
  const big = ev.shiftKey ? 5 : 1;
  if (ev.key === 'ArrowLeft') order.rudder = Math.max(-35, order.rudder - big);
  else if (ev.key === 'ArrowRight') order.rudder = Math.min(35, order.rudder + big);
  else if (ev.key === 'm') order.rudder = 0;
  else if (ev.key === 'ArrowUp') order.rps = Math.min(Number($('rps-input').max), order.rps + 0.05);
  else if (ev.key === 'ArrowDown') order.rps = Math.max(0, order.rps - 0.05);
  else return;
  ev.preventDefault();
  sendOrder();
}

const params = new URLSearchParams(window.location.search);
const stopAfter = Number(params.get('updates') || 0);
const scriptedHelm = params.get('helm');

async function scriptedOrder() {
  await claim();
  order.rudder = Math.max(-35, Math.min(35, Number(scriptedHelm)));
  await sendOrder();
}

function start() {
  $('claim').addEventListener('click', claim);
  $('release').addEventListener('click', release);
  $('rudder-input').addEventListener('input', (e) => { order.rudder = Number(e.target.value); sendOrder(); });
  $('rps-input').addEventListener('input', (e) => { order.rps = Number(e.target.value); sendOrder(); });
  document.addEventListener('keydown', onKey);
  const keepHelm = setInterval(sendOrder, 1000);  // keeps the helm while held
  // The track from before this page opened, ahead of what the stream adds.
  fetch('/track').then((r) => r.json()).then((t) => {
    track.unshift(...t.x.map((x, i) => [x, t.y[i]]));
  }).catch(() => {});
  const source = new EventSource('/stream');
  let count = 0;
  let since = performance.now();
  let received = 0;
  source.onmessage = (m) => {
    show(JSON.parse(m.data));
    ++received;
    if (received === 1 && scriptedHelm !== null) scriptedOrder();
    if (stopAfter && received >= stopAfter) {
      source.close();
      clearInterval(keepHelm);
      $('link').textContent = `stopped after ${received} updates`;
    }
    ++count;
    const now = performance.now();
    if (now - since > 2000) {
      $('link').textContent = `${(count * 1000 / (now - since)).toFixed(1)} updates/s`;
      count = 0;
      since = now;
    }
  };
  source.onerror = () => { $('link').textContent = 'stream lost; retrying'; };
}

start();
