// The time plots (uPlot): upper-body tilt, CoM and ZMP/CoP against the support polygon, desired
// and measured contact forces and torques of each foot, FSM state, controller cycle time, joint
// angles against their limits. Each plot shows the replay's time as a vertical line.
import uPlot from 'uplot';

const BLUE = '#1f77b4', ORANGE = '#ff7f0e', GREEN = '#2ca02c', RED = '#d62728', PURPLE = '#9467bd';
const BROWN = '#8c564b', GREY = '#7f7f7f';

const line = (label, values, stroke, extra = {}) => ({ label, values, stroke, ...extra });
// Desired traces are dashed, a little wider, and listed after the measured ones so that uPlot draws
// them on top: a measured trace that follows its target closely does not hide it.
const desired = (label, values, stroke) => line(label, values, stroke, { dash: [7, 4], width: 2 });
const bound = (label, values) => line(label, values, GREY, { dash: [2, 3], width: 1 });

function definitions(data) {
  const L = data.log;
  const defs = [
    {
      title: 'Upper-body tilt against gravity φ_x (sagittal), φ_y (lateral)', unit: '°',
      series: [line('φ_x', L.phi_x, BLUE), line('φ_y', L.phi_y, ORANGE)],
    },
  ];
  // Relative to the planned CoM, so that a long walk keeps its scale (the page's data is absolute).
  for (const [axis, name] of [['x', 'x (forward)'], ['y', 'y (lateral)']]) {
    const ref = L[`com_des_${axis}`];
    const rel = (values) => values.map((v, i) => (v === null ? null : v - ref[i]));
    defs.push({
      title: `CoM and ZMP/CoP against the support polygon, ${name}, relative to the planned CoM`, unit: 'm',
      series: [
        bound('support polygon min', rel(L[`support_${axis}_min`])),
        bound('support polygon max', rel(L[`support_${axis}_max`])),
        line('CoM estimated', rel(L[`com_est_${axis}`]), PURPLE),
        line('CoM true', rel(L[`com_${axis}`]), BROWN),
        line('CoP measured', rel(L[`cop_${axis}`]), BLUE),
        desired('ZMP desired', rel(L[`zmp_des_${axis}`]), RED),
      ],
    });
  }
  for (const foot of data.feet) {
    defs.push({
      title: `${foot.side} foot: normal force F_z, desired against measured`, unit: 'N',
      series: [line('F_z measured', foot.fz, BLUE), desired('F_z desired', foot.fz_des, GREEN)],
    });
    defs.push({
      title: `${foot.side} foot: torques T_x, T_y, desired against measured`, unit: 'N·m',
      series: [
        line('T_x measured', foot.tx, BLUE), line('T_y measured', foot.ty, ORANGE),
        desired('T_x desired', foot.tx_des, GREEN), desired('T_y desired', foot.ty_des, RED),
      ],
    });
  }
  defs.push({
    title: 'Walking state machine', unit: '', states: L.states,
    series: [line('state', L.state, BLUE, { paths: uPlot.paths.stepped({ align: 1 }) })],
  });
  defs.push({
    title: 'Controller cycle time (wall clock)', unit: 'µs',
    series: [line('longest cycle of the log interval', L.cycle_us_max, RED, { width: 1 }),
      line('logged cycle', L.cycle_us, BLUE, { width: 1 })],
  });
  return defs;
}

// One small plot per joint, scaled to the joint's own motion (a few degrees of a 180° range would
// be a flat line on a scale from limit to limit); a limit is drawn where the motion comes near it,
// and the title gives the closest approach to any limit.
function jointDefinitions(data) {
  const n = data.log.t.length;
  const constant = (v) => new Array(n).fill(v);
  return data.joints.map((j) => {
    const q = j.q.filter((v) => v !== null && Number.isFinite(v));
    const lo = q.length ? q.reduce((a, b) => Math.min(a, b)) : j.lower;
    const hi = q.length ? q.reduce((a, b) => Math.max(a, b)) : j.upper;
    const pad = Math.max(2, 0.15 * (hi - lo));
    const margins = [['software lower', lo - j.soft_lower], ['software upper', j.soft_upper - hi]];
    const [which, margin] = margins.reduce((a, b) => (b[1] < a[1] ? b : a));
    return {
      title: `${j.name}: closest ${margin.toFixed(1)}° to its ${which} limit`, unit: '°', small: true,
      yRange: [Math.max(j.lower - 1, lo - pad), Math.min(j.upper + 1, hi + pad)],
      series: [
        line('angle', j.q, BLUE),
        line('lower limit', constant(j.lower), RED, { width: 1 }),
        line('upper limit', constant(j.upper), RED, { width: 1 }),
        line('software lower', constant(j.soft_lower), ORANGE, { dash: [4, 3], width: 1 }),
        line('software upper', constant(j.soft_upper), ORANGE, { dash: [4, 3], width: 1 }),
      ],
    };
  });
}

function makePlot(container, def, t, cursor, setTime) {
  const box = document.createElement('div');
  box.className = def.small ? 'plot small' : 'plot';
  container.appendChild(box);
  const width = () => Math.max(200, box.clientWidth);
  const yAxis = { label: def.unit, size: def.states ? 90 : 55 };
  if (def.states) {
    yAxis.values = (u, splits) => splits.map((v) => (Number.isInteger(v) ? def.states[v] ?? '' : ''));
    yAxis.splits = () => def.states.map((_, i) => i);
  }
  const opts = {
    title: def.title,
    width: width(),
    height: def.small ? 150 : 230,
    cursor: { sync: { key: 'time' } },
    legend: { show: !def.small },
    scales: {
      x: { time: false },
      ...(def.states ? { y: { range: [-0.5, def.states.length - 0.5] } } : {}),
      ...(def.yRange ? { y: { range: def.yRange } } : {}),
    },
    axes: [{ label: 't [s]', size: 36 }, yAxis],
    series: [{ label: 't' }, ...def.series.map((s) => ({
      label: s.label, stroke: s.stroke, width: s.width ?? 1.5, dash: s.dash, paths: s.paths, spanGaps: false,
    }))],
    hooks: { setScale: [() => place()] },
  };
  const plot = new uPlot(opts, [t, ...def.series.map((s) => s.values)], box);
  plot.title = def.title;

  // The replay time: a line over the plot, moved without redrawing the plot.
  const marker = document.createElement('div');
  marker.className = 'time-marker';
  plot.over.appendChild(marker);
  function place() {
    const x = plot.valToPos(cursor.t, 'x');
    marker.style.display = Number.isFinite(x) && x >= 0 && x <= plot.over.clientWidth ? 'block' : 'none';
    marker.style.left = `${x}px`;
  }
  cursor.listeners.push(place);
  plot.over.addEventListener('click', () => {
    if (plot.cursor.left >= 0) setTime(plot.posToVal(plot.cursor.left, 'x'));
  });
  window.addEventListener('resize', () => plot.setSize({ width: width(), height: opts.height }));
  return plot;
}

export function createPlots(container, data, cursor, setTime) {
  const t = data.log.t;
  const main = document.createElement('div');
  main.className = 'plot-grid';
  container.appendChild(main);
  const plots = definitions(data).map((d) => makePlot(main, d, t, cursor, setTime));
  const heading = document.createElement('h2');
  heading.textContent = 'Joint angles, each on the scale of its own motion, against their limits (red: hard, orange dashed: software)';
  container.appendChild(heading);
  const joints = document.createElement('div');
  joints.className = 'plot-grid joints';
  container.appendChild(joints);
  return plots.concat(jointDefinitions(data).map((d) => makePlot(joints, d, t, cursor, setTime)));
}
