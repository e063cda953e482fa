// The page's shift-and-sum refocus (apps/view/web/render.js) in node, against the sum written out ray by ray
// (shift_and_sum.mjs) on light fields of 9x9 and 17x17 views (above 257 views the red and blue sums no longer share a
// 32-bit word): the drag's preview (every other view), letting go (all views, adding to the preview's sums), and a
// preview asked for after the whole sum at the same disparity.
//   node refocus_test.mjs WEB_DIR
import path from 'node:path';
import { pathToFileURL } from 'node:url';

import { expectedRefocus, worstDifference } from './shift_and_sum.mjs';
import { check } from './viewer_process.mjs';

const web = process.argv[2];
const { refocusedImage } = await import(pathToFileURL(path.join(web, 'render.js')).href);

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
    const worst = worstDifference(refocusedImage(data, state), 3, expectedRefocus(data, views, d, step));
    check(worst <= 0.5, `${n}x${n} views, d = ${d}, ${what}: within ${worst.toFixed(2)} of 255`);
  }
}
