#!/usr/bin/env node
// test_viewer.js - end-to-end test of the 3-D viewer in headless Chromium (Debian's chromium,
// driven by playwright-core; no browser download). Stages the fixture run (and, when LVSIM is
// the CLI and it has `export`, a real run of examples/dof3-branch) with viewer/stage.sh, serves
// it with `lvsim view` at the URL it prints (token and all; Node's http module when LVSIM is not
// set), and checks: no console error, no failed or
// outside request, a track per body, the phase table, the event list, a moving clock and a
// screenshot that is not blank. Exit 0 pass, 1 fail, 77 skip (only when chromium cannot start).
// Env: LV_SOURCE_DIR, LVSIM, CHROMIUM (default /usr/bin/chromium), LV_VIEWER_OUT (default
// ./viewer), LV_DOCS_IMG (also write the screenshot there, e.g. docs/img/viewer.png),
// LV_DOCS_MODEL_IMG (also run examples/rlv-hthl and write its vehicle models 31 s after staging
// there: docs/img/viewer-models.png, the README's picture beside the paper's Figure 11).
// Vehicle models (a two-stage-6dof run): every CZML model packet an entity with a glTF data
// URI, the Model primitives ready, the 6-DoF phase's model turned (screenshot pixels differ
// between its attitudes at one time and camera); labels only on the selected entity.
'use strict';
const fs = require('fs');
const http = require('http');
const path = require('path');
const zlib = require('zlib');
const { execFileSync, spawn, spawnSync } = require('child_process');

const SRC = path.resolve(process.env.LV_SOURCE_DIR || path.join(__dirname, '..', '..'));
const OUT = path.resolve(process.env.LV_VIEWER_OUT || 'viewer');
const CHROMIUM = process.env.CHROMIUM || '/usr/bin/chromium';
const ARGS = ['--headless', '--no-sandbox', '--use-angle=swiftshader', '--enable-unsafe-swiftshader',
              '--disable-gpu', '--no-first-run', '--disable-background-networking',
              '--disable-component-update', '--disable-sync'];
const T_START = Date.now();
let fails = 0;
let passes = 0;

function log(msg) { console.log(`[${((Date.now() - T_START) / 1000).toFixed(1)} s] ${msg}`); }
function check(ok, what, detail) {
  if (ok) { passes++; return; }
  fails++;
  console.log(`FAIL: ${what}${detail ? `\n      ${detail}` : ''}`);
}

// ---- a static HTTP server on 127.0.0.1, random port ------------------------------------------
const MIME = { '.html': 'text/html', '.js': 'text/javascript', '.css': 'text/css',
               '.json': 'application/json', '.czml': 'application/json', '.png': 'image/png',
               '.jpg': 'image/jpeg', '.svg': 'image/svg+xml', '.wasm': 'application/wasm',
               '.xml': 'application/xml', '.glb': 'model/gltf-binary', '.ktx2': 'image/ktx2' };

function serve(root) {
  const server = http.createServer((req, res) => {
    const rel = decodeURIComponent(new URL(req.url, 'http://127.0.0.1').pathname);
    const file = path.join(root, path.normalize(rel));
    let f = file;
    if (!f.startsWith(root)) { res.writeHead(403); res.end(); return; }
    try {
      if (fs.statSync(f).isDirectory()) f = path.join(f, 'index.html');
      const body = fs.readFileSync(f);
      res.writeHead(200, { 'Content-Type': MIME[path.extname(f)] || 'application/octet-stream' });
      res.end(body);
    } catch (e) {
      res.writeHead(404); res.end('not found');
    }
  });
  return new Promise((resolve) => server.listen(0, '127.0.0.1', () => resolve(server)));
}

// ---- or `lvsim view DIR` (the site already staged: it only serves), at the URL it prints -----
const servers = [];   // ended however the test ends
process.on('exit', () => { for (const c of servers) if (c.exitCode === null) c.kill('SIGINT'); });
function lvsimView(dir) {
  return new Promise((resolve, reject) => {
    const child = spawn(process.env.LVSIM, ['view', dir], { stdio: ['ignore', 'pipe', 'pipe'] });
    servers.push(child);
    let out = '';
    const timer = setTimeout(() => { child.kill('SIGINT'); reject(new Error(`lvsim view ${dir}: no URL in 20 s: ${out}`)); }, 20000);
    const onData = (d) => {
      out += d;
      const m = /^lvsim view: (http:\/\/127\.0\.0\.1:\d+\/[0-9a-f]+\/)viewer\/ /m.exec(out);
      if (m) { clearTimeout(timer); resolve({ base: m[1], close: () => child.kill('SIGINT') }); }
    };
    child.stdout.on('data', onData);
    child.stderr.on('data', onData);
    child.on('exit', (code) => { clearTimeout(timer); reject(new Error(`lvsim view ${dir} exited ${code}: ${out}`)); });
  });
}

// ---- PNG decoding (8-bit RGB/RGBA, non-interlaced: what Chromium writes) ----------------------
function decodePng(buf) {
  const sig = Buffer.from([137, 80, 78, 71, 13, 10, 26, 10]);
  if (!buf.subarray(0, 8).equals(sig)) throw new Error('not a PNG');
  let off = 8, w = 0, h = 0, depth = 0, type = 0, interlace = 0;
  const idat = [];
  while (off < buf.length) {
    const len = buf.readUInt32BE(off);
    const kind = buf.toString('ascii', off + 4, off + 8);
    const data = buf.subarray(off + 8, off + 8 + len);
    if (kind === 'IHDR') {
      w = data.readUInt32BE(0); h = data.readUInt32BE(4);
      depth = data[8]; type = data[9]; interlace = data[12];
    } else if (kind === 'IDAT') idat.push(data);
    else if (kind === 'IEND') break;
    off += 12 + len;
  }
  if (depth !== 8 || (type !== 2 && type !== 6) || interlace !== 0)
    throw new Error(`unsupported PNG: depth ${depth}, colour type ${type}, interlace ${interlace}`);
  const bpp = type === 6 ? 4 : 3;
  const raw = zlib.inflateSync(Buffer.concat(idat));
  const stride = w * bpp;
  const px = Buffer.alloc(h * stride);
  for (let y = 0; y < h; y++) {
    const f = raw[y * (stride + 1)];
    const line = raw.subarray(y * (stride + 1) + 1, (y + 1) * (stride + 1));
    for (let x = 0; x < stride; x++) {
      const a = x >= bpp ? px[y * stride + x - bpp] : 0;
      const b = y > 0 ? px[(y - 1) * stride + x] : 0;
      const c = x >= bpp && y > 0 ? px[(y - 1) * stride + x - bpp] : 0;
      let v = line[x];
      if (f === 1) v += a;
      else if (f === 2) v += b;
      else if (f === 3) v += (a + b) >> 1;
      else if (f === 4) {
        const p = a + b - c, pa = Math.abs(p - a), pb = Math.abs(p - b), pc = Math.abs(p - c);
        v += pa <= pb && pa <= pc ? a : pb <= pc ? b : c;
      }
      px[y * stride + x] = v & 255;
    }
  }
  return { w, h, bpp, px };
}

// Colour count (5 bits per channel), luminance mean and standard deviation, and the share of
// blue or green pixels (sea and land of the globe imagery) in the region [x0, x1) x [0, y1).
function imageStats(img, x0, x1, y1) {
  const colours = new Set();
  let n = 0, sum = 0, sum2 = 0, earth = 0;
  for (let y = 0; y < y1; y++) {
    for (let x = x0; x < x1; x++) {
      const i = (y * img.w + x) * img.bpp;
      const r = img.px[i], g = img.px[i + 1], b = img.px[i + 2];
      colours.add(((r >> 3) << 10) | ((g >> 3) << 5) | (b >> 3));
      if (Math.max(r, g, b) > 40 && (b > r + 10 || g > r + 10)) earth++;
      const l = 0.299 * r + 0.587 * g + 0.114 * b;
      n++; sum += l; sum2 += l * l;
    }
  }
  const mean = sum / n;
  return { colours: colours.size, stddev: Math.sqrt(Math.max(0, sum2 / n - mean * mean)), mean,
           earth: earth / n };
}

// ---- the sites to test -----------------------------------------------------------------------
function stage(dir) {
  execFileSync(path.join(SRC, 'viewer', 'stage.sh'), [dir], { stdio: ['ignore', 'ignore', 'inherit'] });
}

function sites() {
  const list = [];
  const fix = path.join(OUT, 'site-fixture');
  fs.rmSync(fix, { recursive: true, force: true });
  fs.cpSync(path.join(SRC, 'tests', 'viewer', 'fixture'), fix, { recursive: true });
  stage(fix);
  list.push({ name: 'fixture', dir: fix,
              labels: ['burnout', 'separation', 'apogee', 'impact'] });
  const lvsim = process.env.LVSIM;
  if (!lvsim) { log('LVSIM not set: the fixture only'); return list; }
  const run = path.join(OUT, 'site-run');
  fs.rmSync(run, { recursive: true, force: true });
  const mission = path.join(SRC, 'examples', 'dof3-branch', 'mission.yaml');
  const r1 = spawnSync(lvsim, ['run', mission, '-o', run], { encoding: 'utf8' });
  check(r1.status === 0, `lvsim run ${mission}`, (r1.stderr || '').trim());
  if (r1.status !== 0) return list;
  const r2 = spawnSync(lvsim, ['export', run], { encoding: 'utf8' });
  if (r2.status !== 0 && /unknown command/.test(r2.stderr + r2.stdout)) {
    log(`${lvsim} has no 'export' command yet: the fixture only`);
    return list;
  }
  check(r2.status === 0 && fs.existsSync(path.join(run, 'mission.czml')),
        `lvsim export ${run} writes mission.czml`, (r2.stderr || '').trim());
  if (!fs.existsSync(path.join(run, 'mission.czml'))) return list;
  stage(run);
  list.push({ name: 'dof3-branch', dir: run, labels: ['burnout', 'impact'] });
  // The 6-DoF example: vehicle models turned by the rigid body's quaternion (and 3-DoF phases
  // by alpha, beta, mu), the booster left behind at staging.
  const run6 = path.join(OUT, 'site-6dof');
  fs.rmSync(run6, { recursive: true, force: true });
  const m6 = path.join(SRC, 'examples', 'two-stage-6dof', 'mission.yaml');
  const r3 = spawnSync(lvsim, ['run', m6, '-o', run6], { encoding: 'utf8' });
  check(r3.status === 0 && fs.existsSync(path.join(run6, 'mission.czml')), `lvsim run ${m6}`, (r3.stderr || '').trim());
  if (r3.status !== 0) return list;
  stage(run6);
  list.push({ name: 'two-stage-6dof', dir: run6, labels: ['MECO', 'SECO'],
              models: ['model/liftoff', 'model/boost', 'model/boost/spent', 'model/coast', 'model/upper-burn'],
              turn: { model: 'model/boost', phase: 'boost' } });
  if (process.env.LV_DOCS_MODEL_IMG) {   // the README's picture: rlv-hthl 31 s after staging
    const runR = path.join(OUT, 'site-rlv');
    fs.rmSync(runR, { recursive: true, force: true });
    const mR = path.join(SRC, 'examples', 'rlv-hthl', 'mission.yaml');
    const r4 = spawnSync(lvsim, ['run', mR, '-o', runR], { encoding: 'utf8' });
    check(r4.status === 0, `lvsim run ${mR}`, (r4.stderr || '').trim());
    if (r4.status !== 0) return list;
    stage(runR);
    list.push({ name: 'rlv-hthl', dir: runR, labels: ['MECO', 'touchdown', 'wheels stop'],
                models: ['model/liftoff', 'model/turn-around', 'model/us-ascent'],
                turn: { model: 'model/ascent', phase: 'ascent' },
                docsShot: { t: 222, range: 32000, pitch: -1.0, heading: 0.3 } });
  }
  return list;
}

// ---- vehicle models: present, loaded, turned by the CZML orientation --------------------------
// Pixels that differ (any channel by more than 24) between two screenshots of one size.
function pixelDiff(a, b) {
  let n = 0;
  for (let i = 0; i < a.w * a.h; i++) {
    const ia = i * a.bpp, ib = i * b.bpp;
    if (Math.abs(a.px[ia] - b.px[ib]) > 24 || Math.abs(a.px[ia + 1] - b.px[ib + 1]) > 24 ||
        Math.abs(a.px[ia + 2] - b.px[ib + 2]) > 24) n++;
  }
  return n;
}

async function checkModels(page, site, czml, summary) {
  const ids = czml.filter((p) => String(p.id).startsWith('model/')).map((p) => p.id);
  for (const id of site.models) check(ids.includes(id), `${site.name}: CZML model packet ${id}`, ids.join(' '));
  // every model packet is an entity with a model graphics whose glTF is a data URI (offline)
  const ents = await page.evaluate((list) => list.map((id) => {
    const e = window.lvsim.dataSource.entities.getById(id);
    const uri = e && e.model && e.model.uri && e.model.uri.getValue(window.viewer.clock.currentTime);
    return { id, model: !!(e && e.model), data: String(uri && (uri.url || uri)).startsWith('data:model/gltf-binary') };
  }), ids);
  for (const e of ents) check(e.model && e.data, `${site.name}: ${e.id} has a glTF model (data URI)`, JSON.stringify(e));

  // A phase's model at two instants whose attitudes differ by more than 10 deg.
  const ph = summary.phases.find((p) => p.name === site.turn.phase);
  const pick = await page.evaluate(({ id, t0, t1 }) => {
    const ep = Cesium.JulianDate.fromIso8601(window.lvsim.summary.epoch);
    const at = (t) => Cesium.JulianDate.addSeconds(ep, t, new Cesium.JulianDate());
    const e = window.lvsim.dataSource.entities.getById(id);
    // from 10 % of the phase, the instant among 20 %, 30 %, .. 90 % that turned it most
    const ta = t0 + 0.1 * (t1 - t0);
    const qa = e.orientation.getValue(at(ta));
    let best = { ta, tb: ta, deg: 0 };
    for (let k = 2; k <= 9; k++) {
      const tb = t0 + 0.1 * k * (t1 - t0);
      const dot = Math.abs(Cesium.Quaternion.dot(qa, e.orientation.getValue(at(tb))));
      const deg = 2 * Math.acos(Math.min(1, dot)) * 180 / Math.PI;
      if (deg > best.deg) best = { ta, tb, deg };
    }
    return best;
  }, { id: site.turn.model, t0: ph.t_start, t1: ph.t_end });
  check(pick.deg > 10, `${site.name}: ${site.turn.model} turns between ${pick.ta.toFixed(1)} and ${pick.tb.toFixed(1)} s`,
        `${pick.deg.toFixed(2)} deg`);

  // At ta, the camera 400 m from the model, looking at it from the side: a screenshot with the
  // model's own attitude, then one with the attitude of tb (same time, camera, globe): the
  // pictures differ only by the model's turn.
  await page.evaluate(({ id, ta }) => {
    const v = window.viewer;
    const ep = Cesium.JulianDate.fromIso8601(window.lvsim.summary.epoch);
    v.clock.currentTime = Cesium.JulianDate.addSeconds(ep, ta, new Cesium.JulianDate());
    v.selectedEntity = undefined;
    const e = window.lvsim.dataSource.entities.getById(id);
    v.camera.lookAt(e.position.getValue(v.clock.currentTime), new Cesium.HeadingPitchRange(0.0, -0.2, 400.0));
    window.lvsim.settle(3000);
  }, { id: site.turn.model, ta: pick.ta });
  // the models in the scene have loaded (Cesium Model primitives, ready)
  const ready = () => page.evaluate(() => {
    const found = [];
    const walk = (c) => {
      if (!c) return;
      if (c instanceof Cesium.Model) { if (c.show) found.push(c.ready); return; }
      if (typeof c.get === 'function' && typeof c.length === 'number') for (let i = 0; i < c.length; i++) walk(c.get(i));
    };
    walk(window.viewer.scene.primitives);
    return { n: found.length, ready: found.filter(Boolean).length };
  });
  await page.waitForFunction(() => {
    let ok = 0;
    const walk = (c) => {
      if (!c) return;
      if (c instanceof Cesium.Model) { if (c.show && c.ready) ok++; return; }
      if (typeof c.get === 'function' && typeof c.length === 'number') for (let i = 0; i < c.length; i++) walk(c.get(i));
    };
    walk(window.viewer.scene.primitives);
    return ok > 0;
  }, null, { timeout: 60000 }).catch(() => {});
  const rd = await ready();
  check(rd.n > 0 && rd.ready === rd.n, `${site.name}: vehicle models loaded (Cesium Model primitives ready)`, JSON.stringify(rd));
  await page.waitForTimeout(3000);
  const clip = { x: 0, y: 0, width: 1280 - 440, height: 720 - 60 };
  const shotA = path.join(OUT, `model-${site.name}-a.png`);
  await page.screenshot({ path: shotA, clip });
  await page.evaluate(({ id, tb }) => {
    const ep = Cesium.JulianDate.fromIso8601(window.lvsim.summary.epoch);
    const e = window.lvsim.dataSource.entities.getById(id);
    window.lvsim.savedOrientation = e.orientation;
    e.orientation = new Cesium.ConstantProperty(e.orientation.getValue(Cesium.JulianDate.addSeconds(ep, tb, new Cesium.JulianDate())));
    window.lvsim.settle(3000);
  }, { id: site.turn.model, tb: pick.tb });
  await page.waitForTimeout(3000);
  const shotB = path.join(OUT, `model-${site.name}-b.png`);
  await page.screenshot({ path: shotB, clip });
  const a = decodePng(fs.readFileSync(shotA)), b = decodePng(fs.readFileSync(shotB));
  const diff = pixelDiff(a, b);
  log(`${site.name}: ${site.turn.model} turned by ${pick.deg.toFixed(1)} deg: ${diff} of ${a.w * a.h} pixels differ`);
  check(diff > 0.002 * a.w * a.h, `${site.name}: the model's pixels change with its attitude`, `${diff} pixels`);
  // the same attitude again: the same picture (the difference above is the turn, not noise)
  await page.evaluate(({ id }) => {
    const e = window.lvsim.dataSource.entities.getById(id);
    e.orientation = window.lvsim.savedOrientation;
    window.lvsim.settle(3000);
  }, { id: site.turn.model });
  await page.waitForTimeout(3000);
  const shotC = path.join(OUT, `model-${site.name}-c.png`);
  await page.screenshot({ path: shotC, clip });
  const same = pixelDiff(a, decodePng(fs.readFileSync(shotC)));
  check(same < 0.1 * diff, `${site.name}: the model's own attitude again gives the first picture`, `${same} pixels differ`);

  // Labels: a selected model shows its own label, and only it.
  const shown = await page.evaluate((id) => {
    window.viewer.selectedEntity = window.lvsim.dataSource.entities.getById(id);
    return window.lvsim.shownLabels();
  }, site.turn.model);
  check(shown.length === 1 && shown[0] === site.turn.model, `${site.name}: only the selected model's label`, JSON.stringify(shown));
  await page.evaluate(() => { window.viewer.selectedEntity = undefined; window.viewer.camera.lookAtTransform(Cesium.Matrix4.IDENTITY); });
}

// ---- one site in the browser -----------------------------------------------------------------
async function testSite(browser, site) {
  const summary = JSON.parse(fs.readFileSync(path.join(site.dir, 'summary.json'), 'utf8'));
  const czml = JSON.parse(fs.readFileSync(path.join(site.dir, 'mission.czml'), 'utf8'));
  // served by `lvsim view` when LVSIM is the CLI (every request then carries its token: the
  // page's relative URLs keep it), else by Node
  let server, base;
  if (process.env.LVSIM) {
    const v = await lvsimView(site.dir);
    server = v; base = v.base;
  } else {
    server = await serve(site.dir);
    base = `http://127.0.0.1:${server.address().port}/`;
  }
  const origin = base.replace(/\/$/, '');
  const problems = { console: [], failed: [], outside: [], count: 0 };
  const context = await browser.newContext({ viewport: { width: 1280, height: 720 } });
  // Anything not for our server is recorded and aborted: the test makes no outside traffic.
  await context.route('**/*', (route) => {
    const url = route.request().url();
    if (url.startsWith(origin + '/') || url.startsWith('data:') || url.startsWith('blob:'))
      return route.continue();
    problems.outside.push(url);
    return route.abort();
  });
  const page = await context.newPage();
  page.on('console', (m) => { if (m.type() === 'error') problems.console.push(m.text()); });
  page.on('pageerror', (e) => problems.console.push(`page error: ${e.message}`));
  page.on('request', () => { problems.count++; });
  page.on('requestfailed', (r) => {
    if (!problems.outside.includes(r.url())) problems.failed.push(`${r.url()}: ${r.failure() && r.failure().errorText}`);
  });
  page.on('response', (r) => { if (r.status() >= 400) problems.failed.push(`${r.url()}: HTTP ${r.status()}`); });

  const t0 = Date.now();
  await page.goto(`${base}viewer/`);
  try {
    await page.waitForFunction(() => window.lvsim && (window.lvsim.error ||
      (window.lvsim.ready && window.viewer.scene.globe.tilesLoaded)), null, { timeout: 90000 });
  } catch (e) {
    check(false, `${site.name}: viewer ready within 90 s`, e.message.split('\n')[0]);
  }
  const error = await page.evaluate(() => window.lvsim && window.lvsim.error);
  check(!error, `${site.name}: viewer loads the mission`, error);
  log(`${site.name}: ready in ${((Date.now() - t0) / 1000).toFixed(1)} s`);

  // Every body has a track entity in the viewer's data sources.
  const ids = await page.evaluate(() => {
    const out = [];
    const dss = window.viewer.dataSources;
    for (let i = 0; i < dss.length; i++) for (const e of dss.get(i).entities.values) out.push(e.id);
    return out;
  });
  for (const b of summary.bodies)
    check(ids.some((id) => id.startsWith(`track/${b.name}/`)), `${site.name}: track of body '${b.name}'`,
          `entities: ${ids.join(' ')}`);
  const czmlEvents = czml.filter((p) => String(p.id).startsWith('event/')).map((p) => p.id);
  for (const id of czmlEvents) check(ids.includes(id), `${site.name}: event marker ${id}`);

  // The phase table lists every phase; the event list has the expected labels.
  const rows = await page.$$eval('#phases tbody tr', (trs) => trs.map((tr) => tr.dataset.phase));
  for (const p of summary.phases) check(rows.includes(p.name), `${site.name}: phase table row '${p.name}'`, `rows: ${rows}`);
  const evs = await page.evaluate(() => window.lvsim.events || []);
  check(evs.length >= czmlEvents.length && evs.length > 0, `${site.name}: events listed`, JSON.stringify(evs));
  for (const l of site.labels) check(evs.some((e) => e.text === l), `${site.name}: event '${l}' listed`, JSON.stringify(evs));
  // one vocabulary: events as summary.json names them - the user's name (`name: MECO`) where
  // it has one, else the condition's; a spent stage's impact is never a "landing"
  const named = new Set();
  for (const p of summary.phases)
    for (const e of (p.events || [])) if (e.kind === 'state') named.add(e.label || e.name);
  for (const l of named) check(evs.some((e) => e.text === l), `${site.name}: event '${l}' as summary.json names it`,
                               JSON.stringify(evs));
  check(!evs.some((e) => /landing/.test(e.text)), `${site.name}: no event called a landing`, JSON.stringify(evs));

  // The clock moves after Play.
  const clockNow = () => page.evaluate(() =>
    Cesium.JulianDate.secondsDifference(window.viewer.clock.currentTime, window.viewer.clock.startTime));
  log(`${site.name}: entities, table, events checked`);
  const before = await clockNow();
  // DOM clicks (dispatchEvent): the handlers run without Playwright waiting for stable
  // frames, which software WebGL draws slowly while the clock plays.
  const click = (sel) => page.locator(sel).dispatchEvent('click');
  await click('#play');
  await page.waitForTimeout(1500);
  const after = await clockNow();
  await click('#play');               // pause
  check(after > before, `${site.name}: clock advances after play`, `${before} -> ${after} s`);

  // Click an event (the separation if there is one): the clock jumps to it.
  const target = evs.find((e) => e.text === 'separation') || evs[0];
  if (target) {
    const idx = evs.indexOf(target);
    await click(`#events li:nth-child(${idx + 1})`);
    const epochOff = await page.evaluate(() => {
      const ep = Cesium.JulianDate.fromIso8601(window.lvsim.summary.epoch);
      return Cesium.JulianDate.secondsDifference(window.viewer.clock.currentTime, ep);
    });
    check(Math.abs(epochOff - target.t) < 1e-3, `${site.name}: event click sets the clock`,
          `${epochOff} vs ${target.t}`);
  }
  // Labels only on the selected entity: none with nothing selected, then only the chosen one's.
  const labelsWith = (sel) => page.evaluate((id) => {
    const ds = window.lvsim.dataSource;
    window.viewer.selectedEntity = id ? (ds.entities.getById(id) || window.viewer.entities.getById(id)) : undefined;
    return window.lvsim.shownLabels();
  }, sel);
  check((await labelsWith(undefined)).length === 0, `${site.name}: no label with nothing selected`,
        JSON.stringify(await labelsWith(undefined)));
  const ev0 = czml.find((p) => String(p.id).startsWith('event/') && p.label);
  if (ev0) {
    await page.evaluate((t) => { window.viewer.clock.currentTime = Cesium.JulianDate.addSeconds(
      Cesium.JulianDate.fromIso8601(window.lvsim.summary.epoch), t, new Cesium.JulianDate()); },
    0.5 * (Math.min(...summary.phases.map((p) => p.t_start)) + Math.max(...summary.phases.map((p) => p.t_end))));
    const shown = await labelsWith(ev0.id);
    check(shown.length === 1, `${site.name}: one label with marker ${ev0.id} selected`, JSON.stringify(shown));
  }

  if (site.models) {
    await checkModels(page, site, czml, summary);
    await click('#home');            // back to the view of every track
    await page.waitForTimeout(2500);
  }
  if (site.docsShot) {   // the models at one instant, the camera on the middle of them
    await page.evaluate((d) => {
      const v = window.viewer, ds = window.lvsim.dataSource;
      const now = Cesium.JulianDate.addSeconds(Cesium.JulianDate.fromIso8601(window.lvsim.summary.epoch), d.t, new Cesium.JulianDate());
      v.clock.currentTime = now;
      const ps = window.lvsim.models.map((id) => ds.entities.getById(id)).filter((e) => e.isAvailable(now))
        .map((e) => e.position.getValue(now)).filter(Boolean);
      v.camera.lookAt(Cesium.BoundingSphere.fromPoints(ps).center, new Cesium.HeadingPitchRange(d.heading, d.pitch, d.range));
      window.lvsim.settle(5000);
    }, site.docsShot);
    await page.waitForFunction(() => window.viewer.scene.globe.tilesLoaded, null, { timeout: 30000 }).catch(() => {});
    await page.waitForTimeout(4000);
    await page.screenshot({ path: process.env.LV_DOCS_MODEL_IMG, clip: { x: 0, y: 0, width: 840, height: 690 } });
    log(`${site.name}: vehicle models at t = ${site.docsShot.t} s written to ${process.env.LV_DOCS_MODEL_IMG}`);
    await page.evaluate(() => window.viewer.camera.lookAtTransform(Cesium.Matrix4.IDENTITY));
    await click('#home');
    await page.waitForTimeout(2500);
  }

  // The picture at the mission's end: every track, marker and body where it ended.
  await page.evaluate(() => {
    window.viewer.clock.currentTime = window.viewer.clock.stopTime.clone();
    window.viewer.selectedEntity = undefined;
  });
  log(`${site.name}: checks done`);
  await page.waitForFunction(() => window.viewer.scene.globe.tilesLoaded, null, { timeout: 30000 }).catch(() => {});
  await page.waitForTimeout(3000);    // the page draws for 2 s after a change (label glyphs)
  log(`${site.name}: tiles loaded`);

  const shot = path.join(OUT, `viewer-${site.name}.png`);
  await page.screenshot({ path: shot });
  const img = decodePng(fs.readFileSync(shot));
  const globeW = Math.max(1, img.w - 440);        // the globe, left of the side panel
  const st = imageStats(img, 0, globeW, img.h - 60);   // above the clock widgets
  log(`${site.name}: screenshot ${shot} ${img.w}x${img.h}: ${st.colours} colours, ` +
      `luminance sd ${st.stddev.toFixed(1)}, mean ${st.mean.toFixed(1)}, globe ${(100 * st.earth).toFixed(0)} %`);
  check(st.colours >= 200 && st.stddev >= 8 && st.mean >= 5, `${site.name}: screenshot not blank`,
        JSON.stringify(st));
  check(st.earth >= 0.1, `${site.name}: the globe is drawn (sea/land pixels)`, JSON.stringify(st));

  check(problems.console.length === 0, `${site.name}: no console errors`, problems.console.join('\n      '));
  check(problems.failed.length === 0, `${site.name}: no failed requests`, problems.failed.join('\n      '));
  check(problems.outside.length === 0, `${site.name}: no request outside ${origin}`, problems.outside.join('\n      '));
  log(`${site.name}: ${problems.count} requests, all to ${origin}`);
  await context.close();
  server.close();
  return shot;
}

async function main() {
  fs.mkdirSync(OUT, { recursive: true });
  const inst = spawnSync(path.join(SRC, 'viewer', 'install.sh'), { stdio: 'inherit' });
  if (inst.status !== 0) { console.log('FAIL: viewer/install.sh'); process.exit(1); }
  const { chromium } = require(path.join(SRC, 'viewer', 'node_modules', 'playwright-core'));
  const list = sites();
  let browser;
  try {
    if (!fs.existsSync(CHROMIUM)) throw new Error(`${CHROMIUM} not found (apt-get install chromium)`);
    browser = await chromium.launch({ executablePath: CHROMIUM, args: ARGS, timeout: 60000 });
  } catch (e) {
    console.log(`SKIP: chromium cannot start: ${e.message.split('\n')[0]}`);
    process.exit(77);
  }
  log(`chromium ${browser.version()} started`);
  const shots = [];
  try {
    for (const s of list) shots.push(await testSite(browser, s));
  } finally {
    await browser.close();
  }
  if (process.env.LV_DOCS_IMG && fails === 0 && shots.length > 0) {
    fs.copyFileSync(shots[shots.length - 1], process.env.LV_DOCS_IMG);
    log(`screenshot copied to ${process.env.LV_DOCS_IMG}`);
  }
  if (fails === 0) for (const s of list) fs.rmSync(path.join(s.dir, 'viewer'), { recursive: true, force: true });
  console.log(`test_viewer: ${passes} passed, ${fails} failed (${((Date.now() - T_START) / 1000).toFixed(1)} s)`);
  process.exit(fails === 0 ? 0 : 1);
}

main().catch((e) => { console.log(`FAIL: ${e.stack || e}`); process.exit(1); });
