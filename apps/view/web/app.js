// The page: loads the light field once, keeps what the user chose (state), and redraws on each change.

import { prepareEdit } from './colour.js';
import { drawColourBar, drawEpi, drawView, drawViewGrid, packedViews } from './render.js';

const $ = (id) => document.getElementById(id);
const data = {};
const state = {
  view: { u: 0, v: 0 },
  cursor: { x: 0, y: 0 },
  show: 'image',
  boundaries: true,
  highlight: true,
  tool: 'click',
  selected: new Uint8Array(0),
  selectionVersion: 0,
  params: { space: 'lch', hue: 0, saturation: 1, value: 1, feather: 0 },
  edit: null,
  editVersion: 0,
  // coarse: sum every other view (the preview while dragging); fullNext: sum them all in the frame after this one.
  refocus: { on: false, disparity: 0, allInFocus: false, coarse: false, fullNext: false },
  zoom: 1, panX: 0, panY: 0,
};
// What a page test or a user reads back: load time and slider-to-frame times (ms).
window.lfspStats = { loadMs: null, frames: [], ready: false };

// ---- loading -------------------------------------------------------------------------------------------------

async function fetchBytes(path) {
  const response = await fetch(path);
  if (!response.ok) throw new Error(`${path}: HTTP ${response.status}`);
  return response.arrayBuffer();
}

function finiteRange(values) {
  let min = Infinity, max = -Infinity;
  for (const v of values) if (Number.isFinite(v)) { if (v < min) min = v; if (v > max) max = v; }
  return min <= max ? { min, max } : { min: 0, max: 1 };
}

// Mean centre-view disparity per label, for "similar depth".
function labelDepths() {
  if (!data.labels || !data.disparity) return null;
  const N = data.width * data.height, centre = (Math.floor(data.nv / 2) * data.nu + Math.floor(data.nu / 2)) * N;
  const sum = new Float64Array(data.largestLabel + 1), count = new Uint32Array(data.largestLabel + 1);
  for (let p = 0; p < N; ++p) {
    const label = data.labels[centre + p], d = data.disparity[p];
    if (label <= data.largestLabel && Number.isFinite(d)) { sum[label] += d; count[label] += 1; }
  }
  return sum.map((s, i) => (count[i] ? s / count[i] : NaN));
}

async function load() {
  const started = performance.now();
  const meta = await (await fetch('/api/meta')).json();
  Object.assign(data, { nu: meta.nu, nv: meta.nv, width: meta.width, height: meta.height, meta });
  const [views, labels, disparity, confidence] = await Promise.all([
    fetchBytes('/api/views'),
    meta.label_bytes ? fetchBytes('/api/labels') : null,
    meta.has_disparity ? fetchBytes('/api/disparity') : null,
    meta.has_confidence ? fetchBytes('/api/confidence') : null,
  ]);
  data.views = new Uint8Array(views);
  data.labels = labels ? (meta.label_bytes === 2 ? new Uint16Array(labels) : new Int32Array(labels)) : null;
  data.largestLabel = meta.largest_label ?? -1;
  data.disparity = disparity ? new Float32Array(disparity) : null;
  data.confidence = confidence ? new Float32Array(confidence) : null;
  if (data.disparity) data.disparityRange = finiteRange(data.disparity);
  if (data.confidence) data.confidenceRange = finiteRange(data.confidence);
  data.labelDepths = labelDepths();
  state.selected = new Uint8Array(Math.max(0, data.largestLabel + 1));
  state.view = { u: Math.floor(data.nu / 2), v: Math.floor(data.nv / 2) };
  state.cursor = { x: Math.floor(data.width / 2), y: Math.floor(data.height / 2) };
  window.lfspStats.loadMs = performance.now() - started;
}

// ---- drawing -------------------------------------------------------------------------------------------------

let image = null;
let pendingSince = null;  // when the oldest change not yet drawn happened
let pendingSource = null;

// Draws at the next animation frame, once for all changes until then. `source` names a change to time (a slider,
// the view, the selection); null for cursor moves, which are not timed: a timed change that joins a pending cursor
// redraw is timed from itself.
function requestDraw(source, since = performance.now()) {
  if (pendingSince === null) {
    pendingSince = since;
    pendingSource = source;
    requestAnimationFrame(drawFrame);
  } else if (source && !pendingSource) {
    pendingSince = since;
    pendingSource = source;
  }
}

// A refocus that needs every view (letting go of the slider, a click on its track, a key, the tick boxes) is drawn
// in two frames, so that one follows the change at once: the preview of every other view first (already summed
// after a drag), then all views, timed from the same change ('focus-full').
function requestFullRefocus(source) {
  if (!state.refocus.on && !state.refocus.allInFocus) return requestDraw(source);  // turned off: the view alone
  state.refocus.coarse = true;
  state.refocus.fullNext = true;
  state.refocus.fullSince = performance.now();
  requestDraw(source);
}

function drawFrame() {
  const canvas = $('view');
  if (!image) image = canvas.getContext('2d').createImageData(data.width, data.height);
  drawView(data, state, image);
  canvas.getContext('2d').putImageData(image, 0, 0);
  drawEpis();
  drawViewGrid(data, state, $('view-grid'));
  drawReadout();
  const since = pendingSince, elapsed = performance.now() - since;
  if (pendingSource) {
    // ms: the change drawn; presentedMs: the next frame begins, so the browser has shown this one.
    const record = { source: pendingSource, ms: elapsed, presentedMs: null };
    window.lfspStats.frames.push(record);
    requestAnimationFrame(() => { record.presentedMs = performance.now() - since; });
  }
  $('timing').textContent = `last frame ${elapsed.toFixed(1)} ms after the change` +
                            (window.lfspStats.loadMs ? ` · loaded in ${(window.lfspStats.loadMs / 1000).toFixed(2)} s` : '');
  pendingSince = null;
  pendingSource = null;
  if (state.refocus.fullNext) {
    state.refocus.fullNext = false;
    state.refocus.coarse = false;
    requestDraw('focus-full', state.refocus.fullSince);
  }
}

function drawEpis() {
  for (const [id, horizontal] of [['epi-horizontal', true], ['epi-vertical', false]]) {
    const epi = drawEpi(data, state, horizontal);
    const canvas = $(id);
    // The vertical EPI is drawn with views as columns: transpose the lines.
    const width = horizontal ? epi.width : epi.height, height = horizontal ? epi.height : epi.width;
    if (canvas.width !== width || canvas.height !== height) { canvas.width = width; canvas.height = height; }
    const context = canvas.getContext('2d');
    if (horizontal) { context.putImageData(epi, 0, 0); continue; }
    const transposed = context.createImageData(width, height);
    for (let line = 0; line < epi.height; ++line) for (let t = 0; t < epi.width; ++t) {
      const from = 4 * (line * epi.width + t), to = 4 * (t * width + line);
      for (let c = 0; c < 4; ++c) transposed.data[to + c] = epi.data[from + c];
    }
    context.putImageData(transposed, 0, 0);
  }
}

function placeCursorLines() {
  $('cursor-row').style.top = `${state.panY + (state.cursor.y + 0.5) * state.zoom}px`;
  $('cursor-column').style.left = `${state.panX + (state.cursor.x + 0.5) * state.zoom}px`;
}

function drawReadout() {
  placeCursorLines();
  const { x, y } = state.cursor, N = data.width * data.height;
  const parts = [`view (${state.view.u}, ${state.view.v})`, `x ${x} y ${y}`];
  if (data.labels) {
    const label = data.labels[(state.view.v * data.nu + state.view.u) * N + y * data.width + x];
    parts.push(label <= data.largestLabel ? `label ${label}` : 'unlabelled');
  }
  if (data.disparity) parts.push(`disparity ${data.disparity[y * data.width + x].toFixed(3)} (centre view)`);
  if (data.confidence) parts.push(`confidence ${data.confidence[y * data.width + x].toFixed(3)}`);
  $('readout').textContent = parts.join(' · ');
  $('view-name').textContent = `view (${state.view.u}, ${state.view.v}) of ${data.nu} x ${data.nv}`;
}

// ---- zoom and pan --------------------------------------------------------------------------------------------

const EPI_THICKNESS = 90;  // CSS pixels across an EPI (style.css)

function applyTransform() {
  $('view').style.transform = `translate(${state.panX}px, ${state.panY}px) scale(${state.zoom})`;
  $('epi-horizontal').style.transform = `translate(${state.panX}px, 0) scale(${state.zoom}, ${EPI_THICKNESS / data.nu})`;
  $('epi-vertical').style.transform = `translate(0, ${state.panY}px) scale(${EPI_THICKNESS / data.nv}, ${state.zoom})`;
  placeCursorLines();
}

function fitToViewport() {
  const box = $('viewport').getBoundingClientRect();
  state.zoom = Math.min(box.width / data.width, box.height / data.height);
  state.panX = (box.width - data.width * state.zoom) / 2;
  state.panY = (box.height - data.height * state.zoom) / 2;
  applyTransform();
}

function imagePoint(event) {
  const rect = $('view').getBoundingClientRect();
  const x = Math.floor(((event.clientX - rect.left) / rect.width) * data.width);
  const y = Math.floor(((event.clientY - rect.top) / rect.height) * data.height);
  return { x: Math.max(0, Math.min(data.width - 1, x)), y: Math.max(0, Math.min(data.height - 1, y)) };
}

// ---- selection and history -----------------------------------------------------------------------------------

const history = { past: [], future: [] };

function snapshot() { return { selected: state.selected.slice(), params: { ...state.params } }; }

function remember() {
  history.past.push(snapshot());
  if (history.past.length > 200) history.past.shift();
  history.future = [];
  updateButtons();
}

function restore(saved) {
  state.selected = saved.selected;
  state.params = saved.params;
  selectionChanged();
  paramsChanged('history');
  syncSliders();
}

function undo() {
  if (!history.past.length) return;
  history.future.push(snapshot());
  restore(history.past.pop());
  updateButtons();
}

function redo() {
  if (!history.future.length) return;
  history.past.push(snapshot());
  restore(history.future.pop());
  updateButtons();
}

function selectedIds() {
  const ids = [];
  state.selected.forEach((on, id) => { if (on) ids.push(id); });
  return ids;
}

function selectionChanged() {
  state.selectionVersion += 1;
  const count = selectedIds().length;
  $('selection-count').textContent = `${count} superpixel${count === 1 ? '' : 's'} selected`;
  updateButtons();
  requestDraw('selection');
}

function labelAt(point) {
  const N = data.width * data.height;
  const label = data.labels[(state.view.v * data.nu + state.view.u) * N + point.y * data.width + point.x];
  return label <= data.largestLabel ? label : null;
}

function clickSelect(point, additive) {
  const label = labelAt(point);
  if (label === null) return;
  remember();
  if (state.tool === 'depth') {
    const target = data.labelDepths[label], tolerance = Number($('depth-tolerance').value);
    if (!additive) state.selected.fill(0);
    data.labelDepths.forEach((d, id) => { if (Math.abs(d - target) <= tolerance) state.selected[id] = 1; });
  } else if (additive) {
    state.selected[label] ^= 1;
  } else {
    state.selected.fill(0);
    state.selected[label] = 1;
  }
  selectionChanged();
}

function paintAt(point, erase) {
  const label = labelAt(point);
  if (label === null || state.selected[label] === (erase ? 0 : 1)) return;
  state.selected[label] = erase ? 0 : 1;
  selectionChanged();
}

// ---- edit parameters -----------------------------------------------------------------------------------------

const SLIDERS = ['hue', 'saturation', 'value', 'feather'];

function paramsChanged(source) {
  state.edit = prepareEdit(state.params);
  state.editVersion += 1;
  requestDraw(source);
}

function syncSliders() {
  for (const name of SLIDERS) {
    $(name).value = state.params[name];
    document.querySelector(`output[for=${name}]`).value = state.params[name];
  }
  $('space').value = state.params.space;
}

function updateButtons() {
  $('undo').disabled = !history.past.length;
  $('redo').disabled = !history.future.length;
}

// ---- export --------------------------------------------------------------------------------------------------

async function exportEdit() {
  const result = $('export-result');
  result.textContent = 'exporting…';
  delete result.dataset.arguments;
  const body = JSON.stringify({ label_ids: selectedIds(), ...state.params });
  const response = await fetch('/api/export', { method: 'POST', headers: { 'Content-Type': 'application/json' }, body });
  const answer = await response.json();
  if (!response.ok) { result.textContent = answer.error; return; }
  result.dataset.arguments = JSON.stringify(answer.arguments);
  result.textContent = `${answer.command}\n\nwrote:\n${answer.files.join('\n')}`;
}

// ---- events --------------------------------------------------------------------------------------------------

function setView(u, v) {
  u = Math.max(0, Math.min(data.nu - 1, u));
  v = Math.max(0, Math.min(data.nv - 1, v));
  if (u === state.view.u && v === state.view.v) return;
  state.view = { u, v };
  requestDraw('view');
}

function bindViewport() {
  const viewport = $('viewport');
  let drag = null;
  viewport.addEventListener('contextmenu', (event) => event.preventDefault());
  viewport.addEventListener('mousedown', (event) => {
    const point = imagePoint(event);
    drag = { button: event.button, x: event.clientX, y: event.clientY, moved: false,
             view: { ...state.view }, pan: { x: state.panX, y: state.panY } };
    if (event.button === 0 && state.tool === 'paint' && data.labels) { remember(); paintAt(point, event.shiftKey); }
  });
  window.addEventListener('mousemove', (event) => {
    if (event.target === $('view') || drag) {
      state.cursor = imagePoint(event);
      requestDraw(null);
    }
    if (!drag) return;
    const dx = event.clientX - drag.x, dy = event.clientY - drag.y;
    if (Math.abs(dx) + Math.abs(dy) > 4) drag.moved = true;
    if (drag.button !== 0) {  // pan
      state.panX = drag.pan.x + dx; state.panY = drag.pan.y + dy;
      applyTransform();
    } else if (state.tool === 'paint' && data.labels) {
      paintAt(imagePoint(event), event.shiftKey);
    } else if (drag.moved) {  // move through the views: 40 screen pixels per view
      setView(drag.view.u - Math.round(dx / 40), drag.view.v - Math.round(dy / 40));
    }
  });
  window.addEventListener('mouseup', (event) => {
    if (drag && drag.button === 0 && !drag.moved && state.tool !== 'paint' && data.labels &&
        event.target === $('view')) {
      clickSelect(imagePoint(event), event.shiftKey);
    }
    drag = null;
  });
  viewport.addEventListener('wheel', (event) => {
    event.preventDefault();
    const box = viewport.getBoundingClientRect();
    const mx = event.clientX - box.left, my = event.clientY - box.top;
    const factor = Math.exp(-event.deltaY * 0.0015);
    const zoom = Math.max(0.05, Math.min(32, state.zoom * factor));
    state.panX = mx - ((mx - state.panX) * zoom) / state.zoom;
    state.panY = my - ((my - state.panY) * zoom) / state.zoom;
    state.zoom = zoom;
    applyTransform();
  }, { passive: false });
  viewport.addEventListener('dblclick', fitToViewport);
}

function bindViewGrid() {
  const grid = $('view-grid');
  let dragging = false;
  const pick = (event) => {
    const rect = grid.getBoundingClientRect();
    const cell = Math.floor(Math.min(grid.width / data.nu, grid.height / data.nv));
    const x = ((event.clientX - rect.left) / rect.width) * grid.width, y = ((event.clientY - rect.top) / rect.height) * grid.height;
    setView(Math.floor(x / cell), Math.floor(y / cell));
  };
  grid.addEventListener('mousedown', (event) => { dragging = true; pick(event); });
  grid.addEventListener('mousemove', (event) => { if (dragging) pick(event); });
  window.addEventListener('mouseup', () => { dragging = false; });
}

function bindControls() {
  for (const name of SLIDERS) {
    const slider = $(name);
    slider.addEventListener('pointerdown', remember);
    slider.addEventListener('keydown', (event) => { if (!event.repeat) remember(); });
    slider.addEventListener('input', () => {
      state.params[name] = Number(slider.value);
      document.querySelector(`output[for=${name}]`).value = slider.value;
      paramsChanged(name);
    });
  }
  $('space').addEventListener('change', () => { remember(); state.params.space = $('space').value; paramsChanged('space'); });
  for (const radio of document.querySelectorAll('input[name=show]')) {
    radio.addEventListener('change', () => {
      state.show = radio.value;
      const range = state.show === 'disparity' ? data.disparityRange : state.show === 'confidence' ? data.confidenceRange : null;
      $('colour-bar-box').classList.toggle('visible', !!range);
      if (range) { $('bar-min').textContent = range.min.toFixed(2); $('bar-max').textContent = range.max.toFixed(2); }
      requestDraw('show');
    });
  }
  for (const radio of document.querySelectorAll('input[name=tool]')) radio.addEventListener('change', () => { state.tool = radio.value; });
  $('boundaries').addEventListener('change', () => { state.boundaries = $('boundaries').checked; requestDraw('boundaries'); });
  $('highlight').addEventListener('change', () => { state.highlight = $('highlight').checked; requestDraw('highlight'); });
  $('clear').addEventListener('click', () => { remember(); state.selected.fill(0); selectionChanged(); });
  $('undo').addEventListener('click', undo);
  $('redo').addEventListener('click', redo);
  $('refocus').addEventListener('change', () => { state.refocus.on = $('refocus').checked; requestFullRefocus('refocus'); });
  $('all-in-focus').addEventListener('change', () => { state.refocus.allInFocus = $('all-in-focus').checked; requestFullRefocus('refocus'); });
  // Dragging previews with every other view (render.js refocusedImage); letting go sums them all.
  $('focus').addEventListener('input', () => {
    state.refocus.disparity = Number($('focus').value);
    state.refocus.coarse = true;
    document.querySelector('output[for=focus]').value = $('focus').value;
    requestDraw('focus');
  });
  $('focus').addEventListener('change', () => requestFullRefocus('focus-release'));
  $('export').addEventListener('click', exportEdit);
  window.addEventListener('keydown', (event) => {
    if (event.target instanceof HTMLInputElement || event.target instanceof HTMLSelectElement) return;
    const moves = { ArrowLeft: [-1, 0], ArrowRight: [1, 0], ArrowUp: [0, -1], ArrowDown: [0, 1] };
    if (moves[event.key]) {
      event.preventDefault();
      setView(state.view.u + moves[event.key][0], state.view.v + moves[event.key][1]);
    } else if ((event.ctrlKey || event.metaKey) && event.key === 'z') {
      undo();
    } else if ((event.ctrlKey || event.metaKey) && event.key === 'y') {
      redo();
    }
  });
  window.addEventListener('resize', fitToViewport);
}

// What the data allows: no labels -> no selection or edit; no disparity -> no depth view or similar-depth tool.
function enableControls() {
  const labelled = !!data.labels;
  for (const id of ['selection-tools', 'edit']) $(id).disabled = !labelled;
  $('export').disabled = !labelled;
  $('boundaries').disabled = $('highlight').disabled = !labelled;
  $('show-disparity').disabled = !data.disparity;
  $('tool-depth').disabled = !(data.disparity && labelled);
  $('show-confidence').disabled = !data.confidence;
  $('all-in-focus').disabled = !data.disparity;
  if (data.disparityRange) {
    const reach = Math.max(Math.abs(data.disparityRange.min), Math.abs(data.disparityRange.max), 0.5);
    $('focus').min = (-Math.ceil(reach * 10) / 10).toString();
    $('focus').max = (Math.ceil(reach * 10) / 10).toString();
  }
  updateButtons();
}

async function main() {
  try {
    await load();
  } catch (error) {
    $('status').textContent = `could not load: ${error.message}`;
    return;
  }
  const canvas = $('view');
  canvas.width = data.width;
  canvas.height = data.height;
  $('input-name').textContent = `${data.meta.input} · ${data.nu}x${data.nv} views of ${data.width}x${data.height}` +
                                (data.labels ? '' : ' · no labels: viewing only');
  $('view-grid').width = $('view-grid').height = 120;
  drawColourBar($('colour-bar'));
  enableControls();
  bindViewport();
  bindViewGrid();
  bindControls();
  fitToViewport();
  selectionChanged();
  paramsChanged(null);
  $('status').textContent = `loaded in ${(window.lfspStats.loadMs / 1000).toFixed(2)} s`;
  requestAnimationFrame(() => { window.lfspStats.ready = true; });
  // Packing the rays for refocusing takes tens of milliseconds on 9x9x512x512: done while the page is idle, not in
  // the frame of the first refocus.
  const whenIdle = window.requestIdleCallback || ((callback) => setTimeout(callback, 200));
  whenIdle(() => packedViews(data));
}

main();
