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
// other view in each direction (25 of 9x9, spanning the same aperture) and every other pixel in each direction are
// summed; letting go sums all at full resolution.
function refocusedImage(data, state) {
  const { coarse, allInFocus, disparity } = state.refocus;
  const key = `${allInFocus ? 'aif' : disparity}/${coarse}/${state.selectionVersion}/${state.editVersion}`;
  if (state.refocusCache && state.refocusCache.key === key) return state.refocusCache.rgb;
  const { width: W, height: H, nu, nv, views } = data;
  const N = W * H, uc = Math.floor(nu / 2), vc = Math.floor(nv / 2);
  const sum = new Float32Array(N * 3), count = new Uint16Array(N);
  const perPixel = allInFocus && data.disparity;
  const step = coarse && !perPixel ? 2 : 1;  // views and pixels
  const evenIfCoarse = (i) => i + (i % step);
  const edit = state.edit && data.labels ? state.edit : null;
  const selected = state.selected, labels = data.labels, colour = [0, 0, 0];
  // Adds ray q (edited when selected) to pixel p.
  const add = (p, q) => {
    let r = views[3 * q], g = views[3 * q + 1], b = views[3 * q + 2];
    if (edit && selected[labels[q]] === 1) {
      edit.apply(r, g, b, edit, 1, colour);
      r = colour[0]; g = colour[1]; b = colour[2];
    }
    sum[3 * p] += r; sum[3 * p + 1] += g; sum[3 * p + 2] += b;
    count[p] += 1;
  };
  for (let v = vc % step; v < nv; v += step) for (let u = uc % step; u < nu; u += step) {
    const base = (v * nu + u) * N;
    if (perPixel) {
      for (let y = 0; y < H; ++y) for (let x = 0; x < W; ++x) {
        const p = y * W + x, d = data.disparity[p];
        const sx = Math.round(x - (u - uc) * d), sy = Math.round(y - (v - vc) * d);
        if (sx >= 0 && sy >= 0 && sx < W && sy < H) add(p, base + sy * W + sx);
      }
      continue;
    }
    // One disparity: the whole view moves by one whole-pixel shift (nearest neighbour, as a preview).
    const dx = Math.round((u - uc) * disparity), dy = Math.round((v - vc) * disparity);
    const x0 = evenIfCoarse(Math.max(0, dx)), x1 = Math.min(W, W + dx);
    for (let y = evenIfCoarse(Math.max(0, dy)); y < Math.min(H, H + dy); y += step) {
      for (let p = y * W + x0, q = base + (y - dy) * W + x0 - dx, end = y * W + x1; p < end; p += step, q += step) {
        if (edit && selected[labels[q]] === 1) { add(p, q); continue; }
        sum[3 * p] += views[3 * q]; sum[3 * p + 1] += views[3 * q + 1]; sum[3 * p + 2] += views[3 * q + 2];
        count[p] += 1;
      }
    }
  }
  const rgb = new Uint8ClampedArray(N * 3);
  for (let y = 0; y < H; ++y) for (let x = 0; x < W; ++x) {
    const p = y * W + x, s = step === 1 ? p : (y - (y % step)) * W + (x - (x % step));  // coarse: 2x2 blocks
    const c = count[s] || 1;
    rgb[3 * p] = sum[3 * s] / c; rgb[3 * p + 1] = sum[3 * s + 1] / c; rgb[3 * p + 2] = sum[3 * s + 2] / c;
  }
  state.refocusCache = { key, rgb };
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
