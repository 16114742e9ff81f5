// tessera view's page: keeps the settings, asks the server for frames (GET /api/frame), picks
// (GET /api/pick) and the reproducing command (GET /api/command); every setting is a query
// parameter named like the command line's option. One frame request is in flight at a time: while it
// runs only the newest wanted frame is remembered, and the server drops a waiting request of this page
// once a later one arrives (client, seq), so the page never queues behind old work.
'use strict';

const $ = (id) => document.getElementById(id);
const frame = $('frame');
const client = Math.random().toString(36).slice(2, 12);
let info = null;
let seq = 0;
let inflight = false;
let pending = null;         // {query, preview}
let shownQuery = null;      // the settings of the full frame on screen
let camera = null;          // {eye, target, up} as arrays, or null: the server's framing camera
let cameraMoved = false;

// Settings the controls hold, as request parameters.
const controlIds = ['view', 'scheme', 'isolation', 'partitioning', 'lod', 'factor', 'edge-pixels', 'cull', 'factor-kind',
                    'displacement-scale', 'msaa', 'resolution'];

function vec(a) { return a.map((x) => Number(x.toPrecision(7))).join(','); }
function sub(a, b) { return a.map((x, i) => x - b[i]); }
function add(a, b) { return a.map((x, i) => x + b[i]); }
function scale(a, s) { return a.map((x) => x * s); }
function dot(a, b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
function cross(a, b) { return [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]; }
function norm(a) { const l = Math.hypot(a[0], a[1], a[2]) || 1; return scale(a, 1 / l); }
// a rotated by angle about the unit axis k (Rodrigues).
function rotate(a, k, angle) {
  const c = Math.cos(angle), s = Math.sin(angle);
  return add(add(scale(a, c), scale(cross(k, a), s)), scale(k, dot(k, a) * (1 - c)));
}

function settings(preview) {
  const p = new URLSearchParams();
  const base = info.settings;
  for (const id of controlIds) {
    const el = $(id);
    if (id === 'displacement-scale' && (!info.displaced || el.value === '')) continue;
    if (el.value !== '' && String(el.value) !== String(base[id] ?? '')) p.set(id, el.value);
  }
  if (cameraMoved) {
    p.set('camera-position', vec(camera.eye));
    p.set('camera-target', vec(camera.target));
  }
  if ($('freeze').checked && $('freeze').dataset.eye) p.set('dicing-camera-position', $('freeze').dataset.eye);
  if (info.animated && Number($('time').value) !== Number(base.time)) p.set('time', $('time').value);
  if (preview) {
    const [w, h] = $('resolution').value.split('x').map(Number);
    p.set('resolution', Math.max(1, Math.round(w / 2)) + 'x' + Math.max(1, Math.round(h / 2)));
    p.set('format', 'jpeg');
  }
  return p.toString();
}

function status(text, error) {
  $('status').textContent = text;
  $('status').classList.toggle('error', !!error);
}

function want(preview) {
  pending = {query: settings(preview), preview};
  if (!preview) frame.dataset.state = 'loading';
  pump();
}

async function pump() {
  if (inflight || !pending) return;
  const job = pending;
  pending = null;
  inflight = true;
  seq += 1;
  try {
    const sep = job.query ? '&' : '';
    const asked = performance.now();
    const watch = watchProgress();
    const r = await fetch('/api/frame?' + job.query + sep + 'client=' + client + '&seq=' + seq)
      .finally(() => clearInterval(watch));
    if (r.ok) {
      const blob = await r.blob();
      const roundTrip = (performance.now() - asked) / 1e3;
      const old = frame.src;
      frame.src = URL.createObjectURL(blob);
      if (old.startsWith('blob:')) URL.revokeObjectURL(old);
      showStats(JSON.parse(r.headers.get('X-Tessera-Summary') || '{}'), job.preview, roundTrip, blob.size);
      if (!job.preview) {
        await frame.decode().catch(() => {});
        shownQuery = job.query;
        frame.dataset.query = job.query;
        history.replaceState(null, '', job.query ? '?' + job.query : location.pathname);
        if (!pending) frame.dataset.state = 'ready';
        showCommand();
      }
    } else if (r.status !== 409) {
      status((await r.text()).trim(), true);
      if (!pending) frame.dataset.state = 'error';
    }
  } catch (e) {
    status('the server is gone: ' + e, true);
  } finally {
    inflight = false;
    pump();
  }
}

// While a frame takes more than half a second (a scheme's first load of a large cage, say), the
// status line says which step the server is in, as `tessera render` does on stderr (GET /api/progress).
function watchProgress() {
  const started = performance.now();
  return setInterval(async () => {
    if (performance.now() - started < 500) return;
    try {
      const p = await (await fetch('/api/progress')).json();
      if (p.busy && inflight) status(p.step + ' (' + p.step_s.toFixed(1) + ' s)');
    } catch (e) { /* the frame request reports a server that is gone */ }
  }, 250);
}

function ms(seconds) { return (seconds * 1e3).toFixed(1) + ' ms'; }

function showStats(s, preview, roundTrip, size) {
  const t = s.times || {};
  const rows = [
    ['frame', (s.width || 0) + '×' + (s.height || 0) + (preview ? ' (preview)' : '')],
    ['triangles', (s.triangles ?? 0).toLocaleString()],
    ['patches', (s.patches ?? 0).toLocaleString()],
    ['patches culled', (s.patches_culled ?? 0).toLocaleString()],
    ['patches facing away', (s.patches_facing_away ?? 0).toLocaleString()],
    ['pixels shaded', (s.pixels_shaded ?? 0).toLocaleString()],
    ['frame (request to image)', ms(roundTrip) + ', ' + Math.round(size / 1024) + ' KiB'],
    ['draw (wall)', ms(t.wall_s || 0)],
    ['IA + VS · HS', ms(t.ia_vs_s || 0) + ' · ' + ms(t.hs_s || 0)],
    ['tessellator · DS', ms(t.tessellator_s || 0) + ' · ' + ms(t.ds_s || 0)],
    ['setup · raster + PS', ms(t.setup_s || 0) + ' · ' + ms(t.raster_s || 0)],
    // What the loader or the scheme left out (creases drawn smooth, tags on no edge), one row each.
    ...(s.warnings || []).map((w) => ['warning', w]),
  ];
  $('stats').replaceChildren(...rows.map(([k, v]) => {
    const tr = document.createElement('tr');
    tr.append(Object.assign(document.createElement('td'), {textContent: k}),
              Object.assign(document.createElement('td'), {textContent: v}));
    return tr;
  }));
  status(preview ? 'moving…' : 'ready');
}

async function showCommand() {
  const query = shownQuery;
  const r = await fetch('/api/command?' + query);
  if (!r.ok || query !== shownQuery) return;
  const c = await r.json();
  $('command').textContent = c.command;
  $('scene').textContent = JSON.stringify(c.scene, null, 2);
}

function factorsText(f) {
  return 'edge ' + f.edge.join(', ') + ' · inside ' + f.inside.join(', ');
}

async function pick(x, y) {
  if (shownQuery === null) return;
  const sep = shownQuery ? '&' : '';
  const r = await fetch('/api/pick?' + shownQuery + sep + 'x=' + x + '&y=' + y);
  const box = $('pick');
  if (!r.ok) { status((await r.text()).trim(), true); return; }
  const j = await r.json();
  box.dataset.pixel = x + ',' + y;
  box.dataset.face = j.patch ? j.patch.face : '';
  if (!j.patch) { box.replaceChildren(Object.assign(document.createElement('p'), {className: 'muted', textContent: 'no patch at (' + x + ', ' + y + ')'})); return; }
  const p = j.patch;
  const rows = [
    ['pixel', x + ', ' + y],
    ['face', p.face + (p.sub ? ' (sub-patch ' + p.sub + ')' : '')],
    ['patch', p.domain + ' #' + p.id],
    ['kind · type', p.kind + ' · ' + p.type],
    ['combination', p.combination + (p.combination_text ? ' (' + p.combination_text + ')' : '')],
    ['raw factors', factorsText(p.raw)],
    ['processed', factorsText(p.processed)],
    ['segments', factorsText(p.segments)],
    ['triangles', String(p.triangles)],
    ['screen size', p.screen_pixels === null ? '–' : p.screen_pixels.toFixed(1) + ' px'],
    ['culled', p.culled || 'no'],
  ];
  const table = document.createElement('table');
  for (const [k, v] of rows) {
    const tr = document.createElement('tr');
    tr.append(Object.assign(document.createElement('td'), {textContent: k}),
              Object.assign(document.createElement('td'), {textContent: v}));
    table.append(tr);
  }
  box.replaceChildren(table);
}

// Mouse: drag orbits about the target (about the up axis, and about the camera's right axis), shift
// or the right button pans, the wheel dollies; a press that does not move is a pick.
function startCamera() {
  if (camera) return;
  camera = {eye: info.camera.position.slice(), target: info.camera.target.slice(), up: info.camera.up.slice()};
}

function orbit(dx, dy) {
  startCamera();
  const up = norm(camera.up);
  let offset = sub(camera.eye, camera.target);
  offset = rotate(offset, up, -dx * 0.01);
  const right = norm(cross(offset, up));
  const turned = rotate(offset, right, -dy * 0.01);
  // Not over the pole: the view direction would meet the up axis (a degenerate camera).
  if (Math.abs(dot(norm(turned), up)) < 0.995) offset = turned;
  camera.eye = add(camera.target, offset);
  cameraMoved = true;
}

function pan(dx, dy) {
  startCamera();
  const offset = sub(camera.eye, camera.target);
  const dist = Math.hypot(...offset);
  const h = frame.clientHeight || 720;
  const unit = 2 * dist * Math.tan((info.camera.fov * Math.PI / 180) / 2) / h;
  const right = norm(cross(offset, camera.up));
  const upv = norm(cross(right, offset));
  const move = add(scale(right, dx * unit), scale(upv, dy * unit));
  camera.eye = add(camera.eye, move);
  camera.target = add(camera.target, move);
  cameraMoved = true;
}

function dolly(amount) {
  startCamera();
  const offset = sub(camera.eye, camera.target);
  camera.eye = add(camera.target, scale(offset, Math.exp(amount * 0.001)));
  cameraMoved = true;
}

function resetCamera() {
  camera = null;
  cameraMoved = false;
  want(false);
}

function framePixel(ev) {
  const r = frame.getBoundingClientRect();
  const x = Math.floor((ev.clientX - r.left) * frame.naturalWidth / r.width);
  const y = Math.floor((ev.clientY - r.top) * frame.naturalHeight / r.height);
  return [Math.min(Math.max(x, 0), frame.naturalWidth - 1), Math.min(Math.max(y, 0), frame.naturalHeight - 1)];
}

function hookMouse() {
  let drag = null;
  frame.addEventListener('contextmenu', (ev) => ev.preventDefault());
  frame.addEventListener('mousedown', (ev) => {
    ev.preventDefault();
    drag = {x: ev.clientX, y: ev.clientY, moved: false, pan: ev.shiftKey || ev.button === 2};
    frame.classList.add('dragging');
  });
  window.addEventListener('mousemove', (ev) => {
    if (!drag) return;
    const dx = ev.clientX - drag.x, dy = ev.clientY - drag.y;
    if (!drag.moved && Math.hypot(dx, dy) < 3) return;
    drag.moved = true;
    drag.x = ev.clientX;
    drag.y = ev.clientY;
    if (drag.pan) pan(-dx, dy); else orbit(dx, dy);
    want(true);
  });
  window.addEventListener('mouseup', (ev) => {
    if (!drag) return;
    frame.classList.remove('dragging');
    const d = drag;
    drag = null;
    if (d.moved) { want(false); return; }
    if (ev.target !== frame) return;
    const [x, y] = framePixel(ev);
    const box = $('frame-box').getBoundingClientRect();
    const marker = $('marker');
    marker.style.left = (ev.clientX - box.left) + 'px';
    marker.style.top = (ev.clientY - box.top) + 'px';
    marker.hidden = false;
    pick(x, y);
  });
  let wheelTimer = null;
  frame.addEventListener('wheel', (ev) => {
    ev.preventDefault();
    dolly(ev.deltaY);
    want(true);
    clearTimeout(wheelTimer);
    wheelTimer = setTimeout(() => want(false), 200);
  }, {passive: false});
  window.addEventListener('keydown', (ev) => {
    if ((ev.key === 'r' || ev.key === 'R') && !(ev.target instanceof HTMLInputElement)) resetCamera();
  });
}

// The page's address holds the settings of the full frame on screen (those that differ from the
// server's, as in /api/frame), so a debugging session is a link: opening it restores them. A value
// the server refuses is shown as the frame's error.
function applyAddress() {
  const q = new URLSearchParams(location.search);
  for (const id of controlIds) {
    if (!q.has(id)) continue;
    const el = $(id), v = q.get(id);
    if (el.tagName === 'SELECT' && ![...el.options].some((o) => o.value === v))
      el.append(Object.assign(document.createElement('option'), {textContent: v, value: v}));
    el.value = v;
  }
  const v3 = (text) => text.split(',').map(Number);
  if (q.has('camera-position') && q.has('camera-target')) {
    startCamera();
    camera.eye = v3(q.get('camera-position'));
    camera.target = v3(q.get('camera-target'));
    cameraMoved = true;
  }
  if (q.has('dicing-camera-position')) {
    $('freeze').checked = true;
    $('freeze').dataset.eye = q.get('dicing-camera-position');
  }
  if (q.has('time')) {
    $('time').value = q.get('time');
    $('time-text').textContent = Number($('time').value).toFixed(2) + ' s';
  }
}

function fillSelect(el, values, current) {
  el.replaceChildren(...values.map((v) => Object.assign(document.createElement('option'), {textContent: v, value: v})));
  el.value = current;
}

async function start() {
  const r = await fetch('/api/info');
  if (!r.ok) { status((await r.text()).trim(), true); return; }
  info = await r.json();
  const s = info.settings;
  $('asset').textContent = info.asset + ' · ' + info.faces + ' faces, ' + info.patches + ' patches';
  fillSelect($('view'), info.views, s.view);
  fillSelect($('scheme'), info.schemes, s.scheme);
  const resolutions = ['640x360', '960x540', '1280x720', '1920x1080'];
  if (!resolutions.includes(s.resolution)) resolutions.push(s.resolution);
  fillSelect($('resolution'), resolutions, s.resolution);
  for (const id of ['isolation', 'partitioning', 'lod', 'cull', 'factor-kind', 'factor', 'edge-pixels', 'msaa'])
    $(id).value = s[id];
  // The isolation level is the adaptive scheme's only.
  const isolationRow = () => { $('isolation-row').hidden = $('scheme').value !== 'adaptive'; };
  isolationRow();
  $('scheme').addEventListener('change', isolationRow);
  $('displacement-row').hidden = !info.displaced;
  $('displacement-scale').value = s['displacement-scale'] ?? '';
  $('displacement-scale').placeholder = 'the asset\'s';
  const animation = info.animations.find((a) => a.name === s.animation) || info.animations[0];
  $('time-row').hidden = !info.animated || !animation;
  if (animation) {
    $('time').min = Math.min(animation.start, s.time);
    $('time').max = Math.max(animation.end, s.time);
    $('time').step = Math.max((animation.end - animation.start) / 200, 0.001);
  }
  $('time').value = s.time;
  $('time-text').textContent = Number(s.time).toFixed(2) + ' s';
  applyAddress();
  isolationRow();
  for (const id of controlIds) $(id).addEventListener('change', () => want(false));
  $('time').addEventListener('input', () => { $('time-text').textContent = Number($('time').value).toFixed(2) + ' s'; want(true); });
  $('time').addEventListener('change', () => want(false));
  $('freeze').addEventListener('change', () => {
    startCamera();
    $('freeze').dataset.eye = $('freeze').checked ? vec(camera.eye) : '';
    if ($('freeze').checked && $('lod').value === 'uniform') $('lod').value = 'screen';
    want(false);
  });
  $('reset').addEventListener('click', resetCamera);
  $('copy').addEventListener('click', () => navigator.clipboard && navigator.clipboard.writeText($('command').textContent));
  hookMouse();
  want(false);
}

start();
