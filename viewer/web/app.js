// lvsim mission viewer: loads ../mission.czml (written by `lvsim export`) into an offline
// CesiumJS globe (NaturalEarthII imagery shipped in the cesium package; no ion, no outside
// request) and ../summary.json into the side panel. Track packets are "track/<body>/<phase>",
// event packets "event/<phase>/<k>" (see docs/visualization.md). Exposes window.viewer and
// window.lvsim (ready flag, summary, data source) for the browser test.
'use strict';

(function () {
  const params = new URLSearchParams(window.location.search);
  const czmlUrl = params.get('czml') || '../mission.czml';
  const summaryUrl = params.get('summary') || '../summary.json';
  const $ = (id) => document.getElementById(id);
  const state = { ready: false, error: null };
  window.lvsim = state;

  function setStatus(text, isError) {
    const el = $('status');
    el.textContent = text;
    el.className = isError ? 'error' : '';
  }

  function el(tag, text, cls) {
    const e = document.createElement(tag);
    if (text !== undefined) e.textContent = text;
    if (cls) e.className = cls;
    return e;
  }

  async function fetchJson(url) {
    const r = await fetch(url);
    if (!r.ok) throw new Error(`${url}: HTTP ${r.status}`);
    return r.json();
  }

  window.addEventListener('error', (ev) => {   // e.g. no WebGL: say so in the panel
    state.error = ev.message;
    setStatus(`viewer error: ${ev.message}`, true);
  });

  // No ion token and no ion asset: the only imagery is the one inside the cesium package.
  Cesium.Ion.defaultAccessToken = '';
  const viewer = new Cesium.Viewer('globe', {
    baseLayer: Cesium.ImageryLayer.fromProviderAsync(Cesium.TileMapServiceImageryProvider.fromUrl(
      Cesium.buildModuleUrl('Assets/Textures/NaturalEarthII'))),
    terrainProvider: new Cesium.EllipsoidTerrainProvider(),
    baseLayerPicker: false, geocoder: false, homeButton: false, sceneModePicker: false,
    navigationHelpButton: false, fullscreenButton: false, infoBox: false,
    selectionIndicator: true, animation: true, timeline: true, shouldAnimate: false,
    // Draw only when something changes (camera, data, clock time): an idle page costs no
    // CPU, which also keeps software WebGL (headless test, remote desktops) responsive.
    requestRenderMode: true, maximumRenderTimeChange: 0.0,
  });
  window.viewer = viewer;
  // The vehicle models lit from the camera (a head lamp): the sun may be below the horizon
  // at the mission's time and place, and a model in the dark shows no attitude.
  const headLamp = new Cesium.DirectionalLight({ direction: new Cesium.Cartesian3(0, 0, -1), intensity: 2.0 });
  viewer.scene.light = headLamp;
  viewer.scene.preRender.addEventListener((scene) => {
    Cesium.Cartesian3.clone(scene.camera.directionWC, headLamp.direction);
  });

  // requestRenderMode draws on changes, but Cesium fills label glyphs and images into its
  // texture atlas asynchronously without asking for a frame: keep drawing for a moment after
  // anything changes (clock time, camera, panel actions) so labels come out whole.
  let settleUntil = 0;
  let settleTimer = null;
  function settle(ms) {
    settleUntil = Math.max(settleUntil, performance.now() + (ms || 2000));
    if (settleTimer !== null) return;
    const step = () => {
      viewer.scene.requestRender();
      settleTimer = performance.now() < settleUntil ? setTimeout(step, 250) : null;
    };
    step();
  }
  let lastTime = viewer.clock.currentTime.clone();
  viewer.clock.onTick.addEventListener((clock) => {
    if (!Cesium.JulianDate.equals(clock.currentTime, lastTime)) {
      lastTime = clock.currentTime.clone();
      settle();
    }
  });
  viewer.camera.moveEnd.addEventListener(() => settle());
  state.settle = settle;

  function missionSeconds(epoch, date) { return Cesium.JulianDate.secondsDifference(date, epoch); }
  function fmtT(s) { return (s < 0 ? 'T' : 'T+') + s.toFixed(1) + ' s'; }

  function colourOf(entity, when) {
    const g = entity.path || entity.polyline;
    const m = g && g.material;
    const c = m && m.color && m.color.getValue(when);
    return c || Cesium.Color.WHITE;
  }

  // Points along every track (sampled in its phase interval) for the camera's bounding sphere.
  function trackSphere(tracks, at) {
    const pts = [];
    for (const tr of tracks) {
      for (let i = 0; i <= 40; i++) {
        const p = tr.entity.position && tr.entity.position.getValue(at(tr.t0 + (tr.t1 - tr.t0) * i / 40));
        if (p) pts.push(p);
      }
    }
    if (pts.length === 0) return undefined;
    const bs = Cesium.BoundingSphere.fromPoints(pts);
    bs.radius = Math.max(bs.radius, 50e3);
    // Mostly vertical tracks (a flat-world run climbs straight up from its site): look from
    // the side instead of from above.
    const carto = pts.map((p) => Cesium.Cartographic.fromCartesian(p));
    const hs = carto.map((c) => c.height);
    const ground = Cesium.Ellipsoid.WGS84.cartesianToCartographic(bs.center);
    const spread = Math.max(...pts.map((p) => {
      const c = Cesium.Cartographic.fromCartesian(p);
      c.height = 0;
      ground.height = 0;
      return Cesium.Cartesian3.distance(Cesium.Cartographic.toCartesian(c), Cesium.Cartographic.toCartesian(ground));
    }));
    bs.vertical = Math.max(...hs) - Math.min(...hs) > 4 * spread;
    return bs;
  }

  function flyHome(bs, duration) {
    return new Promise((resolve) => {
      if (!bs) { resolve(); return; }
      viewer.camera.flyToBoundingSphere(bs, {
        duration, offset: bs.vertical ? new Cesium.HeadingPitchRange(0.0, -0.25, bs.radius * 3.0)
                                      : new Cesium.HeadingPitchRange(0.0, -0.9, bs.radius * 2.8),
        complete: resolve, cancel: resolve,
      });
    });
  }

  async function main() {
    const [summary, ds] = await Promise.all([fetchJson(summaryUrl),
                                             Cesium.CzmlDataSource.load(czmlUrl)]);
    await viewer.dataSources.add(ds);
    viewer.clockTrackedDataSource = ds;
    const epoch = Cesium.JulianDate.fromIso8601(summary.epoch);
    const at = (t) => Cesium.JulianDate.addSeconds(epoch, t, new Cesium.JulianDate());
    const phaseByName = new Map(summary.phases.map((p) => [p.name, p]));

    // Mission time on the clock widgets.
    viewer.animation.viewModel.dateFormatter = (d) => Cesium.JulianDate.toIso8601(d, 0).slice(0, 19) + 'Z';
    viewer.animation.viewModel.timeFormatter = (d) => fmtT(missionSeconds(epoch, d));
    viewer.timeline.makeLabel = (d) => fmtT(missionSeconds(epoch, d));
    viewer.timeline.zoomTo(viewer.clock.startTime, viewer.clock.stopTime);

    // Tracks: "track/<body>/<phase>".
    const entities = ds.entities.values;
    const tracks = [];
    const phaseColour = new Map();
    for (const b of summary.bodies) {
      const prefix = `track/${b.name}/`;
      for (const e of entities) {
        if (!e.id.startsWith(prefix)) continue;
        const phase = e.id.slice(prefix.length);
        const p = phaseByName.get(phase);
        const tr = { body: b.name, phase, entity: e,
                     t0: p ? p.t_start : 0, t1: p ? p.t_end : 0 };
        tracks.push(tr);
        if (!phaseColour.has(phase)) phaseColour.set(phase, colourOf(e, at(tr.t0)));
      }
    }
    state.tracks = tracks.map((t) => t.entity.id);

    // Vehicle models "model/<phase>" (and "model/<phase>/spent"): the stack of the phase's
    // stages, a glTF lvsim export built, turned by the body's attitude (CZML orientation).
    const models = entities.filter((e) => e.id.startsWith('model/') && e.model);
    state.models = models.map((e) => e.id);
    for (const e of models) {
      e.label = new Cesium.LabelGraphics({
        text: e.name, font: '12px sans-serif', pixelOffset: new Cesium.Cartesian2(12, -12),
        horizontalOrigin: Cesium.HorizontalOrigin.LEFT, fillColor: Cesium.Color.WHITE,
        showBackground: true, disableDepthTestDistance: Number.POSITIVE_INFINITY });
    }

    // A moving marker per body over all its phases: its position is the track of the phase
    // it is in, then (after its last phase) wherever that track holds it. It replaces the
    // marker lvsim export rides on a body's last track only. With vehicle models the models
    // are the bodies: no marker.
    const tEnd = missionSeconds(epoch, viewer.clock.stopTime);
    for (const b of (models.length > 0 ? [] : summary.bodies)) {
      const mine = tracks.filter((t) => t.body === b.name).sort((x, y) => x.t0 - y.t0);
      if (mine.length === 0) continue;
      const pos = new Cesium.CompositePositionProperty();
      mine.forEach((t, i) => {
        const last = i === mine.length - 1;
        pos.intervals.addInterval(new Cesium.TimeInterval({
          start: at(t.t0), stop: at(last ? Math.max(t.t1, tEnd) : t.t1), isStartIncluded: true,
          isStopIncluded: last, data: t.entity.position }));
        if (t.entity.point) t.entity.point.show = false;
        if (t.entity.label) t.entity.label.show = false;
      });
      viewer.entities.add({
        id: `vehicle/${b.name}`, name: b.name, position: pos,
        availability: new Cesium.TimeIntervalCollection([new Cesium.TimeInterval({
          start: at(mine[0].t0), stop: at(Math.max(mine[mine.length - 1].t1, tEnd)) })]),
        point: { pixelSize: 9, color: Cesium.Color.WHITE, outlineColor: Cesium.Color.BLACK,
                 outlineWidth: 2, disableDepthTestDistance: Number.POSITIVE_INFINITY },
        label: { text: b.name, font: '12px sans-serif', pixelOffset: new Cesium.Cartesian2(-10, 10),
                 horizontalOrigin: Cesium.HorizontalOrigin.RIGHT, fillColor: Cesium.Color.WHITE,
                 showBackground: true, disableDepthTestDistance: Number.POSITIVE_INFINITY },
      });
    }

    // Side panel: header and phase table (with the legend colour of each phase).
    $('mission').textContent = summary.mission;
    $('meta').textContent = `${summary.world} world · epoch ${summary.epoch} · ` +
      `${summary.phases.length} phases · ${summary.bodies.length} bodies`;
    const rows = new Map();
    const tbody = $('phases').querySelector('tbody');
    for (const p of summary.phases) {
      const tr = document.createElement('tr');
      tr.dataset.phase = p.name;
      const sw = el('span', undefined, 'swatch');
      sw.style.background = (phaseColour.get(p.name) || Cesium.Color.GRAY).toCssColorString();
      const td0 = el('td');
      td0.appendChild(sw);
      tr.appendChild(td0);
      const end = p.end ? (p.end.event || p.end.reason) : p.state;
      const st = p.stats || {};
      const cells = [p.name, p.from || '-', p.t_start.toFixed(3), p.t_end.toFixed(3), end,
                     st.steps !== undefined ? String(st.steps) : '',
                     st.cpu_time !== undefined ? (st.cpu_time * 1e3).toFixed(2) : ''];
      for (const c of cells) tr.appendChild(el('td', c));
      tr.addEventListener('click', () => { viewer.clock.currentTime = at(p.t_start); });
      tbody.appendChild(tr);
      rows.set(p.name, { tr, p });
    }
    for (const b of summary.bodies) {
      const n = tracks.filter((t) => t.body === b.name).length;
      $('bodies').appendChild(el('li', `${b.name}: ${b.phases.join(' → ')} (${n} tracks)`));
    }

    // Events: the CZML markers "event/<phase>/<k>"; their time is properties.t (mission s),
    // else the start of their availability (lvsim export: from the event to the end).
    const events = [];
    for (const e of entities) {
      if (!e.id.startsWith('event/')) continue;
      const [, phase, k] = e.id.split('/');
      const p = phaseByName.get(phase);
      let t = e.properties && e.properties.t ? e.properties.t.getValue(viewer.clock.currentTime) : undefined;
      if (t === undefined && e.availability && e.availability.length > 0)
        t = missionSeconds(epoch, e.availability.start);
      if (t === undefined && p) {      // lvsim export's numbering: 0 the phase start, k its k-th event
        const x = Number(k) > 0 ? (p.events || [])[Number(k) - 1] : undefined;
        t = x ? x.t : p.t_start;
      }
      const text = (e.label && e.label.text && e.label.text.getValue(at(t || 0))) || e.name || e.id;
      events.push({ t: t || 0, text, phase, entity: e });
    }
    // Markers at the same instant and place (a parent's end event and its children's starts)
    // share one label, and labels get a dark background so phase-coloured text reads.
    const groups = [];
    for (const ev of events) {
      const where = ev.entity.position && ev.entity.position.getValue(at(ev.t));
      const g = groups.find((x) => Math.abs(x.t - ev.t) < 1e-3 && where && x.where &&
                                   Cesium.Cartesian3.distance(x.where, where) < 1.0);
      if (g) g.members.push(ev);
      else groups.push({ t: ev.t, where, members: [ev] });
    }
    for (const g of groups) {
      g.members.forEach((ev, i) => {
        const lab = ev.entity.label;
        if (!lab) return;
        if (i > 0) { lab.show = false; return; }
        if (g.members.length > 1) lab.text = g.members.map((x) => x.text).join(' / ');
        lab.showBackground = true;
        lab.backgroundColor = new Cesium.Color(0.1, 0.1, 0.12, 0.75);
      });
    }
    // Labels only on the selected entity (a vehicle, a marker; a marker group's one label on
    // any of its members): bodies that fly together and markers at one place never write over
    // each other. The phase and event lists name everything; click one to see its label.
    const labelOwner = new Map();      // entity -> the entities whose selection shows its label
    for (const g of groups) {
      g.members.forEach((ev, i) => { if (i === 0) labelOwner.set(ev.entity, g.members.map((x) => x.entity)); });
    }
    const labelled = [...entities, ...viewer.entities.values].filter((e) => e.label);
    for (const e of labelled) {
      const owners = labelOwner.get(e) || (e.id.startsWith('event/') ? [] : [e]);
      e.label.show = new Cesium.CallbackProperty(() => owners.includes(viewer.selectedEntity), false);
    }
    viewer.selectedEntityChanged.addEventListener(() => settle());
    state.shownLabels = () => labelled.filter((e) => e.isShowing && e.isAvailable(viewer.clock.currentTime) &&
      e.label.show.getValue(viewer.clock.currentTime)).map((e) => e.id);
    if (events.length === 0) {   // no markers in the CZML: list the summary's events
      for (const p of summary.phases) {
        for (const x of p.events || []) if (x.name) events.push({ t: x.t, text: x.name, phase: p.name });
      }
    }
    events.sort((a, b) => a.t - b.t);
    for (const ev of events) {
      const li = el('li');
      li.appendChild(el('span', fmtT(ev.t), 't'));
      li.appendChild(document.createTextNode(ev.text.includes(ev.phase) ? ev.text : `${ev.text} (${ev.phase})`));
      li.addEventListener('click', () => {
        viewer.clock.currentTime = at(ev.t);
        if (ev.entity) viewer.selectedEntity = ev.entity;
      });
      $('events').appendChild(li);
    }
    state.events = events.map((e) => ({ t: e.t, text: e.text, phase: e.phase }));

    // Clock controls and the current-phase highlight.
    const play = $('play');
    const syncPlay = () => { play.textContent = viewer.clock.shouldAnimate ? 'Pause' : 'Play'; };
    play.addEventListener('click', () => {
      if (!viewer.clock.shouldAnimate &&
          Cesium.JulianDate.greaterThanOrEquals(viewer.clock.currentTime, viewer.clock.stopTime))
        viewer.clock.currentTime = viewer.clock.startTime.clone();
      viewer.clock.shouldAnimate = !viewer.clock.shouldAnimate;
      syncPlay();
    });
    // Whole tracks (default) or only what has been flown up to the clock time.
    const duration = missionSeconds(epoch, viewer.clock.stopTime) - missionSeconds(epoch, viewer.clock.startTime);
    const lead = new Map(tracks.map((t) => [t, t.entity.path ? t.entity.path.leadTime : undefined]));
    const setWhole = (on) => {
      for (const t of tracks) {
        if (t.entity.path) t.entity.path.leadTime = on ? duration + 1.0 : lead.get(t);
      }
      settle();
    };
    $('whole').addEventListener('change', (ev) => setWhole(ev.target.checked));
    setWhole($('whole').checked);
    $('restart').addEventListener('click', () => { viewer.clock.currentTime = viewer.clock.startTime.clone(); });
    let lastKey = '';
    viewer.clock.onTick.addEventListener((clock) => {
      syncPlay();
      const s = missionSeconds(epoch, clock.currentTime);
      const key = summary.phases.filter((p) => s >= p.t_start && s <= p.t_end).map((p) => p.name).join(',');
      if (key === lastKey) return;
      lastKey = key;
      const on = new Set(key.split(','));
      for (const [name, r] of rows) r.tr.classList.toggle('current', on.has(name));
    });

    const bs = trackSphere(tracks, at);
    $('home').addEventListener('click', () => { flyHome(bs, 1.5); });
    await flyHome(bs, 1.5);
    settle();
    setStatus(`${tracks.length} tracks, ${models.length} vehicle models, ${events.length} events`);
    state.summary = summary;
    state.dataSource = ds;
    state.ready = true;
  }

  main().catch((err) => {
    state.error = String(err && err.message ? err.message : err);
    setStatus(`cannot load the mission: ${state.error}`, true);
    console.error('lvsim viewer:', err);
  });
})();
