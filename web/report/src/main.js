// The report page: reads the run's data (JSON embedded by `biped run`), lays out the summary,
// the 3D replay and the plots, and keeps them on one time cursor.
import uPlotCss from 'uplot/dist/uPlot.min.css';
import { createPlots } from './plots.js';
import { createReplay } from './replay.js';
import pageCss from './report.css';

function element(tag, attributes = {}, children = []) {
  const e = document.createElement(tag);
  for (const [k, v] of Object.entries(attributes)) {
    if (k === 'text') e.textContent = v;
    else e.setAttribute(k, v);
  }
  for (const c of children) e.appendChild(c);
  return e;
}

function summaryTable(data) {
  const s = data.summary;
  const fmt = (v, digits = 2) => (typeof v === 'number' ? v.toFixed(digits) : String(v));
  const rows = [
    ['robot', s.robot],
    ['scenario', s.scenario],
    ['simulated', `${fmt(s.sim_time_s, 1)} s in ${fmt(s.wall_time_s)} s (${fmt(s.realtime_factor, 1)}× real time)`],
    ['fall', s.fell ? `at ${fmt(s.fall_time_s)} s: ${s.fall_reason}` : 'no'],
    ['distance', `${fmt(s.distance_m)} m, ${s.steps} steps, mean ${fmt(s.mean_speed_mps)} m/s`],
    ['upper-body tilt', `RMS ${fmt(s.upper_body_tilt_deg.rms_x)}° / ${fmt(s.upper_body_tilt_deg.rms_y)}°, max ${fmt(s.upper_body_tilt_deg.max)}°`],
    ['controller cycle', `median ${fmt(s.controller_cycle_us.median, 1)} µs, p99 ${fmt(s.controller_cycle_us.p99, 1)} µs, max ${fmt(s.controller_cycle_us.max, 1)} µs`],
    ['final state', s.fault ? `${s.final_state} (fault: ${s.fault})`
      : s.fault_after_fall ? `${s.final_state} (after the fall, its impact tripped the sensor check: ${s.fault_after_fall})`
        : s.final_state],
  ];
  return element('table', { class: 'summary' },
    rows.map(([k, v]) => element('tr', {}, [element('th', { text: k }), element('td', { text: v })])));
}

function main() {
  const data = JSON.parse(document.getElementById('report-data').textContent);
  document.head.appendChild(element('style', { text: uPlotCss + pageCss }));
  document.title = `${data.summary.scenario} (${data.summary.robot}): biped run report`;

  const viewer = element('div', { id: 'viewer' });
  const controls = element('div', { id: 'controls' });
  const plots = element('div', { id: 'plots' });
  document.body.appendChild(element('header', {}, [
    element('h1', { text: `${data.summary.scenario}: ${data.summary.robot}` }), summaryTable(data)]));
  document.body.appendChild(element('section', { id: 'replay' }, [viewer, controls]));
  document.body.appendChild(plots);

  // One time cursor: the replay's time, shown as a line in every plot; a click in a plot moves it.
  const cursor = { t: 0, listeners: [] };
  const setTime = (t) => {
    cursor.t = Math.min(Math.max(t, data.replay.t[0] ?? 0), data.replay.t[data.replay.t.length - 1] ?? 0);
    for (const f of cursor.listeners) f(cursor.t);
  };
  // Without WebGL the plots still work; the viewer says why it stays empty.
  let replay = null;
  try {
    replay = createReplay(viewer, controls, data, cursor, setTime);
  } catch (e) {
    viewer.textContent = `The 3D replay needs WebGL, which this browser does not provide (${e.message}).`;
    console.error(e);
  }
  const charts = createPlots(plots, data, cursor, setTime);
  setTime(0);

  // For the browser test and for scripting the page from a console.
  window.__report = {
    ready: true,
    time: () => cursor.t,
    setTime,
    // A getter: uPlot settles its scales after the first draw, not while the page is being built.
    get plots() {
      return charts.map((c) => ({
        title: c.title,
        points: c.data[0].length,
        series: c.data.slice(1).map((s) => s.filter((v) => v !== null && Number.isFinite(v)).length),
        labels: c.series.slice(1).map((s) => s.label),
        dashed: c.series.slice(1).map((s) => Array.isArray(s.dash) && s.dash.length > 0),
        yRange: [c.scales.y.min, c.scales.y.max],
      }));
    },
    bodyPosition: (name) => replay?.bodyPosition(name) ?? null,
    pelvis: () => replay?.bodyPosition(data.model.bodies[data.model.pelvis]) ?? null,
    canvas: () => replay?.canvas ?? null,
    render: () => replay?.render(),
  };
}

main();
