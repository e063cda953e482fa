// The page's shift-and-sum refocus (apps/view/web/render.js) in node, against the sum written out here ray by ray:
// light fields of 9x9 and 17x17 views (above 257 views the red and blue sums no longer share a 32-bit word), the
// drag's preview (every other view), letting go (all views, adding to the preview's sums), and a preview asked for
// after the whole sum at the same disparity.
//   node refocus_test.mjs WEB_DIR
import path from 'node:path';
import { pathToFileURL } from 'node:url';

const web = process.argv[2];
const { refocusedImage } = await import(pathToFileURL(path.join(web, 'render.js')).href);

function check(condition, message) {
  if (!condition) throw new Error(`FAILED: ${message}`);
  console.log(`ok: ${message}`);
}

function expected(data, d, step) {
  const { nu, nv, width: W, height: H, views } = data;
  const uc = Math.floor(nu / 2), vc = Math.floor(nv / 2), N = W * H;
  const sum = new Float64Array(3 * N), count = new Uint32Array(N);
  for (let v = vc % step; v < nv; v += step) for (let u = uc % step; u < nu; u += step) {
    const dx = Math.round((u - uc) * d), dy = Math.round((v - vc) * d);
    for (let y = 0; y < H; ++y) for (let x = 0; x < W; ++x) {
      const sx = x - dx, sy = y - dy;
      if (sx < 0 || sy < 0 || sx >= W || sy >= H) continue;
      const q = (v * nu + u) * N + sy * W + sx, p = y * W + x;
      for (let c = 0; c < 3; ++c) sum[3 * p + c] += views[3 * q + c];
      count[p] += 1;
    }
  }
  return { sum, count };
}

for (const [n, low, high] of [[9, 0, 255], [17, 240, 255]]) {
  const W = 40, H = 30;
  const views = new Uint8Array(n * n * W * H * 3);
  for (let i = 0; i < views.length; ++i) views[i] = low + ((i * 2654435761) >>> 0) % (high - low + 1);
  const data = { nu: n, nv: n, width: W, height: H, views, labels: null, disparity: null };
  const state = { refocus: {}, selectionVersion: 0, editVersion: 0, selected: new Uint8Array(1), edit: null };
  const steps = [[1.5, true, 2, 'dragged'], [1.5, false, 1, 'let go'], [1.5, true, 1, 'preview after the whole sum'],
                 [-0.75, true, 2, 'dragged'], [-0.75, false, 1, 'let go']];
  for (const [d, coarse, step, what] of steps) {
    if (what.startsWith('preview')) state.refocusCache = null;
    state.refocus = { coarse, allInFocus: false, disparity: d };
    const rgb = refocusedImage(data, state);
    const { sum, count } = expected(data, d, step);
    let worst = 0;
    for (let p = 0; p < W * H; ++p)
      for (let c = 0; c < 3; ++c) if (count[p]) worst = Math.max(worst, Math.abs(rgb[3 * p + c] - sum[3 * p + c] / count[p]));
    check(worst <= 0.5, `${n}x${n} views, d = ${d}, ${what}: within ${worst.toFixed(2)} of 255`);
  }
}
