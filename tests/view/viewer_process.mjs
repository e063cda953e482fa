// Starting and stopping `lfsp view` from a test: the command prints its address on stdout once it listens.

import { spawn } from 'node:child_process';

export function startViewer(lfsp, args, { timeoutMs = 120000 } = {}) {
  const child = spawn(lfsp, ['-q', 'view', ...args, '--port', '0'], { stdio: ['ignore', 'pipe', 'pipe'] });
  let stderr = '';
  child.stderr.on('data', (chunk) => { stderr += chunk; });
  return new Promise((resolve, reject) => {
    let stdout = '';
    const timer = setTimeout(() => reject(new Error(`lfsp view did not start in ${timeoutMs} ms: ${stderr}`)), timeoutMs);
    child.stdout.on('data', (chunk) => {
      stdout += chunk;
      const match = stdout.match(/http:\/\/([\d.]+):(\d+)\//);
      if (match) {
        clearTimeout(timer);
        resolve({ child, url: match[0], host: match[1], port: Number(match[2]), stderr: () => stderr });
      }
    });
    child.on('exit', (code) => { clearTimeout(timer); reject(new Error(`lfsp view exited (${code}): ${stderr}`)); });
  });
}

export function stopViewer(viewer) {
  viewer.child.removeAllListeners('exit');
  viewer.child.kill('SIGTERM');
}

// Runs lfsp to completion; resolves { code, stdout, stderr }.
export function runLfsp(lfsp, args) {
  return new Promise((resolve) => {
    const child = spawn(lfsp, args, { stdio: ['ignore', 'pipe', 'pipe'] });
    let stdout = '', stderr = '';
    child.stdout.on('data', (chunk) => { stdout += chunk; });
    child.stderr.on('data', (chunk) => { stderr += chunk; });
    child.on('exit', (code) => resolve({ code, stdout, stderr }));
  });
}

export function check(condition, message) {
  if (!condition) throw new Error(`FAILED: ${message}`);
  console.log(`ok: ${message}`);
}
