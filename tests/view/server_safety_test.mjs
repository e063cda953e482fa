// `lfsp view`'s server: loopback only by default, nothing but its own routes (no path reaches another file),
// survives malformed requests and a client that goes away mid-download, and fails like every command on a port in
// use or a bad input (one line naming it, exit 2).
// Also: an export with fractional numbers gives a command line that writes the same bytes.
//   node server_safety_test.mjs LFSP SAMPLE_LIGHT_FIELD

import fs from 'node:fs';
import net from 'node:net';
import os from 'node:os';
import path from 'node:path';
import { check, runLfsp, startViewer, stopViewer } from './viewer_process.mjs';

const [lfsp, sample] = process.argv.slice(2);
const work = fs.mkdtempSync(path.join(os.tmpdir(), 'lfsp-view-safety-'));

// Sends raw bytes (no client-side path normalisation) and resolves with what came back before the server closed
// the connection (or after `waitMs`).
function rawRequest(port, bytes, waitMs = 2000) {
  return new Promise((resolve) => {
    const socket = net.connect(port, '127.0.0.1');
    let answer = '';
    socket.on('data', (chunk) => { answer += chunk.toString('latin1'); });
    socket.on('error', () => resolve(answer));
    socket.on('close', () => resolve(answer));
    socket.on('connect', () => socket.write(bytes));
    setTimeout(() => { socket.destroy(); resolve(answer); }, waitMs);
  });
}

function statusOf(answer) {
  const match = answer.match(/^HTTP\/1\.[01] (\d{3})/);
  return match ? Number(match[1]) : null;
}

async function stillServes(viewer, after) {
  const response = await fetch(`${viewer.url}api/meta`);
  check(response.status === 200 && (await response.json()).nu > 0, `still serves after ${after}`);
}

// The listening socket's local address from /proc/net/tcp (hex, little-endian IPv4).
function listeningAddresses(port) {
  const hexPort = port.toString(16).toUpperCase().padStart(4, '0');
  const rows = fs.readFileSync('/proc/net/tcp', 'utf8').split('\n').slice(1);
  return rows.map((row) => row.trim().split(/\s+/))
    .filter((fields) => fields[1] && fields[1].endsWith(`:${hexPort}`) && fields[3] === '0A')
    .map((fields) => fields[1].split(':')[0]);
}

const viewer = await startViewer(lfsp, [sample, '--out', path.join(work, 'export')]);
try {
  check(viewer.host === '127.0.0.1', 'announces the loopback address');
  check(JSON.stringify(listeningAddresses(viewer.port)) === '["0100007F"]', 'listens on 127.0.0.1 only');

  const page = await fetch(viewer.url);
  check(page.status === 200 && (await page.text()).includes('lfsp view'), 'serves the page');

  const sampleName = sample.split('/').pop();
  const outside = ['/../../../../etc/passwd', '/%2e%2e/%2e%2e/%2e%2e/etc/passwd', '//etc/passwd', '/etc/passwd',
                   '/app.js/../../../../etc/passwd', `/${sampleName}`, sample, `/${sample}`,
                   '/api/../../../../etc/passwd', '/api/views/../../../etc/passwd', '/..%2f..%2f..%2fetc%2fpasswd',
                   'http://127.0.0.1/etc/passwd', '/web/app.js', '/CMakeLists.txt'];
  for (const target of outside) {
    const answer = await rawRequest(viewer.port, `GET ${target} HTTP/1.1\r\nHost: x\r\nConnection: close\r\n\r\n`);
    const status = statusOf(answer);
    check((status === 404 || status === 400) && !answer.includes('root:') && !answer.includes('HDF'),
          `refuses ${target} (status ${status})`);
  }

  for (const [name, bytes] of [
    ['garbage bytes', '\x00\x01\x02 not http at all\r\n\r\n'],
    ['a request line without a version', 'GET /\r\n\r\n'],
    ['a header of 100 KB', `GET / HTTP/1.1\r\nX-Long: ${'a'.repeat(100000)}\r\n\r\n`],
    ['a request cut off mid-header', 'GET /api/meta HTTP/1.1\r\nHost: 127.0'],
    ['an export with broken JSON', 'POST /api/export HTTP/1.1\r\nContent-Length: 9\r\nConnection: close\r\n\r\n{"label_i'],
    ['an export of 5 MB', `POST /api/export HTTP/1.1\r\nContent-Length: 5000000\r\nConnection: close\r\n\r\n${'x'.repeat(5000000)}`],
  ]) {
    await rawRequest(viewer.port, bytes, 1000);
    await stillServes(viewer, name);
  }
  const badExport = await fetch(`${viewer.url}api/export`, { method: 'POST', body: '{"label_ids": [999999999]}' });
  check(badExport.status === 400 && (await badExport.json()).error.length > 0, 'answers a bad export with 400 and why');

  // An export with fractional numbers, HSV and a feather: the printed command line writes the same bytes (the
  // numbers survive the round trip through text exactly).
  const edit = { label_ids: [0, 2], hue: -37.5, saturation: 0.85, value: 1.1, space: 'hsv', feather: 1.5 };
  const exported = await fetch(`${viewer.url}api/export`, { method: 'POST', body: JSON.stringify(edit) });
  const answer = await exported.json();
  check(exported.status === 200 && answer.arguments.includes('--saturation') &&
        answer.arguments[answer.arguments.indexOf('--saturation') + 1] === '0.85', `exports ${answer.command}`);
  const again = [...answer.arguments];
  again[again.indexOf('--out') + 1] = path.join(work, 'by_command.h5');
  const rerun = await runLfsp(lfsp, ['-q', ...again]);
  check(rerun.code === 0 && fs.readFileSync(answer.files[0]).equals(fs.readFileSync(path.join(work, 'by_command.h5'))),
        'the exported command line writes the same bytes as the export');

  // A browser closed while the views download.
  await new Promise((resolve) => {
    const socket = net.connect(viewer.port, '127.0.0.1', () => socket.write('GET /api/views HTTP/1.1\r\nHost: x\r\n\r\n'));
    socket.once('data', () => { socket.destroy(); resolve(); });
    socket.on('error', resolve);
  });
  await new Promise((resolve) => setTimeout(resolve, 300));
  await stillServes(viewer, 'a client that closed mid-download');

  const busy = await runLfsp(lfsp, ['view', sample, '--port', String(viewer.port)]);
  const busyLines = busy.stderr.trim().split('\n');
  check(busy.code === 2 && busyLines.length === 1 && busyLines[0].includes(`127.0.0.1:${viewer.port}`),
        `a port in use: exit 2, one line naming it (${busyLines.join(' | ')})`);
} finally {
  stopViewer(viewer);
}

const missing = await runLfsp(lfsp, ['view', '/nonexistent/scene.h5']);
const missingLines = missing.stderr.trim().split('\n');
check(missing.code === 2 && missingLines.length === 1 && missingLines[0].includes('/nonexistent/scene.h5'),
      `a missing input: exit 2, one line naming it (${missingLines.join(' | ')})`);
const notLightField = await runLfsp(lfsp, ['view', '/etc/passwd']);
check(notLightField.code === 2 && notLightField.stderr.trim().split('\n').length === 1 &&
      notLightField.stderr.includes('/etc/passwd'), `a file that is no light field: exit 2 (${notLightField.stderr.trim()})`);
fs.rmSync(work, { recursive: true, force: true });
console.log('server safety: all checks passed');
