// The rgnav live viewer page: draws the frames procs/viewer streams on /ws (all in the map
// frame: x right, y up, metres) on one canvas, with pan and zoom, and sends a goal when a
// region is clicked and the operator confirms. Counts and the robot's pose are mirrored into
// #state's data-* attributes so a test can read them back from the DOM.
'use strict';

const canvas = document.getElementById('map');
const ctx = canvas.getContext('2d');
const stateEl = document.getElementById('state');

const scene = { map: null, graph: null, pose: null, scan: null, targets: null, trajectory: null,
                path: null, obstacles: null };
const view = { scale: 40, cx: 0, cy: 0, fitted: false };   // pixels per metre, map point at the centre
let socket = null;
let hello = { goals: 'allowed' };
let frames = 0, poseUpdates = 0, goalsSent = 0;

// Gateway classes (rgmap::GatewayClass / gateway_t.CLASS_*): colour and name.
const GATEWAY_CLASSES = [
  ['unknown', '#888'], ['door', '#d62728'], ['narrow passage', '#ff7f0e'], ['X crossing', '#2ca02c'],
  ['T crossing', '#17becf'], ['LT crossing', '#1f77b4'], ['RT crossing', '#9467bd'], ['L turn', '#8c564b'],
  ['R turn', '#e377c2'], ['dead end', '#7f7f7f'], ['hallway', '#bcbd22'], ['opening', '#aec7e8'],
];

function setState(key, value) { stateEl.dataset[key] = String(value); }

// ---- coordinates -------------------------------------------------------------------------
function toScreen(x, y) {
  return [canvas.width / 2 + (x - view.cx) * view.scale, canvas.height / 2 - (y - view.cy) * view.scale];
}
function toMap(px, py) {
  return [view.cx + (px - canvas.width / 2) / view.scale, view.cy - (py - canvas.height / 2) / view.scale];
}

function fit() {
  if (!scene.map || scene.map.regions.length === 0) return;
  let lo = [Infinity, Infinity], hi = [-Infinity, -Infinity];
  for (const r of scene.map.regions) {
    for (let i = 0; i < r.outline.length; i += 2) {
      lo = [Math.min(lo[0], r.outline[i]), Math.min(lo[1], r.outline[i + 1])];
      hi = [Math.max(hi[0], r.outline[i]), Math.max(hi[1], r.outline[i + 1])];
    }
  }
  view.cx = (lo[0] + hi[0]) / 2;
  view.cy = (lo[1] + hi[1]) / 2;
  const w = Math.max(hi[0] - lo[0], 1), h = Math.max(hi[1] - lo[1], 1);
  view.scale = Math.max(2, Math.min(400, 0.9 * Math.min(canvas.width / w, canvas.height / h)));
  view.fitted = true;
}

// ---- drawing ------------------------------------------------------------------------------
function regionColour(id, alpha) { return `hsla(${(id * 137.508) % 360}, 60%, 70%, ${alpha})`; }

function polyline(flat, close) {
  ctx.beginPath();
  for (let i = 0; i < flat.length; i += 2) {
    const [x, y] = toScreen(flat[i], flat[i + 1]);
    if (i === 0) ctx.moveTo(x, y); else ctx.lineTo(x, y);
  }
  if (close) ctx.closePath();
}

function segment(s) {
  const [ax, ay] = toScreen(s[0], s[1]), [bx, by] = toScreen(s[2], s[3]);
  ctx.beginPath();
  ctx.moveTo(ax, ay);
  ctx.lineTo(bx, by);
  ctx.stroke();
}

function draw() {
  const w = canvas.clientWidth, h = canvas.clientHeight;
  if (canvas.width !== w || canvas.height !== h) { canvas.width = w; canvas.height = h; }
  if (!view.fitted) fit();
  ctx.clearRect(0, 0, canvas.width, canvas.height);
  let regionsDrawn = 0;
  const map = scene.map;
  if (map) {
    for (const r of map.regions) {
      if (r.freespace) {
        drawFreespace(r, r.id === map.current_region ? 0.6 : 0.4);
      } else {
        polyline(r.outline, true);
        ctx.fillStyle = regionColour(r.id, r.id === map.current_region ? 0.45 : 0.25);
        ctx.fill();
      }
      polyline(r.outline, true);
      ctx.strokeStyle = regionColour(r.id, 0.9);
      ctx.lineWidth = 1;
      ctx.stroke();
      ctx.strokeStyle = '#222';
      ctx.lineWidth = 2;
      for (const s of r.segments) segment(s);
      ctx.fillStyle = 'rgba(60, 60, 160, 0.5)';
      for (const o of r.objects) drawObject(o);
      regionsDrawn++;
    }
    if (scene.graph) {
      ctx.setLineDash([4, 4]);
      ctx.lineWidth = 1;
      ctx.strokeStyle = 'rgba(0, 0, 0, 0.25)';
      for (const e of scene.graph.edges) segment(e);
      ctx.setLineDash([]);
    }
    ctx.lineWidth = 4;
    for (const g of map.gateways) {
      ctx.strokeStyle = (GATEWAY_CLASSES[g.class] || GATEWAY_CLASSES[0])[1];
      for (const l of g.lines) segment(l);
    }
    // Names last, over everything.
    ctx.fillStyle = '#000';
    ctx.font = '13px sans-serif';
    ctx.textAlign = 'center';
    for (const r of map.regions) {
      const [x, y] = toScreen(r.centre[0], r.centre[1]);
      ctx.fillText(r.name || `#${r.id}`, x, y);
    }
  }
  if (scene.obstacles) {
    ctx.strokeStyle = '#9400d3';
    ctx.lineWidth = 3;
    for (const e of scene.obstacles.edges) segment(e);
  }
  if (scene.path && scene.path.points.length >= 4 && scene.path.status === 0) {
    ctx.strokeStyle = 'rgba(31, 119, 180, 0.8)';
    ctx.lineWidth = 3;
    polyline(scene.path.points, false);
    ctx.stroke();
  }
  if (scene.trajectory && scene.trajectory.points.length >= 4) {
    ctx.strokeStyle = '#2ca02c';
    ctx.lineWidth = 2;
    polyline(scene.trajectory.points, false);
    ctx.stroke();
  }
  if (scene.targets) {
    ctx.fillStyle = '#ff7f0e';
    for (const t of scene.targets.targets) {
      const [x, y] = toScreen(t[0], t[1]);
      ctx.beginPath();
      ctx.arc(x, y, 4, 0, 2 * Math.PI);
      ctx.fill();
    }
  }
  if (scene.scan) {
    ctx.fillStyle = '#d62728';
    const p = scene.scan.points;
    for (let i = 0; i < p.length; i += 2) {
      const [x, y] = toScreen(p[i], p[i + 1]);
      ctx.fillRect(x - 1.5, y - 1.5, 3, 3);
    }
  }
  if (scene.pose) drawRobot(scene.pose);
  setState('regionsDrawn', regionsDrawn);
}

// A region's freespace bitmap (1 bit per cell, row-major, LSB first), painted in its colour
// through screen_from_map * map_from_grid; the image is made once per map frame.
function freespaceBits(r) {
  if (!r.freespace._bytes) {
    const raw = atob(r.freespace.bits);
    const bytes = new Uint8Array(raw.length);
    for (let i = 0; i < raw.length; i++) bytes[i] = raw.charCodeAt(i);
    r.freespace._bytes = bytes;
  }
  return r.freespace._bytes;
}

function isFree(r, x, y) {
  const f = r.freespace, [gx, gy, gt] = f.frame, dx = x - gx, dy = y - gy;
  const u = Math.floor((Math.cos(gt) * dx + Math.sin(gt) * dy) / f.resolution);
  const v = Math.floor((-Math.sin(gt) * dx + Math.cos(gt) * dy) / f.resolution);
  if (u < 0 || v < 0 || u >= f.width || v >= f.height) return false;
  const i = v * f.width + u;
  return (freespaceBits(r)[i >> 3] >> (i & 7)) & 1;
}

function drawFreespace(r, alpha) {
  const f = r.freespace;
  if (!f._image) {
    const bytes = freespaceBits(r);
    const img = new ImageData(f.width, f.height);
    const hue = (r.id * 137.508) % 360;
    const probe = document.createElement('canvas').getContext('2d');
    probe.fillStyle = `hsl(${hue}, 60%, 70%)`;
    const rgb = probe.fillStyle.match(/[0-9a-f]{2}/g).map(h => parseInt(h, 16));
    for (let i = 0; i < f.width * f.height; i++) {
      if (!((bytes[i >> 3] >> (i & 7)) & 1)) continue;
      img.data.set([rgb[0], rgb[1], rgb[2], 255], i * 4);
    }
    const c = document.createElement('canvas');
    c.width = f.width;
    c.height = f.height;
    c.getContext('2d').putImageData(img, 0, 0);
    f._image = c;
  }
  const [gx, gy, gt] = f.frame, k = view.scale * f.resolution;
  ctx.save();
  ctx.globalAlpha = alpha;
  ctx.imageSmoothingEnabled = false;
  ctx.setTransform(k * Math.cos(gt), -k * Math.sin(gt), -k * Math.sin(gt), -k * Math.cos(gt),
                   canvas.width / 2 + (gx - view.cx) * view.scale, canvas.height / 2 - (gy - view.cy) * view.scale);
  ctx.drawImage(f._image, 0, 0);
  ctx.restore();
}

function drawObject(o) {
  const [x, y] = toScreen(o.pose[0], o.pose[1]);
  ctx.save();
  ctx.translate(x, y);
  ctx.rotate(-o.pose[2]);
  if (o.shape === 'circle') {
    ctx.beginPath();
    ctx.arc(0, 0, o.length / 2 * view.scale, 0, 2 * Math.PI);
    ctx.fill();
  } else {
    ctx.fillRect(-o.length / 2 * view.scale, -o.width / 2 * view.scale, o.length * view.scale, o.width * view.scale);
  }
  ctx.restore();
}

function drawRobot(p) {
  const [x, y] = toScreen(p.pose[0], p.pose[1]);
  const r = Math.max(4, p.radius * view.scale);
  ctx.beginPath();
  ctx.arc(x, y, r, 0, 2 * Math.PI);
  ctx.fillStyle = 'rgba(255, 200, 0, 0.6)';
  ctx.fill();
  ctx.strokeStyle = '#000';
  ctx.lineWidth = 2;
  ctx.stroke();
  ctx.beginPath();
  ctx.moveTo(x, y);
  ctx.lineTo(x + r * Math.cos(p.pose[2]), y - r * Math.sin(p.pose[2]));
  ctx.stroke();
}

// Drawn at most every 50 ms, however fast frames come.
let drawPending = false, lastDraw = 0;
function requestDraw() {
  if (drawPending) return;
  const wait = Math.max(0, 50 - (Date.now() - lastDraw));
  drawPending = true;
  setTimeout(() => { drawPending = false; lastDraw = Date.now(); draw(); }, wait);
}

// ---- the side panel -----------------------------------------------------------------------
function text(el, s) { el.textContent = s; }

function fillTable(id, rows) {
  const body = document.querySelector(`#${id} tbody`);
  body.replaceChildren(...rows.map(([cells, bad]) => {
    const tr = document.createElement('tr');
    if (bad) tr.className = 'bad';
    for (const c of cells) { const td = document.createElement('td'); td.textContent = c; tr.appendChild(td); }
    return tr;
  }));
}

function showProcesses(m) {
  let rows;
  if (m.processes.length > 0) {
    rows = m.processes.map(p => [[p.name, p.state, p.restarts, p.heartbeat_age_s < 0 ? '—' : p.heartbeat_age_s.toFixed(1) + ' s',
                                  p.cpu_percent.toFixed(1)], p.state !== 'running']);
  } else {   // no supervisor: the heartbeats alone
    rows = m.heartbeats.map(b => [[b.name, b.state, '—', b.age_s.toFixed(1) + ' s', b.cpu_percent.toFixed(1)],
                                  b.state !== 'running' || b.age_s > 2]);
  }
  fillTable('processes', rows);
  const alerts = document.getElementById('alerts');
  if (m.alerts.length === 0) {
    alerts.innerHTML = '<li class="none">none</li>';
  } else {
    alerts.replaceChildren(...m.alerts.map(a => { const li = document.createElement('li'); li.textContent = a; return li; }));
  }
}

function showRates(m) {
  fillTable('streams', m.streams.map(s => [[s.channel, s.hz.toFixed(1), s.age_s.toFixed(1), s.count], false]));
}

function showLegend() {
  const legend = document.getElementById('legend');
  legend.replaceChildren(...GATEWAY_CLASSES.slice(1).map(([name, colour]) => {
    const li = document.createElement('li');
    const sw = document.createElement('span');
    sw.style.background = colour;
    li.append(sw, name);
    return li;
  }));
}

// ---- the stream ---------------------------------------------------------------------------
function onFrame(m) {
  frames++;
  setState('frames', frames);
  switch (m.type) {
    case 'hello':
      hello = m;
      break;
    case 'map':
      scene.map = m;
      setState('mapVersion', m.version);
      setState('regions', m.regions.length);
      setState('gateways', m.gateways.length);
      break;
    case 'pose':
      scene.pose = m;
      poseUpdates++;
      setState('poseUpdates', poseUpdates);
      setState('poseX', m.pose[0]);
      setState('poseY', m.pose[1]);
      setState('poseTheta', m.pose[2]);
      text(document.getElementById('robot'),
           `robot (${m.source}): x ${m.pose[0].toFixed(2)} m, y ${m.pose[1].toFixed(2)} m, ` +
           `heading ${(m.pose[2] * 180 / Math.PI).toFixed(0)}°${m.region_id ? ', region ' + m.region_id : ''}`);
      break;
    case 'scan':
      scene.scan = m;
      setState('scanPoints', m.points.length / 2);
      break;
    case 'path':
      scene.path = m;
      text(document.getElementById('goal'), `goal ${m.goal_id}: ${m.status_name}` +
           (m.status === 0 ? `, ${m.cost_s.toFixed(0)} s left` : '') + (m.reason ? ` (${m.reason})` : ''));
      break;
    case 'graph': case 'targets': case 'trajectory': case 'obstacles':
      scene[m.type] = m;
      break;
    case 'processes':
      showProcesses(m);
      return;
    case 'rates':
      showRates(m);
      return;
    case 'goal_ack':
      text(document.getElementById('goal'), m.ok ? (m.cancel ? 'cancel sent' : `goal to region ${m.region_id} sent`)
                                                 : `goal refused: ${m.why}`);
      return;
    default:
      return;
  }
  requestDraw();
}

function connect() {
  socket = new WebSocket(`ws://${location.host}/ws`);
  const conn = document.getElementById('connection');
  socket.onopen = () => { setState('connected', true); conn.className = 'ok'; text(conn, `connected to ${location.host}`); };
  socket.onmessage = ev => {
    try { onFrame(JSON.parse(ev.data)); } catch (e) { console.error('bad frame', e); }
  };
  socket.onclose = () => {
    setState('connected', false);
    conn.className = 'bad';
    text(conn, 'disconnected: reconnecting…');
    setTimeout(connect, 1000);
  };
}

// ---- input: pan, zoom, click to send a goal ------------------------------------------------
let drag = null;
canvas.addEventListener('mousedown', e => { drag = { x: e.offsetX, y: e.offsetY, moved: false }; });
canvas.addEventListener('mousemove', e => {
  if (!drag) return;
  const dx = e.offsetX - drag.x, dy = e.offsetY - drag.y;
  if (Math.abs(dx) + Math.abs(dy) > 3) drag.moved = true;
  if (!drag.moved) return;
  view.cx -= dx / view.scale;
  view.cy += dy / view.scale;
  drag.x = e.offsetX;
  drag.y = e.offsetY;
  requestDraw();
});
canvas.addEventListener('mouseup', e => {
  const click = drag && !drag.moved;
  drag = null;
  if (click) clickAt(e.offsetX, e.offsetY, e.shiftKey);
});
canvas.addEventListener('wheel', e => {
  e.preventDefault();
  const [mx, my] = toMap(e.offsetX, e.offsetY);
  view.scale = Math.max(2, Math.min(1000, view.scale * Math.exp(-e.deltaY * 0.001)));
  // Zoom about the pointer: the map point under it stays there.
  const [nx, ny] = toMap(e.offsetX, e.offsetY);
  view.cx += mx - nx;
  view.cy += my - ny;
  requestDraw();
}, { passive: false });
window.addEventListener('keydown', e => { if (e.key === 'f') { view.fitted = false; requestDraw(); } });
window.addEventListener('resize', requestDraw);

function inside(flat, x, y) {
  let inPoly = false;
  for (let i = 0, j = flat.length - 2; i < flat.length; j = i, i += 2) {
    const xi = flat[i], yi = flat[i + 1], xj = flat[j], yj = flat[j + 1];
    if ((yi > y) !== (yj > y) && x < (xj - xi) * (y - yi) / (yj - yi) + xi) inPoly = !inPoly;
  }
  return inPoly;
}

function clickAt(px, py, withPose) {
  if (!scene.map || !socket || socket.readyState !== WebSocket.OPEN) return;
  const [x, y] = toMap(px, py);
  // The smallest region under the click (regions' rectangles may overlap).
  let hit = null, best = Infinity;
  for (const r of scene.map.regions) {
    if (!inside(r.outline, x, y) || (r.freespace && !isFree(r, x, y))) continue;
    const o = r.outline, area = Math.hypot(o[2] - o[0], o[3] - o[1]) * Math.hypot(o[4] - o[2], o[5] - o[3]);
    if (area < best) { best = area; hit = r; }
  }
  if (!hit) return;
  const name = hit.name ? `'${hit.name}' (region ${hit.id})` : `region ${hit.id}`;
  const goal = { type: 'goal', region_id: hit.id };
  let what = `Send the robot to ${name}?`;
  if (withPose) {
    // The clicked spot in the region's frame.
    const [fx, fy, ft] = hit.frame, dx = x - fx, dy = y - fy;
    goal.pose = [Math.cos(ft) * dx + Math.sin(ft) * dy, -Math.sin(ft) * dx + Math.cos(ft) * dy, 0];
    what = `Send the robot to (${x.toFixed(2)}, ${y.toFixed(2)}) in ${name}?`;
  }
  if (!window.confirm(what)) return;
  if (hello.goals === 'off') { text(document.getElementById('goal'), 'goals from this host are off'); return; }
  if (hello.goals === 'token') {
    let token = sessionStorage.getItem('rgnav-goal-token');
    if (!token) { token = window.prompt('Goal token (http.goal_token of config/viewer.yaml):') || ''; sessionStorage.setItem('rgnav-goal-token', token); }
    goal.token = token;
  }
  socket.send(JSON.stringify(goal));
  goalsSent++;
  setState('goalsSent', goalsSent);
}

showLegend();
connect();
requestDraw();
