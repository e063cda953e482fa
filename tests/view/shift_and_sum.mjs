// Shift-and-sum written out ray by ray, the reference the viewer's refocus is checked against (browser_test.mjs on
// the page's canvas, refocus_test.mjs on render.js in node): every view (or every `step`-th one in each direction
// through the centre, the drag's preview at step 2) moved by its whole-pixel shift round((u - uc) d),
// round((v - vc) d); `sum` per sample and `count` per pixel of the rays that reach it.
export function expectedRefocus({ nu, nv, width: W, height: H }, views, d, step) {
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

// The largest difference between a picture (`channels` samples per pixel, its first three RGB) and that mean.
export function worstDifference(picture, channels, { sum, count }) {
  let worst = 0;
  for (let p = 0; p < count.length; ++p)
    for (let c = 0; c < 3; ++c)
      if (count[p] > 0) worst = Math.max(worst, Math.abs(picture[channels * p + c] - sum[3 * p + c] / count[p]));
  return worst;
}
