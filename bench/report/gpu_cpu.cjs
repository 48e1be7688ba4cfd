// CPU time of the chromium GPU processes this node process launched (their
// /proc stat: user + system), in milliseconds. With software WebGL
// (SwiftShader) a frame's rendering runs there, on every core; its CPU time
// is the work a frame takes, which unlike its wall time does not depend on
// what else the (shared) machine runs. For bench/report/measure.cjs and
// profile.cjs.
const fs = require('node:fs');
const { execFileSync } = require('node:child_process');

const TICK_MS = 1000 / Number(execFileSync('getconf', ['CLK_TCK'], { encoding: 'utf8' }).trim());

function stat(pid) {
  try {
    const s = fs.readFileSync(`/proc/${pid}/stat`, 'utf8');
    return s.slice(s.lastIndexOf(')') + 2).split(' ');  // fields from the third (state) on
  } catch {
    return null;
  }
}

function ours(pid) {
  let p = pid;
  for (let k = 0; k < 6 && p > 1; ++k) {
    const s = stat(p);
    if (!s) return false;
    p = Number(s[1]);  // ppid
    if (p === process.pid) return true;
  }
  return false;
}

// The GPU processes of the browsers this process launched.
function gpuProcesses() {
  const out = [];
  for (const d of fs.readdirSync('/proc')) {
    if (!/^\d+$/.test(d)) continue;
    let cmd;
    try {
      cmd = fs.readFileSync(`/proc/${d}/cmdline`, 'utf8');
    } catch {
      continue;
    }
    if (cmd.includes('--type=gpu-process') && ours(Number(d))) out.push(Number(d));
  }
  return out;
}

// Their CPU time so far, milliseconds (utime + stime: fields 14 and 15).
function gpuCpuMs(pids = gpuProcesses()) {
  let ticks = 0;
  for (const pid of pids) {
    const s = stat(pid);
    if (s) ticks += Number(s[11]) + Number(s[12]);
  }
  return ticks * TICK_MS;
}

module.exports = { gpuProcesses, gpuCpuMs, TICK_MS };
