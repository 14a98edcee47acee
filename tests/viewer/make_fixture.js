#!/usr/bin/env node
// make_fixture.js RUNDIR FIXDIR - the viewer test's fixture: RUNDIR's summary.json and a small
// mission.czml built from its body_<stage>.csv in the layout of `lvsim export` (src/io/
// export_czml.c: a "document" packet with the clock; "track/<body>/<phase>" paths drawn up to
// the clock time, the body's marker on its last track; "event/<phase>/<k>" markers available
// from their time, k = 0 the phase start, then its events), with the events' names (burnout,
// separation, apogee, impact). Positions thinned to about one per 5 s to keep it small.
// Regenerate: lvsim run examples/dof3-branch/mission.yaml -o RUN; node make_fixture.js RUN fixture
'use strict';
const fs = require('fs');
const path = require('path');

const PALETTE = [[255, 170, 0], [0, 200, 255], [255, 80, 120], [120, 230, 90], [200, 130, 255],
                 [255, 240, 80], [80, 160, 255]];
const DEG = 180 / Math.PI;

function readCsv(file) {
  const lines = fs.readFileSync(file, 'utf8').trim().split('\n');
  const head = lines[0].split(',').map((s) => s.replace(/ \[.*\]$/, ''));
  return lines.slice(1).map((l) => {
    const v = l.split(',');
    const row = {};
    head.forEach((k, i) => { row[k] = k === 'phase' ? v[i] : Number(v[i]); });
    return row;
  });
}

function iso(epochMs, t) { return new Date(epochMs + t * 1000).toISOString(); }

function main() {
  const [runDir, fixDir] = process.argv.slice(2);
  if (!runDir || !fixDir) { console.error('usage: make_fixture.js RUNDIR FIXDIR'); process.exit(2); }
  const sum = JSON.parse(fs.readFileSync(path.join(runDir, 'summary.json'), 'utf8'));
  const epochMs = Date.parse(sum.epoch);
  const t0 = Math.min(...sum.phases.map((p) => p.t_start));
  const t1 = Math.max(...sum.phases.map((p) => p.t_end));
  const whole = `${iso(epochMs, t0)}/${iso(epochMs, t1)}`;
  const colour = {};
  sum.phases.forEach((p, i) => { colour[p.name] = PALETTE[i % PALETTE.length].concat(255); });

  const out = [{
    id: 'document', name: sum.mission, version: '1.0',
    clock: { interval: whole, currentTime: iso(epochMs, t0), multiplier: Math.max(1, Math.ceil((t1 - t0) / 60)),
             range: 'LOOP_STOP', step: 'SYSTEM_CLOCK_MULTIPLIER' },
  }];
  const where = {};               // phase -> rows of its first body, for event positions
  for (const b of sum.bodies) {
    const rows = readCsv(path.join(runDir, b.trajectory));
    b.phases.forEach((ph, ib) => {
      const r = rows.filter((x) => x.phase === ph);
      if (r.length === 0) return;
      if (!where[ph]) where[ph] = r;
      const pos = [];
      let last = -Infinity;
      r.forEach((x, i) => {
        if (x.time - last >= 5 || i === r.length - 1) {
          pos.push(x.time, x.lon * DEG, x.lat * DEG, x.h);
          last = x.time;
        }
      });
      const packet = {
        id: `track/${b.name}/${ph}`, name: `${b.name}, phase ${ph}`, availability: whole,
        position: { epoch: sum.epoch, forwardExtrapolationType: 'HOLD', cartographicDegrees: pos },
        path: { material: { solidColor: { color: { rgba: colour[ph] } } }, width: 2,
                leadTime: 0, trailTime: t1 - t0 + 1, resolution: 1 },
      };
      if (ib === b.phases.length - 1) {
        packet.point = { pixelSize: 8, color: { rgba: colour[ph] } };
        packet.label = { text: b.name, font: '13px sans-serif', horizontalOrigin: 'LEFT',
                         pixelOffset: { cartesian2: [10, 0] } };
      }
      out.push(packet);
    });
  }
  const at = (ph, t) => {
    const r = where[ph];
    let best = r[0];
    for (const x of r) if (Math.abs(x.time - t) < Math.abs(best.time - t)) best = x;
    return [best.lon * DEG, best.lat * DEG, best.h];
  };
  const separated = new Set();    // the first child of a parent is "separation"
  for (const p of sum.phases) {
    if (!where[p.name]) continue;
    let start = `${p.name} start`;
    if (!p.from) start = 'liftoff';
    else if (!separated.has(p.from)) { separated.add(p.from); start = 'separation'; }
    const ev = [{ t: p.t_start, text: start }];
    for (const e of p.events) {
      const text = e.name || 'time event'; // the events' own names, as lvsim export writes them
      ev.push({ t: e.t, text });
    }
    const r = where[p.name];
    const top = r.reduce((a, x) => (x.h > a.h ? x : a), r[0]);
    if (top.time > p.t_start + 1 && top.time < p.t_end - 1) ev.push({ t: top.time, text: 'apogee' });
    ev.forEach((e, k) => out.push({
      id: `event/${p.name}/${k}`, name: `${e.text} (${p.name})`,
      availability: `${iso(epochMs, e.t)}/${iso(epochMs, t1)}`,
      position: { cartographicDegrees: at(p.name, e.t) },
      point: { pixelSize: 8, color: { rgba: colour[p.name] }, outlineColor: { rgba: [0, 0, 0, 255] },
               outlineWidth: 1 },
      label: { text: e.text, font: '13px sans-serif', style: 'FILL_AND_OUTLINE',
               fillColor: { rgba: colour[p.name] }, outlineColor: { rgba: [0, 0, 0, 255] },
               outlineWidth: 2, horizontalOrigin: 'LEFT',
               pixelOffset: { cartesian2: [10, e.text === 'separation' ? 14 : 0] } },
    }));
  }
  fs.mkdirSync(fixDir, { recursive: true });
  fs.writeFileSync(path.join(fixDir, 'mission.czml'), JSON.stringify(out, null, 1) + '\n');
  fs.copyFileSync(path.join(runDir, 'summary.json'), path.join(fixDir, 'summary.json'));
}

main();
