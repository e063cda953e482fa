// The viewer in a real browser (Debian's chromium, headless, driven by puppeteer-core):
//  1. on the bundled sample: click a superpixel, move the hue slider with the keyboard, and check in the page's
//     canvas that pixels of that superpixel changed in two different views while every other pixel stayed; then
//     export, run the exported `lfsp recolor` command line and compare the two light fields byte for byte;
//  2. on a `lfsp pipeline` output folder of the sample: the depth and confidence are shown;
//  3. on HCI antinous (9x9x512x512, when the shared data is there): the load time and the time from a slider
//     change to the frame that shows it (printed, not asserted).
//   node browser_test.mjs LFSP SAMPLE_LIGHT_FIELD WORK_DIR [ANTINOUS_DIR] [--screenshots DIR]

import fs from 'node:fs';
import path from 'node:path';
import puppeteer from 'puppeteer-core';
import { expectedRefocus, worstDifference } from './shift_and_sum.mjs';
import { check, runLfsp, startViewer, stopViewer } from './viewer_process.mjs';

const args = process.argv.slice(2);
const screenshotIndex = args.indexOf('--screenshots');
const screenshots = screenshotIndex >= 0 ? args.splice(screenshotIndex, 2)[1] : null;
const [lfsp, sample, work, antinous] = args;
fs.mkdirSync(work, { recursive: true });

const browser = await puppeteer.launch({
  executablePath: process.env.CHROMIUM || '/usr/bin/chromium',
  headless: true,
  // Root in a container: no sandbox; a small /dev/shm: use /tmp.
  args: ['--no-sandbox', '--disable-dev-shm-usage', '--disable-gpu', '--window-size=1400,900'],
  defaultViewport: { width: 1400, height: 900 },
});

async function openViewer(viewer) {
  const page = await browser.newPage();
  page.on('pageerror', (error) => { throw new Error(`page error: ${error.message}`); });
  await page.goto(viewer.url);
  await page.waitForFunction(() => window.lfspStats && window.lfspStats.ready, { timeout: 120000 });
  return page;
}

async function labelsOf(viewer) {
  const meta = await (await fetch(`${viewer.url}api/meta`)).json();
  const bytes = await (await fetch(`${viewer.url}api/labels`)).arrayBuffer();
  return { meta, labels: meta.label_bytes === 2 ? new Uint16Array(bytes) : new Int32Array(bytes) };
}

// Screen position of view pixel (x, y) and of a cell of the view grid.
async function viewPixelOnScreen(page, meta, x, y) {
  const rect = await page.$eval('#view', (canvas) => canvas.getBoundingClientRect().toJSON());
  return { x: rect.left + ((x + 0.5) / meta.width) * rect.width, y: rect.top + ((y + 0.5) / meta.height) * rect.height };
}

async function goToView(page, meta, u, v) {
  const rect = await page.$eval('#view-grid', (grid) => grid.getBoundingClientRect().toJSON());
  const cell = Math.floor(Math.min(120 / meta.nu, 120 / meta.nv)) * (rect.width / 120);
  await page.mouse.click(rect.left + (u + 0.5) * cell, rect.top + (v + 0.5) * cell);
  await page.waitForFunction((text) => document.getElementById('view-name').textContent.startsWith(text), {},
                             `view (${u}, ${v})`);
  await nextFrame(page);
}

// Puts the cursor at a fraction of the view (the EPIs follow it).
async function pointAt(page, meta, fx, fy) {
  const point = await viewPixelOnScreen(page, meta, Math.floor(fx * meta.width), Math.floor(fy * meta.height));
  await page.mouse.move(point.x, point.y);
  await nextFrame(page);
}

function nextFrame(page) {
  return page.evaluate(() => new Promise((resolve) => requestAnimationFrame(() => requestAnimationFrame(resolve))));
}

async function canvasPixels(page) {
  return page.$eval('#view', (canvas) =>
    Array.from(canvas.getContext('2d').getImageData(0, 0, canvas.width, canvas.height).data));
}

// Presses ArrowRight on a focused slider `steps` times, waiting for the frame each press asks for (for the focus
// slider, the frame with every view, 'focus-full', which follows the first); returns the slider-to-frame times the
// page measured: the frames of source `id`, or all of them with `allSources`.
async function stepSlider(page, id, steps, allSources = false) {
  // A change still waiting for its frame (the click that selected a superpixel) would absorb the first press: one
  // frame draws both and is counted as the earlier change's, so the count below would stay one short.
  await nextFrame(page);
  await page.focus(`#${id}`);
  const before = await page.evaluate(() => window.lfspStats.frames.length);
  const last = id === 'focus' ? 'focus-full' : id;
  for (let i = 0; i < steps; ++i) {
    await page.keyboard.press('ArrowRight');
    await page.waitForFunction((n, source, count) =>
      window.lfspStats.frames.slice(n).filter((f) => f.source === source).length >= count, {}, before, last, i + 1);
  }
  await nextFrame(page);
  return page.evaluate((n, source, all) => window.lfspStats.frames.slice(n).filter((f) => all || f.source === source),
                       before, id, allSources);
}

// Drags the slider's thumb with the mouse from its middle, `steps` moves of 8 px, waiting for the frame of each,
// then lets go; returns the frames (sources `id` while dragging, `id`-release after).
async function dragSlider(page, id, steps) {
  await nextFrame(page);  // as in stepSlider: no earlier change left to absorb the first move
  const box = await page.$eval(`#${id}`, (slider) => slider.getBoundingClientRect().toJSON());
  const y = box.top + box.height / 2;
  let x = box.left + box.width / 2;
  const before = await page.evaluate(() => window.lfspStats.frames.length);
  await page.mouse.move(x, y);
  await page.mouse.down();
  for (let i = 1; i <= steps; ++i) {
    x += 8;
    await page.mouse.move(x, y);
    await page.waitForFunction(
      (n, source, count) => window.lfspStats.frames.slice(n).filter((f) => f.source === source).length >= count, {},
      before, id, i);
  }
  await page.mouse.up();
  await page.waitForFunction((n, source) => window.lfspStats.frames.slice(n).some((f) => f.source === source), {},
                             before, `${id}-release`);
  if (id === 'focus')  // every view follows in the next frame
    await page.waitForFunction((n) => window.lfspStats.frames.slice(n).some((f) => f.source === 'focus-full'), {},
                               before);
  await nextFrame(page);
  return page.evaluate((n) => window.lfspStats.frames.slice(n), before);
}

// The label at centre-view pixel (x, y) of the largest superpixel there (a big target, well inside its edges).
function largestCentreLabel(meta, labels) {
  const N = meta.width * meta.height;
  const centre = (Math.floor(meta.nv / 2) * meta.nu + Math.floor(meta.nu / 2)) * N;
  const area = new Map();
  for (let p = 0; p < N; ++p) area.set(labels[centre + p], (area.get(labels[centre + p]) || 0) + 1);
  const [label] = [...area.entries()].filter(([l]) => l <= meta.largest_label).sort((a, b) => b[1] - a[1])[0];
  // A pixel of that label whose 5x5 neighbourhood is all that label.
  for (let y = 2; y < meta.height - 2; ++y) for (let x = 2; x < meta.width - 2; ++x) {
    let inside = true;
    for (let dy = -2; dy <= 2 && inside; ++dy) for (let dx = -2; dx <= 2; ++dx)
      if (labels[centre + (y + dy) * meta.width + x + dx] !== label) { inside = false; break; }
    if (inside) return { label, x, y };
  }
  throw new Error('no superpixel with an interior');
}

// Median and largest of each measure: `ms` to the frame drawn, `presentedMs` to the next frame (after it was shown).
function timings(frames) {
  // A frame whose next frame has not begun yet has no presentedMs: it is left out of the 'shown' figures.
  const of = (key) => frames.map((f) => f[key]).filter((value) => typeof value === 'number');
  return { drawn_median: +median(of('ms')).toFixed(1), drawn_max: +Math.max(...of('ms')).toFixed(1),
           shown_median: +median(of('presentedMs')).toFixed(1), shown_max: +Math.max(...of('presentedMs')).toFixed(1),
           n: frames.length };
}

function median(values) {
  const sorted = [...values].sort((a, b) => a - b);
  return sorted[Math.floor(sorted.length / 2)];
}

// The refocused picture against shift-and-sum written out ray by ray (shift_and_sum.mjs).
async function checkRefocus(page, viewer, meta) {
  const views = new Uint8Array(await (await fetch(`${viewer.url}api/views`)).arrayBuffer());
  await page.click('#refocus');
  // Two settings within the slider's range (the light field's disparity range): dragged, let go, and another.
  const { min, max } = await page.$eval('#focus', (slider) => ({ min: Number(slider.min), max: Number(slider.max) }));
  const near = min + 0.8 * (max - min), far = min + 0.25 * (max - min);
  await nextFrame(page);
  for (const [wanted, release] of [[near, false], [near, true], [far, true]]) {
    const before = await page.evaluate(() => window.lfspStats.frames.length);
    const d = await page.$eval('#focus', (slider, value, released) => {
      slider.value = String(value);
      slider.dispatchEvent(new Event('input'));
      if (released) slider.dispatchEvent(new Event('change'));
      return Number(slider.value);  // as the slider's step rounds it
    }, wanted, release);
    // Letting go draws the preview at once and every view in the next frame ('focus-full').
    await page.waitForFunction((n, source) => window.lfspStats.frames.slice(n).some((f) => f.source === source), {},
                               before, release ? 'focus-full' : 'focus');
    await nextFrame(page);
    const pixels = await canvasPixels(page);
    const worst = worstDifference(pixels, 4, expectedRefocus(meta, views, d, release ? 1 : 2));
    check(worst <= 1, `refocus at d = ${d} (${release ? 'all views' : 'dragging: 25 views'}) matches shift-and-sum ` +
                      `to ${worst.toFixed(2)} of 255`);
  }
  await page.$eval('#focus', (slider) => { slider.value = '0'; slider.dispatchEvent(new Event('change')); });
  await page.click('#refocus');
  await nextFrame(page);
}

async function sampleTest() {
  const exportDir = path.join(work, 'export');
  const viewer = await startViewer(lfsp, [sample, '--out', exportDir]);
  try {
    const page = await openViewer(viewer);
    const { meta, labels } = await labelsOf(viewer);
    const N = meta.width * meta.height;
    // Plain pixels: no boundaries or outline, so only the edit changes them.
    await page.click('#boundaries');
    await page.click('#highlight');
    await checkRefocus(page, viewer, meta);
    const target = largestCentreLabel(meta, labels);
    const point = await viewPixelOnScreen(page, meta, target.x, target.y);
    await page.mouse.click(point.x, point.y);
    await page.waitForFunction(() => document.getElementById('selection-count').textContent.startsWith('1 '));
    check(true, `clicked superpixel ${target.label} at centre-view (${target.x}, ${target.y})`);

    const views = [[Math.floor(meta.nu / 2), Math.floor(meta.nv / 2)], [0, 0]];
    const before = [];
    for (const [u, v] of views) { await goToView(page, meta, u, v); before.push(await canvasPixels(page)); }
    const frames = await stepSlider(page, 'hue', 90);  // 90 key presses of 1 degree
    check(frames.length > 0 && Number(await page.$eval('#hue', (s) => s.value)) === 90, 'hue slider moved to 90');
    for (const [i, [u, v]] of views.entries()) {
      await goToView(page, meta, u, v);
      const after = await canvasPixels(page);
      const offset = (v * meta.nu + u) * N;
      let inside = 0, changedInside = 0, changedOutside = 0;
      for (let p = 0; p < N; ++p) {
        const changed = [0, 1, 2].some((c) => after[4 * p + c] !== before[i][4 * p + c]);
        if (labels[offset + p] === target.label) { inside += 1; if (changed) changedInside += 1; }
        else if (changed) changedOutside += 1;
      }
      check(inside > 0 && changedInside >= 0.5 * inside,
            `view (${u}, ${v}): ${changedInside} of ${inside} selected pixels changed`);
      check(changedOutside === 0, `view (${u}, ${v}): no pixel outside the selection changed`);
    }

    await page.click('#export');
    await page.waitForSelector('#export-result[data-arguments]', { timeout: 120000 });
    const exported = JSON.parse(await page.$eval('#export-result', (e) => e.dataset.arguments));
    check(exported.includes('--label-ids') && exported[exported.indexOf('--label-ids') + 1] === String(target.label) &&
          exported[exported.indexOf('--hue') + 1] === '90', `export gives ${exported.join(' ')}`);
    const commandOut = path.join(work, 'by_command.h5');
    const commandArgs = [...exported];
    commandArgs[commandArgs.indexOf('--out') + 1] = commandOut;
    const run = await runLfsp(lfsp, ['-q', ...commandArgs]);
    check(run.code === 0, `lfsp ${commandArgs.join(' ')} ran (${run.stderr.trim()})`);
    const viewerBytes = fs.readFileSync(path.join(exportDir, 'recolored.h5'));
    const commandBytes = fs.readFileSync(commandOut);
    check(viewerBytes.equals(commandBytes), `exported recolored.h5 and lfsp recolor's output are byte-identical (${viewerBytes.length} bytes)`);
    check(fs.existsSync(path.join(exportDir, 'selection.json')) && fs.existsSync(path.join(exportDir, 'selection_mask.png')),
          'the selection is exported as a label list and a mask');
    // Undo and redo step the hue back and forth (one history entry per key press).
    await page.click('#undo');
    check(Number(await page.$eval('#hue', (slider) => slider.value)) === 89, 'undo returns the hue to 89');
    await page.click('#redo');
    check(Number(await page.$eval('#hue', (slider) => slider.value)) === 90, 'redo sets it to 90 again');
    // Painting from the selected superpixel across the centre view reaches others.
    await page.click('input[name=tool][value=paint]');
    const from = await viewPixelOnScreen(page, meta, target.x, target.y);
    const to = await viewPixelOnScreen(page, meta, meta.width - 1 - target.x, meta.height - 1 - target.y);
    await page.mouse.move(from.x, from.y);
    await page.mouse.down();
    for (let i = 1; i <= 20; ++i) await page.mouse.move(from.x + ((to.x - from.x) * i) / 20, from.y + ((to.y - from.y) * i) / 20);
    await page.mouse.up();
    const painted = await page.$eval('#selection-count', (e) => parseInt(e.textContent, 10));
    check(painted > 1, `painting across the view selected ${painted} superpixels`);
    await page.click('input[name=tool][value=click]');
    await page.click('#undo');
    check(await page.$eval('#selection-count', (e) => e.textContent.startsWith('1 ')), 'undo takes the painting back');

    if (screenshots) {
      await page.click('#boundaries');
      await page.click('#highlight');
      await goToView(page, meta, Math.floor(meta.nu / 2), Math.floor(meta.nv / 2));
      await pointAt(page, meta, 0.45, 0.6);
      await page.screenshot({ path: path.join(screenshots, 'view_sample.png') });
    }
    await page.close();
  } finally {
    stopViewer(viewer);
  }
}

// A `lfsp pipeline` output folder: its segmentation.h5, disparity and confidence are found and shown.
async function pipelineFolderTest() {
  const folder = path.join(work, 'pipeline');
  const run = await runLfsp(lfsp, ['-q', 'pipeline', sample, '--out', folder]);
  check(run.code === 0 && run.stdout.includes(`view:   lfsp view ${folder}`), `lfsp pipeline prints the view command`);
  const viewer = await startViewer(lfsp, [folder, '--out', path.join(work, 'export_pipeline')]);
  try {
    const meta = await (await fetch(`${viewer.url}api/meta`)).json();
    check(meta.input === path.join(folder, 'segmentation.h5') && meta.label_bytes > 0 && meta.has_disparity &&
          meta.has_confidence, 'a pipeline folder gives its segmentation.h5, labels, disparity and confidence');
    const page = await openViewer(viewer);
    const image = await canvasPixels(page);
    for (const show of ['disparity', 'confidence']) {
      await page.click(`input[name=show][value=${show}]`);
      await nextFrame(page);
      const shown = await canvasPixels(page);
      const bar = await page.$eval('#colour-bar-box', (box) => box.classList.contains('visible'));
      check(bar && shown.some((value, i) => value !== image[i]), `shows the ${show} with a colour bar`);
    }
    await page.close();
  } finally {
    stopViewer(viewer);
  }
}

async function antinousTest() {
  const segmentation = path.join(work, 'antinous_segmentation.h5');
  let started = performance.now();
  const segment = await runLfsp(lfsp, ['-q', 'segment', antinous, '--out', segmentation]);
  check(segment.code === 0, `lfsp segment antinous (${((performance.now() - started) / 1000).toFixed(1)} s) ${segment.stderr.trim()}`);
  started = performance.now();
  const viewer = await startViewer(lfsp, [antinous, '--labels', segmentation, '--out', path.join(work, 'export_antinous')]);
  const serverStart = performance.now() - started;
  try {
    const page = await openViewer(viewer);
    const { meta, labels } = await labelsOf(viewer);
    const loadMs = await page.evaluate(() => window.lfspStats.loadMs);
    const target = largestCentreLabel(meta, labels);
    const point = await viewPixelOnScreen(page, meta, target.x, target.y);
    await page.mouse.click(point.x, point.y);
    await page.waitForFunction(() => document.getElementById('selection-count').textContent.startsWith('1 '));
    const hue = await stepSlider(page, 'hue', 30);
    // A feathered edit costs a distance transform per change.
    const feather = await stepSlider(page, 'feather', 3);
    await page.mouse.move(5, 5);
    const viewSwitch = [];
    await page.evaluate(() => document.activeElement.blur());  // arrow keys now move through the views
    for (let i = 0; i < 8; ++i) {
      const n = await page.evaluate(() => window.lfspStats.frames.length);
      await page.keyboard.press(i < 4 ? 'ArrowLeft' : 'ArrowRight');
      await page.waitForFunction((k) => window.lfspStats.frames.length > k, {}, n);
      await nextFrame(page);
      viewSwitch.push(await page.evaluate(() => window.lfspStats.frames.at(-1)));
    }
    // Shift-and-sum (JS on the CPU): dragging sums 25 of the 81 views per frame, letting go all 81.
    const beforeToggle = await page.evaluate(() => window.lfspStats.frames.length);
    await page.click('#refocus');
    await page.waitForFunction((n) => window.lfspStats.frames.slice(n).some((f) => f.source === 'focus-full'), {},
                               beforeToggle);
    await nextFrame(page);  // the frame after it, which records when it was shown
    const toggle = await page.evaluate((n) => window.lfspStats.frames.slice(n), beforeToggle);
    const refocus = await dragSlider(page, 'focus', 6);
    // Keys jump the slider (a change without a drag before it, like a click on its track).
    const jump = await stepSlider(page, 'focus', 6, true);
    await page.click('#refocus');
    const summary = {
      light_field: `${meta.nu}x${meta.nv}x${meta.width}x${meta.height}`,
      server_load_s: +(serverStart / 1000).toFixed(2),
      page_load_s: +(loadMs / 1000).toFixed(2),
      hue_slider_to_frame_ms: timings(hue),
      feather_slider_to_frame_ms: timings(feather),
      view_switch_to_frame_ms: timings(viewSwitch),
      refocus_on_to_frame_ms: timings(toggle.filter((f) => f.source === 'refocus')),
      refocus_on_to_all_views_ms: timings(toggle.filter((f) => f.source === 'focus-full')),
      refocus_drag_to_frame_ms: timings(refocus.filter((f) => f.source === 'focus')),
      refocus_release_to_frame_ms: timings(refocus.filter((f) => f.source === 'focus-release')),
      refocus_release_to_all_views_ms: timings(refocus.filter((f) => f.source === 'focus-full')),
      refocus_jump_to_frame_ms: timings(jump.filter((f) => f.source === 'focus')),
      refocus_jump_to_all_views_ms: timings(jump.filter((f) => f.source === 'focus-full')),
    };
    console.log(`antinous timings: ${JSON.stringify(summary)}`);
    fs.writeFileSync(path.join(work, 'antinous_timings.json'), `${JSON.stringify(summary, null, 2)}\n`);
    if (screenshots) {  // the bust's chest and everything at its depth, more colourful and turned
      await page.click('input[name=tool][value=depth]');
      await page.$eval('#depth-tolerance', (input) => { input.value = '0.15'; });
      const chest = await viewPixelOnScreen(page, meta, Math.floor(0.5 * meta.width), Math.floor(0.62 * meta.height));
      await page.mouse.click(chest.x, chest.y);
      await stepSlider(page, 'hue', 60);
      await stepSlider(page, 'saturation', 16);
      await page.evaluate(() => document.activeElement.blur());
      await pointAt(page, meta, 0.5, 0.45);
      await page.screenshot({ path: path.join(screenshots, 'view_antinous.png') });
    }
    await page.close();
  } finally {
    stopViewer(viewer);
  }
}

try {
  await sampleTest();
  await pipelineFolderTest();
  if (antinous && fs.existsSync(antinous)) await antinousTest();
  else console.log('antinous: shared data not found, timing part skipped');
  console.log('browser test: all checks passed');
} finally {
  await browser.close();
}
