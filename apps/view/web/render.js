// Drawing the page's pictures from the loaded arrays: the current view (or depth, confidence, a refocused image)
// with the previewed edit and the overlays, the two EPIs, the view grid and the colour bar.

import { TURBO } from './colour.js';

// Everything drawn depends on `data` (loaded once) and `state` (what the user chose); see app.js.

function isSelected(state, label) { return state.selected[label] === 1; }

// Per-pixel edit strength of view `viewIndex` with the feather ramp (chamfer distance to the selection, within the
// view), cached until the selection, the feather or the view change.
function featherStrength(data, state, viewIndex) {
  const key = `${viewIndex}/${state.selectionVersion}/${state.params.feather}`;
  if (state.featherCache && state.featherCache.key === key) return state.featherCache.strength;
  const { width: W, height: H } = data;
  const N = W * H, offset = viewIndex * N, labels = data.labels;
  const distance = new Float32Array(N);
  for (let p = 0; p < N; ++p) distance[p] = isSelected(state, labels[offset + p]) ? 0 : 1e9;
  const D = Math.SQRT2;
  for (let y = 0; y < H; ++y) for (let x = 0; x < W; ++x) {
    const p = y * W + x;
    let d = distance[p];
    if (x > 0) d = Math.min(d, distance[p - 1] + 1);
    if (y > 0) {
      d = Math.min(d, distance[p - W] + 1);
      if (x > 0) d = Math.min(d, distance[p - W - 1] + D);
      if (x < W - 1) d = Math.min(d, distance[p - W + 1] + D);
    }
    distance[p] = d;
  }
  for (let y = H - 1; y >= 0; --y) for (let x = W - 1; x >= 0; --x) {
    const p = y * W + x;
    let d = distance[p];
    if (x < W - 1) d = Math.min(d, distance[p + 1] + 1);
    if (y < H - 1) {
      d = Math.min(d, distance[p + W] + 1);
      if (x < W - 1) d = Math.min(d, distance[p + W + 1] + D);
      if (x > 0) d = Math.min(d, distance[p + W - 1] + D);
    }
    distance[p] = d;
  }
  const feather = state.params.feather;
  const strength = new Float32Array(N);
  for (let p = 0; p < N; ++p) {
    const d = distance[p];
    strength[p] = d === 0 ? 1 : d <= feather ? 1 - d / (feather + 1) : 0;
  }
  state.featherCache = { key, strength };
  return strength;
}

function paintMap(values, range, rgba) {
  const span = range.max > range.min ? range.max - range.min : 1;
  for (let p = 0; p < values.length; ++p) {
    const v = values[p];
    if (!Number.isFinite(v)) { rgba[4 * p] = rgba[4 * p + 1] = rgba[4 * p + 2] = 0; rgba[4 * p + 3] = 255; continue; }
    const i = 3 * Math.max(0, Math.min(255, Math.round(((v - range.min) / span) * 255)));
    rgba[4 * p] = TURBO[i]; rgba[4 * p + 1] = TURBO[i + 1]; rgba[4 * p + 2] = TURBO[i + 2]; rgba[4 * p + 3] = 255;
  }
}

// Shift-and-sum over every view at one disparity, or at each pixel's own (all in focus), with the edit applied to
// selected rays; cached until any of those change. While the slider is dragged (state.refocus.coarse) only every
// other view in each direction is summed (25 of 9x9, spanning the same aperture); letting go sums them all.
export function refocusedImage(data, state) {
  const { coarse, allInFocus, disparity } = state.refocus;
  const key = `${allInFocus ? 'aif' : disparity}/${coarse}/${state.selectionVersion}/${state.editVersion}`;
  if (state.refocusCache && state.refocusCache.key === key) return state.refocusCache.rgb;
  const rays = editedPackedRays(data, state);
  const rgb = allInFocus && data.disparity ? allInFocusImage(data, rays.words, coarse)
                                           : shiftAndSum(data, state, rays, disparity, coarse);
  state.refocusCache = { key, rgb };
  return rgb;
}

// Every ray packed in one 32-bit word (red | green << 8 | blue << 16), so that a sum adds two channels at once
// (shiftAndSum). Built once, on the first refocus or when the page is idle after loading (app.js).
export function packedViews(data) {
  if (data.packedViews) return data.packedViews;
  const views = data.views, rays = views.length / 3, words = new Uint32Array(rays);
  for (let q = 0; q < rays; ++q) words[q] = views[3 * q] | (views[3 * q + 1] << 8) | (views[3 * q + 2] << 16);
  data.packedViews = words;
  return words;
}

const byte = (value) => (value <= 0 ? 0 : value >= 255 ? 255 : Math.round(value));

// The packed rays with the edit applied to every selected ray, so that refocusing sums edited colours: the views'
// own words when nothing is edited, else a copy, rebuilt when the selection or the edit changes (not when the focus
// does). The selected rays are listed once per selection, so an edit change recolours only them. `version` names
// the content, for the sums kept between frames.
function editedPackedRays(data, state) {
  const views = data.views, labels = data.labels, selected = state.selected, base = packedViews(data);
  if (!state.edit || !labels || !selected.includes(1)) return { words: base, version: 'views' };
  const key = `${state.selectionVersion}/${state.editVersion}`;
  const cache = state.editedRaysCache || (state.editedRaysCache = {});
  if (cache.key === key) return { words: cache.words, version: key };
  if (cache.selectionVersion !== state.selectionVersion) {
    let count = 0;
    for (let q = 0; q < labels.length; ++q) count += selected[labels[q]];
    const rays = new Uint32Array(count);
    for (let q = 0, n = 0; q < labels.length; ++q) if (selected[labels[q]] === 1) rays[n++] = q;
    cache.rays = rays;
    cache.selectionVersion = state.selectionVersion;
  }
  if (!cache.words) cache.words = new Uint32Array(base.length);
  const words = cache.words, edit = state.edit, colour = [0, 0, 0];
  words.set(base);
  for (const q of cache.rays) {
    edit.apply(views[3 * q], views[3 * q + 1], views[3 * q + 2], edit, 1, colour);
    words[q] = byte(colour[0]) | (byte(colour[1]) << 8) | (byte(colour[2]) << 16);
  }
  cache.key = key;
  return { words, version: key };
}

// The views used for a refocus: all, or every other one in each direction through the centre view.
function refocusViews(data, coarse) {
  const step = coarse ? 2 : 1, uc = Math.floor(data.nu / 2), vc = Math.floor(data.nv / 2);
  const us = [], vs = [];
  for (let u = uc % step; u < data.nu; u += step) us.push(u);
  for (let v = vc % step; v < data.nv; v += step) vs.push(v);
  return { us, vs, uc, vc };
}

// One disparity: every view moves by one whole-pixel shift (nearest neighbour, as a preview), the same offset for
// all its rays, so each row of a view is added in one tight loop. Rays are packed words (packedViews) and summed two
// channels per add: red and blue in the 16-bit halves of one sum, green in another, as long as 255 times the views
// fits in 16 bits (up to 257 views: 15x15 does, 17x17 is summed a channel per add). How many views reach a pixel is
// the product of how many reach its column (they depend on u only) and its row (v only), so nothing is counted per
// ray.
function shiftAndSum(data, state, rays, disparity, coarse) {
  const { width: W, height: H } = data;
  const N = W * H, words = rays.words;
  // The sums are kept: letting go of the slider adds only the views the drag's preview left out.
  const key = `${disparity}/${rays.version}`;
  if (!state.refocusSums || state.refocusSums.redBlue.length !== N) {
    state.refocusSums = { redBlue: new Uint32Array(N), green: new Uint32Array(N), blue: new Uint32Array(N), key: null,
                          summed: new Set() };
  }
  const sums = state.refocusSums, { redBlue, green, blue } = sums;
  if (sums.key !== key) {
    redBlue.fill(0);
    green.fill(0);
    blue.fill(0);
    sums.key = key;
    sums.summed.clear();
  }
  // The sums hold the preview's views or all of them (the preview's are a subset), never another set; a preview
  // asked for after all views were summed at this disparity is the whole sum.
  const allViews = data.nu * data.nv;
  const halves = allViews * 255 <= 0xffff;  // red and blue share a sum (else redBlue holds red alone)
  const { us, vs, uc, vc } = refocusViews(data, coarse && sums.summed.size < allViews);
  for (const v of vs) for (const u of us) {
    const view = v * data.nu + u;
    if (sums.summed.has(view)) continue;
    sums.summed.add(view);
    const dx = Math.round((u - uc) * disparity), dy = Math.round((v - vc) * disparity);
    const x0 = Math.max(0, dx), x1 = Math.min(W, W + dx);
    if (x1 <= x0) continue;
    const offset = view * N - dy * W - dx;  // pixel p of the sum takes ray p + offset
    for (let y = Math.max(0, dy); y < Math.min(H, H + dy); ++y) {
      const end = y * W + x1;
      if (halves) {
        for (let p = y * W + x0; p < end; ++p) {
          const word = words[p + offset];
          redBlue[p] += word & 0x00ff00ff;
          green[p] += (word >>> 8) & 0xff;
        }
      } else {
        for (let p = y * W + x0; p < end; ++p) {
          const word = words[p + offset];
          redBlue[p] += word & 0xff;
          green[p] += (word >>> 8) & 0xff;
          blue[p] += (word >>> 16) & 0xff;
        }
      }
    }
  }
  const columnCounts = new Uint16Array(W), rowCounts = new Uint16Array(H);
  for (const u of us) {
    const dx = Math.round((u - uc) * disparity);
    for (let x = Math.max(0, dx); x < Math.min(W, W + dx); ++x) columnCounts[x] += 1;
  }
  for (const v of vs) {
    const dy = Math.round((v - vc) * disparity);
    for (let y = Math.max(0, dy); y < Math.min(H, H + dy); ++y) rowCounts[y] += 1;
  }
  const rgb = new Uint8ClampedArray(3 * N);
  for (let y = 0; y < H; ++y) for (let x = 0; x < W; ++x) {
    const p = y * W + x, c = columnCounts[x] * rowCounts[y];
    if (c === 0) continue;
    const scale = 1 / c;
    rgb[3 * p] = (halves ? redBlue[p] & 0xffff : redBlue[p]) * scale;
    rgb[3 * p + 1] = green[p] * scale;
    rgb[3 * p + 2] = (halves ? redBlue[p] >>> 16 : blue[p]) * scale;
  }
  return rgb;
}

// All in focus: each pixel sums the rays (packed words) of its own disparity, ray by ray.
function allInFocusImage(data, words, coarse) {
  const { width: W, height: H } = data;
  const N = W * H;
  const sum = new Float32Array(N * 3), count = new Uint16Array(N);
  const { us, vs, uc, vc } = refocusViews(data, coarse);
  for (const v of vs) for (const u of us) {
    const base = (v * data.nu + u) * N;
    for (let y = 0; y < H; ++y) for (let x = 0; x < W; ++x) {
      const p = y * W + x, d = data.disparity[p];
      const sx = Math.round(x - (u - uc) * d), sy = Math.round(y - (v - vc) * d);
      if (sx < 0 || sy < 0 || sx >= W || sy >= H) continue;
      const word = words[base + sy * W + sx];
      sum[3 * p] += word & 0xff; sum[3 * p + 1] += (word >>> 8) & 0xff; sum[3 * p + 2] += (word >>> 16) & 0xff;
      count[p] += 1;
    }
  }
  const rgb = new Uint8ClampedArray(N * 3);
  for (let p = 0; p < N; ++p) {
    const c = count[p] || 1;
    rgb[3 * p] = sum[3 * p] / c; rgb[3 * p + 1] = sum[3 * p + 1] / c; rgb[3 * p + 2] = sum[3 * p + 2] / c;
  }
  return rgb;
}

// The main picture into `image` (ImageData of the view's size).
export function drawView(data, state, image) {
  const { width: W, height: H } = data;
  const N = W * H, rgba = image.data;
  if (state.show === 'disparity' && data.disparity) return paintMap(data.disparity, data.disparityRange, rgba);
  if (state.show === 'confidence' && data.confidence) return paintMap(data.confidence, data.confidenceRange, rgba);
  const viewIndex = state.view.v * data.nu + state.view.u;
  const refocusing = state.refocus.on || state.refocus.allInFocus;
  const offset = viewIndex * N;
  const source = refocusing ? refocusedImage(data, state) : data.views.subarray(offset * 3, (offset + N) * 3);
  const labels = data.labels;
  const edit = refocusing ? null : state.edit;
  const strength = edit && labels && state.params.feather > 0 ? featherStrength(data, state, viewIndex) : null;
  const colour = [0, 0, 0];
  for (let p = 0; p < N; ++p) {
    let r = source[3 * p], g = source[3 * p + 1], b = source[3 * p + 2];
    if (edit && labels) {
      const s = strength ? strength[p] : isSelected(state, labels[offset + p]) ? 1 : 0;
      if (s > 0) {
        edit.apply(r, g, b, edit, s, colour);
        r = colour[0]; g = colour[1]; b = colour[2];
      }
    }
    rgba[4 * p] = r; rgba[4 * p + 1] = g; rgba[4 * p + 2] = b; rgba[4 * p + 3] = 255;
  }
  if (labels && !refocusing) drawOverlays(data, state, labels, offset, W, H, rgba);
}

// Superpixel boundaries (light) and the selection's outline (cyan) on a view or EPI laid out as W x H pixels whose
// label is labelAt(x, y).
function drawOverlays(data, state, labels, offset, W, H, rgba) {
  for (let y = 0; y < H; ++y) for (let x = 0; x < W; ++x) {
    const p = y * W + x, label = labels[offset + p];
    const right = x + 1 < W ? labels[offset + p + 1] : label;
    const below = y + 1 < H ? labels[offset + p + W] : label;
    const left = x > 0 ? labels[offset + p - 1] : label;
    const above = y > 0 ? labels[offset + p - W] : label;
    const selected = isSelected(state, label);
    if (state.highlight && selected &&
        !(isSelected(state, right) && isSelected(state, below) && isSelected(state, left) && isSelected(state, above))) {
      rgba[4 * p] = 0; rgba[4 * p + 1] = 255; rgba[4 * p + 2] = 255;
    } else if (state.boundaries && (label !== right || label !== below)) {
      rgba[4 * p] = (rgba[4 * p] + 255) >> 1; rgba[4 * p + 1] = (rgba[4 * p + 1] + 255) >> 1;
      rgba[4 * p + 2] = (rgba[4 * p + 2] + 255) >> 1;
    }
  }
}

// One EPI: `count` lines of `length` pixels, line i taken from view viewOf(i) along the cursor's row (horizontal)
// or column (vertical), with the edit and the overlays; returned as ImageData (lines as rows).
export function drawEpi(data, state, horizontal) {
  const { width: W, height: H, nu, nv, views } = data;
  const N = W * H, count = horizontal ? nu : nv, length = horizontal ? W : H;
  const rgb = new Uint8ClampedArray(count * length * 3);
  const epiLabels = data.labels ? new Int32Array(count * length) : null;
  for (let i = 0; i < count; ++i) {
    const viewIndex = horizontal ? state.view.v * nu + i : i * nu + state.view.u;
    for (let t = 0; t < length; ++t) {
      const q = viewIndex * N + (horizontal ? state.cursor.y * W + t : t * W + state.cursor.x);
      const e = i * length + t;
      rgb[3 * e] = views[3 * q]; rgb[3 * e + 1] = views[3 * q + 1]; rgb[3 * e + 2] = views[3 * q + 2];
      if (epiLabels) epiLabels[e] = data.labels[q];
    }
  }
  const image = new ImageData(length, count);
  const colour = [0, 0, 0], edit = state.edit;
  for (let e = 0; e < count * length; ++e) {
    let r = rgb[3 * e], g = rgb[3 * e + 1], b = rgb[3 * e + 2];
    if (edit && epiLabels && isSelected(state, epiLabels[e])) {
      edit.apply(r, g, b, edit, 1, colour);
      r = colour[0]; g = colour[1]; b = colour[2];
    }
    image.data[4 * e] = r; image.data[4 * e + 1] = g; image.data[4 * e + 2] = b; image.data[4 * e + 3] = 255;
  }
  if (epiLabels) drawOverlays(data, state, epiLabels, 0, length, count, image.data);
  return image;
}

export function drawViewGrid(data, state, canvas) {
  const { nu, nv } = data, context = canvas.getContext('2d');
  const cell = Math.floor(Math.min(canvas.width / nu, canvas.height / nv));
  context.fillStyle = '#111';
  context.fillRect(0, 0, canvas.width, canvas.height);
  for (let v = 0; v < nv; ++v) for (let u = 0; u < nu; ++u) {
    const current = u === state.view.u && v === state.view.v;
    const centre = u === Math.floor(nu / 2) && v === Math.floor(nv / 2);
    context.fillStyle = current ? '#9cf' : centre ? '#556' : '#333';
    context.fillRect(u * cell + 1, v * cell + 1, cell - 2, cell - 2);
  }
  return cell;
}

export function drawColourBar(canvas) {
  const context = canvas.getContext('2d'), bar = context.createImageData(256, 1);
  for (let i = 0; i < 256; ++i) {
    bar.data[4 * i] = TURBO[3 * i]; bar.data[4 * i + 1] = TURBO[3 * i + 1]; bar.data[4 * i + 2] = TURBO[3 * i + 2];
    bar.data[4 * i + 3] = 255;
  }
  canvas.width = 256; canvas.height = 1;
  context.putImageData(bar, 0, 0);
}
