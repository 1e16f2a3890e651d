// The page of `scatterlab explore` (sim/explore/api.cpp serves it and its JSON API). Every
// change of a parameter asks the server for the profiles at once and redraws them with Plotly;
// the plotted series are kept on window.explore for the browser test (tests/explore).
'use strict';

const CHANNELS = ['red', 'green', 'blue'];
const COLOURS = {
  dipole: '#1f77b4', better_dipole: '#d62728', quantized_diffusion: '#2ca02c',
  single_scatter: '#9467bd',
};
const EXTRA_COLOURS = ['#ff7f0e', '#8c564b', '#e377c2', '#17becf', '#bcbd22', '#7f7f7f'];
const MC_COLOURS = ['#000000', '#555555', '#8c564b', '#e377c2'];

const state = {
  // Per channel: the canonical parameters, in 1 / (the material's length unit).
  channels: [0, 1, 2].map(() => ({ sigma_a: 0.0021, sigma_s_reduced: 2.19, g: 0, R_dr: null, l_d: null })),
  mode: 'coefficients',
  info: null,
  presets: [],
  textModels: [],
  files: [],
  openFiles: {},  // path -> the file's JSON (/api/file)
  profileSeq: 0,
  sphereSeq: 0,
  invertSeq: [0, 0, 0],
  // Requests the server refused, by source ('profiles', 'sphere', 'mesh', 'invert-0', ...): each
  // {message, channel}, drawn beside the input its message names by showProblems().
  failures: {},
  lastEdited: [null, null, null],  // per channel, the key typed last (α′ or mfp in that mode)
  started: false,
};

// What the browser test reads: the series as plotted (raw R_d, before the plot mode's transform).
window.explore = { series: {}, updates: 0, sphereUpdates: 0, ready: false, lastProfile: null, errors: [] };

const $ = (id) => document.getElementById(id);

// A message that names no input of the page (a file that would not load, a server that does not
// answer): shown above the plots.
function showError(message) {
  const box = $('error');
  box.textContent = message || '';
  box.hidden = !message;
}

// ---- refused inputs: the message beside the field, the field marked, the status, stale plots ----

// A request of `source` refused with `error` (or answered: error null). `channel`: the channel
// whose medium the request sent, when it sent one.
function reportFailure(source, error, channel) {
  if (error) {
    state.failures[source] = { message: error.message, channel };
    window.explore.errors.push(`${source}: ${error.message}`);
  } else {
    delete state.failures[source];
  }
  showProblems();
}

// Inputs of the page by the field names of the server's refusals ("<field>: <problem>; accepted:
// ...", sim/explore/request_fields.cpp); `points` and `model` depend on the request.
const FIELD_INPUTS = {
  eta: 'eta', scale: 'scale', r_max: 'r-max', radius: 'sphere-radius', samples: 'sphere-samples',
  cluster_angle: 'mesh-epsilon', 'light.azimuth': 'light-azimuth', 'light.elevation': 'light-elevation',
};
const CHANNEL_KEYS = ['sigma_a', 'sigma_s', 'sigma_s_reduced', 'g', 'R_dr', 'l_d'];

// The mesh's refusal of a channel's coefficient names the key but not the channel: the channel is
// the one holding the value the message quotes ("sigma_a: got -1.000000; ...", times scale).
function channelQuoted(key, message) {
  const got = Number((/: got ([^;\s]+)/.exec(message) || [])[1]);
  if (!Number.isFinite(got)) return undefined;
  const value = (c) => (key === 'sigma_a' ? c.sigma_a * scale()
    : key === 'sigma_s' ? (c.sigma_s_reduced * scale()) / (1 - c.g) : c[key]);
  const found = state.channels.findIndex((c) => Math.abs(value(c) - got) <= 1e-6 * (1 + Math.abs(got)));
  return found >= 0 ? found : undefined;
}

// The input a refusal of `source` names, or null.
function inputFor(source, failure) {
  const field = (/^([\w.[\]]+): /.exec(failure.message) || [])[1];
  if (!field) return null;
  const [, index, rest] = /^(?:medium\.|media\[(\d)\]\.)?(.*)$/.exec(field);
  let key = rest;
  if (CHANNEL_KEYS.includes(key)) {
    const channel = index !== undefined ? Number(index)
      : failure.channel !== undefined ? failure.channel : channelQuoted(key, failure.message);
    if (channel === undefined) return null;
    if (key === 'sigma_s') key = 'sigma_s_reduced';  // sigma_s = σ′_s / (1 − g): the σ′_s typed
    // In the α′, mfp mode the coefficients come from the one of the two typed last.
    if (state.mode === 'albedo' && key !== 'g') key = state.lastEdited[channel] === 'mfp' ? 'mfp' : 'albedo';
    return $(`${key}-${CHANNELS[channel]}`);
  }
  if (key === 'points') return $(source === 'mesh' ? 'mesh-points' : 'points');
  if (key === 'model') return $(source === 'mesh' ? 'mesh-model' : 'inversion-model');
  if (key.startsWith('mesh')) return $('mesh-shape');
  return FIELD_INPUTS[key] ? $(FIELD_INPUTS[key]) : null;
}

// How the status line names an input: its row and channel in the table, else its label.
function fieldName(input) {
  const row = input.closest('#channels tr');
  if (row) return `${row.cells[0].textContent.replace(/\s*\[.*\]$/, '')} (${CHANNELS[input.dataset.channel]})`;
  const label = input.closest('label');
  const text = label && label.firstChild.nodeType === Node.TEXT_NODE ? label.firstChild.textContent.trim() : '';
  // The plot and the mesh both have "points".
  const view = input.closest('#mesh-controls') ? 'mesh ' : input.closest('#sphere-controls') ? 'lit sphere ' : '';
  return text ? view + text : input.id;
}

function markField(input, message) {
  const id = `${input.id}-error`;
  const existing = $(id);
  if (existing) {  // the same field refused by another request (profiles, lit sphere, mesh)
    if (!existing.textContent.split('\n').includes(message)) existing.textContent += `\n${message}`;
    return;
  }
  input.classList.add('invalid');
  input.setAttribute('aria-invalid', 'true');
  input.setAttribute('aria-describedby', id);
  const box = document.createElement('span');
  box.id = id;
  box.className = 'error field-error';
  box.textContent = message;
  const row = input.closest('#channels tr');
  if (row) {
    // A row of its own under the field's row, the whole table wide: the message stays readable
    // and the table keeps its three columns.
    const tr = document.createElement('tr');
    tr.className = 'field-error-row';
    const td = document.createElement('td');
    td.colSpan = row.cells.length;
    td.appendChild(box);
    tr.appendChild(td);
    let after = row;
    while (after.nextElementSibling && after.nextElementSibling.classList.contains('field-error-row')) after = after.nextElementSibling;
    after.after(tr);
  } else {
    (input.closest('label') || input).after(box);
  }
}

// Draws state.failures: every message beside its field (or above the plots if it names none),
// the status line, and the views whose last request was refused greyed as stale.
function showProblems() {
  document.querySelectorAll('.field-error-row, .field-error').forEach((e) => e.remove());
  document.querySelectorAll('.invalid').forEach((input) => {
    input.classList.remove('invalid');
    input.removeAttribute('aria-invalid');
    input.removeAttribute('aria-describedby');
  });
  const named = [], general = [];
  for (const [source, failure] of Object.entries(state.failures)) {
    const input = inputFor(source, failure);
    if (input) {
      markField(input, failure.message);
      if (!named.includes(fieldName(input))) named.push(fieldName(input));
    } else {
      general.push(`${source}: ${failure.message}`);
    }
  }
  showError(general.join('\n'));
  // A refused inversion leaves the coefficients of before: every view is then stale.
  const inverting = Object.keys(state.failures).some((source) => source.startsWith('invert'));
  for (const [id, source] of [['profile-plot', 'profiles'], ['sphere-plot', 'sphere'], ['mesh-view', 'mesh']]) {
    $(id).classList.toggle('stale', inverting || source in state.failures);
  }
  // The lines under the profiles describe them: as stale as they are.
  for (const id of ['derived', 'timing']) $(id).classList.toggle('stale-text', $('profile-plot').classList.contains('stale'));
  const status = $('status');
  const failed = named.length + general.length > 0;
  status.classList.toggle('error', failed);
  if (failed) {
    status.textContent = named.length ? `error: ${named.join(', ')} rejected` : `error: ${general[0]}`;
    status.title = Object.values(state.failures).map((f) => f.message).join('\n');
  } else {
    status.textContent = state.started ? 'ready' : 'loading…';
    status.title = '';
  }
}

function clearInversionFailures() {
  for (const source of Object.keys(state.failures)) if (source.startsWith('invert')) delete state.failures[source];
}

async function api(path, body) {
  const options = body === undefined ? {} : {
    method: 'POST', headers: { 'Content-Type': 'application/json' }, body: JSON.stringify(body),
  };
  const response = await fetch(path, options);
  const answer = await response.json();
  if (!response.ok) throw new Error(answer.error || `HTTP ${response.status}`);
  return answer;
}

function unit() { return $('unit').value.trim() || 'mm'; }
function scale() { return Number($('scale').value); }
// The plot's length unit: the material's, or (scale != 1) units of `scale` of it.
function plotUnit() {
  const s = scale();
  return s === 1 ? unit() : `${s} ${unit()}`;
}

function format(x) {
  if (x === null || x === undefined || !Number.isFinite(x)) return '–';
  return Number(x.toPrecision(6)).toString();
}

// ---- the per-channel parameter table ----

const ROWS = {
  coefficients: [
    { key: 'sigma_a', label: () => `σ<sub>a</sub> [1/${unit()}]`, title: 'absorption coefficient' },
    { key: 'sigma_s_reduced', label: () => `σ′<sub>s</sub> [1/${unit()}]`, title: 'reduced scattering coefficient σ_s (1 − g)' },
    { key: 'g', label: () => 'g', title: 'Henyey-Greenstein mean cosine' },
  ],
  albedo: [
    { key: 'albedo', label: () => 'α′', title: 'reduced albedo σ′_s / σ′_t, in [0, 1]' },
    { key: 'mfp', label: () => `mfp [${unit()}]`, title: 'reduced mean free path 1 / σ′_t' },
    { key: 'g', label: () => 'g', title: 'Henyey-Greenstein mean cosine' },
  ],
  appearance: [
    { key: 'R_dr', label: () => 'R<sub>dr</sub>', title: 'total diffuse reflectance (Bitterli §3.4)' },
    { key: 'l_d', label: () => `l<sub>d</sub> [${unit()}]`, title: 'diffuse mean free path 1 / σ_tr' },
    { key: 'g', label: () => 'g', title: 'Henyey-Greenstein mean cosine' },
  ],
};

function shown(channel, key) {
  const c = state.channels[channel];
  const sigmaTReduced = c.sigma_a + c.sigma_s_reduced;
  if (key === 'albedo') return sigmaTReduced > 0 ? c.sigma_s_reduced / sigmaTReduced : 0;
  if (key === 'mfp') return sigmaTReduced > 0 ? 1 / sigmaTReduced : Infinity;
  return c[key];
}

function buildRows() {
  const body = $('channel-rows');
  body.innerHTML = '';
  for (const row of ROWS[state.mode]) {
    const tr = document.createElement('tr');
    const th = document.createElement('td');
    th.innerHTML = row.label();
    th.title = row.title;
    tr.appendChild(th);
    CHANNELS.forEach((name, channel) => {
      const td = document.createElement('td');
      const input = document.createElement('input');
      input.type = 'number';
      input.step = 'any';
      input.id = `${row.key}-${name}`;
      input.dataset.key = row.key;
      input.dataset.channel = channel;
      input.title = `${row.title}, ${name}`;
      const value = shown(channel, row.key);
      input.value = value === null || value === undefined ? '' : format(value);
      input.addEventListener('input', onChannelInput);
      td.appendChild(input);
      tr.appendChild(td);
    });
    body.appendChild(tr);
  }
  $('inversion-model-label').hidden = state.mode !== 'appearance';
  showProblems();  // the table's inputs are new: mark them again
}

async function onChannelInput(event) {
  const input = event.target;
  const channel = Number(input.dataset.channel);
  const key = input.dataset.key;
  const value = Number(input.value);
  if (input.value.trim() === '' || !Number.isFinite(value)) return;  // while typing
  const c = state.channels[channel];
  state.lastEdited[channel] = key;
  // The material is no longer the preset's.
  $('preset').value = '';
  $('preset-source').textContent = '';
  if (key === 'albedo' || key === 'mfp') {
    // α′ = σ′_s / σ′_t, mfp = 1 / σ′_t (Bitterli eqs. 2.23-2.24).
    const albedo = key === 'albedo' ? value : shown(channel, 'albedo');
    const mfp = key === 'mfp' ? value : shown(channel, 'mfp');
    const sigmaTReduced = 1 / mfp;
    c.sigma_s_reduced = albedo * sigmaTReduced;
    c.sigma_a = sigmaTReduced - c.sigma_s_reduced;
  } else {
    c[key] = value;
  }
  if (state.mode === 'appearance') {
    if (key === 'g' && (c.R_dr === null || c.l_d === null)) { update(); return; }
    await invertChannel(channel);
  }
  update();
}

async function invertChannel(channel) {
  const c = state.channels[channel];
  if (c.R_dr === null || c.l_d === null) return;
  // Each key typed asks again, and the answers may come back in another order: the last asked wins.
  const seq = ++state.invertSeq[channel];
  try {
    const answer = await api('/api/invert', {
      model: $('inversion-model').value, R_dr: c.R_dr, l_d: c.l_d,
      eta: Number($('eta').value), g: c.g,
    });
    if (seq !== state.invertSeq[channel]) return;
    c.sigma_a = answer.sigma_a;
    c.sigma_s_reduced = answer.sigma_s_reduced;
    reportFailure(`invert-${channel}`, null);
  } catch (error) {
    if (seq === state.invertSeq[channel]) reportFailure(`invert-${channel}`, error, channel);
  }
}

// ---- models ----

function buildModels() {
  const box = $('models');
  box.innerHTML = '';
  for (const model of state.info.models) {
    const label = document.createElement('label');
    label.className = 'model-row';
    label.title = model.reference;
    label.innerHTML = `<input type="checkbox" id="model-${model.name}" data-model="${model.name}" checked> ` +
      `<span style="color:${COLOURS[model.name]}">■</span> ${model.label}`;
    box.appendChild(label);
  }
  box.querySelectorAll('input').forEach((input) => input.addEventListener('change', () => { update(); updateSphere(); }));
  buildTextModels();
}

function textColour(index) { return EXTRA_COLOURS[index % EXTRA_COLOURS.length]; }

function buildTextModels() {
  const box = $('text-models');
  box.innerHTML = '';
  // The mesh view renders the text models too, beside the built-in ones.
  const meshModel = $('mesh-model');
  if (meshModel) {
    const chosen = meshModel.value;
    meshModel.querySelectorAll('option[data-text]').forEach((o) => o.remove());
    for (const model of state.textModels) {
      const option = document.createElement('option');
      option.value = model.name;
      option.dataset.text = 'yes';
      option.textContent = `${model.name} (text)`;
      meshModel.appendChild(option);
    }
    if ([...meshModel.options].some((o) => o.value === chosen)) meshModel.value = chosen;
  }
  state.textModels.forEach((model, index) => {
    const row = document.createElement('div');
    const label = document.createElement('label');
    label.className = 'model-row';
    label.title = `${model.description}\n${model.reference}\n(${model.file})`;
    label.innerHTML = `<input type="checkbox" id="model-${model.name}" data-model="${model.name}" checked> ` +
      `<span style="color:${textColour(index)}">■</span> ${model.name} <span class="note">(${model.file})</span>`;
    label.querySelector('input').addEventListener('change', update);
    row.appendChild(label);
    for (const p of model.parameters) {
      const line = document.createElement('label');
      line.className = 'parameter';
      const step = (p.max - p.min) / 200;
      line.innerHTML = `${p.name} <input type="range" id="param-${model.name}-${p.name}" min="${p.min}" max="${p.max}" step="${step}" value="${p.default}"> <span>${format(p.default)}</span>`;
      const slider = line.querySelector('input');
      slider.addEventListener('input', () => { line.querySelector('span').textContent = format(Number(slider.value)); update(); });
      row.appendChild(line);
    }
    box.appendChild(row);
  });
}

function checkedModels() {
  return [...document.querySelectorAll('#models input:checked, #text-models input[type=checkbox]:checked')]
    .map((input) => input.dataset.model);
}

function textParameters() {
  const parameters = {};
  for (const model of state.textModels) {
    parameters[model.name] = {};
    for (const p of model.parameters) parameters[model.name][p.name] = Number($(`param-${model.name}-${p.name}`).value);
  }
  return parameters;
}

async function reloadModels() {
  try {
    state.textModels = await api('/api/models');
    $('models-error').hidden = true;
    buildTextModels();
    update();
  } catch (error) {
    $('models-error').textContent = error.message;
    $('models-error').hidden = false;
  }
}

// ---- the request for one channel ----

function mediumOf(channel) {
  const c = state.channels[channel];
  return { sigma_a: c.sigma_a, sigma_s_reduced: c.sigma_s_reduced, g: c.g, eta: Number($('eta').value) };
}

// What a plot drawn from `channel`'s medium shows: after "use this medium" (or a grey material)
// all three channels hold one medium, and naming one channel would mislead.
function channelTitle(channel) {
  const [r, g, b] = state.channels.map((c) => `${c.sigma_a} ${c.sigma_s_reduced} ${c.g}`);
  return r === g && g === b ? 'all channels equal' : `${CHANNELS[channel]} channel`;
}

function profileRequest(channel) {
  const request = {
    medium: mediumOf(channel),
    scale: scale(),
    points: Number($('points').value),
    models: checkedModels(),
    parameters: textParameters(),
  };
  const rMax = $('r-max').value.trim();
  if (rMax !== '') request.r_max = Number(rMax);
  return request;
}

// ---- plotting ----

// The plot mode's transform of R_d at r (Bitterli §3.6.3: linear, log, sqrt, r R_d).
function transform(mode, r, value) {
  if (value === null || !Number.isFinite(value)) return null;
  if (mode === 'sqrt') return Math.sqrt(Math.max(value, 0));
  if (mode === 'r') return r * value;
  if (mode === 'log') return value > 0 ? value : null;
  return value;
}

function yTitle(mode) {
  const u = plotUnit();
  if (mode === 'r') return `r · R<sub>d</sub>(r)  [1/${u}]`;
  if (mode === 'sqrt') return `R<sub>d</sub>(r)  [1/${u}²], square-root scale`;
  return `R<sub>d</sub>(r)  [1/${u}²]`;
}

// Ticks of a square-root axis labelled with the values of R_d.
function sqrtTicks(maxValue) {
  if (!(maxValue > 0)) return {};
  const values = [];
  const top = maxValue;
  for (const f of [0, 0.01, 0.05, 0.1, 0.2, 0.4, 0.6, 0.8, 1.0]) values.push(f * top);
  return { tickvals: values.map(Math.sqrt), ticktext: values.map((v) => format(Number(v.toPrecision(2)))) };
}

function profileTraces(answer, mode) {
  const traces = [];
  const series = {};
  const labels = Object.fromEntries(state.info.models.map((m) => [m.name, m.label]));
  answer.curves.forEach((curve) => {
    const index = state.textModels.findIndex((m) => m.name === curve.model);
    const colour = COLOURS[curve.model] || textColour(Math.max(index, 0));
    series[curve.model] = { r: answer.r, values: curve.values };
    traces.push({
      name: labels[curve.model] || `${curve.model} (text)`,
      x: answer.r,
      y: curve.values.map((v, k) => transform(mode, answer.r[k], v)),
      customdata: curve.values,
      mode: 'lines',
      line: { color: colour, width: 2, dash: index >= 0 ? 'dash' : 'solid' },
      hovertemplate: `r = %{x:.4g} ${plotUnit()}<br>R<sub>d</sub> = %{customdata:.5g} /${plotUnit()}²<extra>%{fullData.name}</extra>`,
    });
  });
  // Monte Carlo files, with their standard errors as error bars.
  Object.values(state.openFiles).forEach((file, n) => {
    if (file.kind !== 'searchlight') return;
    for (const tally of file.tallies) {
      if (!$(`tally-${file.path}-${tally.name}`) || !$(`tally-${file.path}-${tally.name}`).checked) continue;
      const upper = [], lower = [];
      const y = tally.mean.map((m, k) => {
        const s = tally.stderr[k];
        const value = transform(mode, file.r[k], m);
        const high = transform(mode, file.r[k], m + s);
        const low = transform(mode, file.r[k], Math.max(m - s, mode === 'log' ? m * 1e-3 : 0));
        upper.push(value === null || high === null ? 0 : high - value);
        lower.push(value === null || low === null ? 0 : value - low);
        return value;
      });
      series[`mc:${file.path}:${tally.name}`] = { r: file.r, values: tally.mean };
      traces.push({
        name: `MC ${file.name}: ${tally.name} (r in ${file.medium.length_unit})`,
        x: file.r, y, customdata: tally.stderr.map((s, k) => [tally.mean[k], s]),
        mode: 'markers',
        marker: { color: MC_COLOURS[n % MC_COLOURS.length], size: 5 },
        error_y: { type: 'data', symmetric: false, array: upper, arrayminus: lower, thickness: 1, width: 2 },
        hovertemplate: `r = %{x:.4g} ${file.medium.length_unit}<br>R<sub>d</sub> = %{customdata[0]:.5g} ± %{customdata[1]:.2g}<extra>%{fullData.name}</extra>`,
      });
    }
  });
  return { traces, series };
}

// `what`: channelTitle() of the request's channel, taken when the request was sent.
function drawProfiles(answer, what) {
  const mode = $('plot-mode').value;
  const { traces, series } = profileTraces(answer, mode);
  let maxValue = 0;
  for (const t of traces) for (const v of t.customdata) if (typeof v === 'number' && Number.isFinite(v)) maxValue = Math.max(maxValue, v);
  // A log axis spans at most nine decades below the largest value: the exact single scattering
  // falls far faster than diffusion, and would otherwise squeeze every other curve to the top.
  let logRange = null;
  if (mode === 'log' && maxValue > 0) {
    let minValue = maxValue;
    for (const t of traces) for (const v of t.customdata) if (typeof v === 'number' && v > 0) minValue = Math.min(minValue, v);
    logRange = [Math.log10(Math.max(minValue, maxValue * 1e-9)), Math.log10(maxValue) + 0.2];
  }
  const layout = {
    // Left, clear of the mode bar on the right.
    title: { text: `Profiles R<sub>d</sub>(r), ${what}, per unit power entering`, font: { size: 15 }, x: 0.01, xanchor: 'left' },
    xaxis: { title: { text: `r  [${plotUnit()}]` }, zeroline: false },
    yaxis: { title: { text: yTitle(mode) }, type: mode === 'log' ? 'log' : 'linear', exponentformat: 'power',
             ...(mode === 'sqrt' ? sqrtTicks(maxValue) : {}), ...(logRange ? { range: logRange } : { autorange: true }) },
    legend: { x: 0.99, xanchor: 'right', y: 0.99, bgcolor: 'rgba(255,255,255,0.8)', bordercolor: '#ccc', borderwidth: 1 },
    margin: { l: 80, r: 20, t: 40, b: 50 },
    hovermode: 'closest',
    uirevision: `${mode}-${plotUnit()}`,  // keeps the user's zoom while parameters change
    dragmode: 'zoom',
  };
  Plotly.react('profile-plot', traces, layout, { responsive: true, displaylogo: false, scrollZoom: true });
  window.explore.series = series;
  window.explore.lastProfile = answer;
  window.explore.plotMode = mode;
  window.explore.updates += 1;
}

function showDerived(answer) {
  const m = answer.medium;
  const sigmaTReduced = m.sigma_a + m.sigma_s_reduced;
  // Classical dipole: σ_tr = sqrt(3 σ_a σ′_t) (Bitterli eq. 2.22), l_d = 1 / σ_tr.
  const sigmaTr = Math.sqrt(3 * m.sigma_a * sigmaTReduced);
  const totals = answer.curves.filter((c) => c.total_reflectance !== undefined)
    .map((c) => `${c.model} ${format(c.total_reflectance)}`).join(', ');
  $('derived').innerHTML = `plotted (×scale): σ<sub>s</sub> = ${format(m.sigma_s)}, α′ = ${format(m.sigma_s_reduced / sigmaTReduced)}, ` +
    `l<sub>d</sub> = ${format(1 / sigmaTr)} ${plotUnit()} (dipole)` + (totals ? `<br>R<sub>dr</sub>: ${totals}` : '');
}

let profileTimer = null;
function update() {
  // At once, but one request per animation frame while a slider is dragged.
  if (profileTimer !== null) return;
  profileTimer = requestAnimationFrame(() => {
    profileTimer = null;
    updateProfiles();
    updateSphere();
    if (window.meshView) window.meshView.materialChanged();
  });
}

async function updateProfiles() {
  const seq = ++state.profileSeq;
  const channel = Number($('channel').value);
  const request = profileRequest(channel);
  const what = channelTitle(channel);
  const started = performance.now();
  try {
    const answer = await api('/api/profiles', request);
    if (seq !== state.profileSeq) return;  // a newer request is on its way
    const elapsed = performance.now() - started;
    drawProfiles(answer, what);
    showDerived(answer);
    const per = answer.curves.map((c) => `${c.model} ${c.ms.toFixed(2)}`).join(', ');
    $('timing').textContent = `${answer.r.length} points; server ms per profile: ${per}; round trip ${elapsed.toFixed(1)} ms`;
    reportFailure('profiles', null);
  } catch (error) {
    if (seq === state.profileSeq) reportFailure('profiles', error, channel);
  }
}

// ---- the lit sphere ----

let sphereTimer = null;
function updateSphere() {
  if (!$('sphere-on').checked) return;
  clearTimeout(sphereTimer);
  sphereTimer = setTimeout(drawSphere, 150);
}

async function drawSphere() {
  const seq = ++state.sphereSeq;
  const models = checkedModels().filter((m) => ['dipole', 'better_dipole', 'quantized_diffusion'].includes(m));
  const channel = Number($('channel').value);
  const what = channelTitle(channel);
  const unitNow = plotUnit();
  const request = {
    medium: mediumOf(channel), scale: scale(),
    radius: Number($('sphere-radius').value), samples: Number($('sphere-samples').value), bins: 36, models,
  };
  try {
    const answer = await api('/api/lit_sphere', request);
    if (seq !== state.sphereSeq) return;
    const labels = Object.fromEntries(state.info.models.map((m) => [m.name, m.label]));
    const degrees = answer.psi.map((p) => (p * 180) / Math.PI);
    const traces = answer.curves.map((c) => ({
      name: labels[c.model], x: degrees, y: c.mean, mode: 'lines+markers',
      line: { color: COLOURS[c.model] }, marker: { size: 4 },
      error_y: { type: 'data', array: c.stderr, thickness: 1, width: 2 },
      hovertemplate: `ψ = %{x:.1f}°<br>M = %{y:.5g}<extra>%{fullData.name}</extra>`,
    }));
    // Path-traced lit spheres (Bitterli §3.1.3) from the open files, as points with error bars.
    Object.values(state.openFiles).forEach((file, n) => {
      if (file.kind !== 'lit_sphere') return;
      const x = file.psi.map((p) => (p * 180) / Math.PI);
      for (const tally of file.tallies) {
        const box = $(`tally-${file.path}-${tally.name}`);
        if (!box || !box.checked) continue;
        traces.push({
          name: `path traced ${file.name}: ${tally.name} (R = ${format(file.radius)} ${file.medium.length_unit})`,
          x, y: tally.mean, mode: 'markers',
          marker: { color: MC_COLOURS[n % MC_COLOURS.length], size: 6, symbol: 'circle-open' },
          error_y: { type: 'data', array: tally.stderr, thickness: 1, width: 2 },
          hovertemplate: `ψ = %{x:.1f}°<br>M = %{y:.5g}<extra>%{fullData.name}</extra>`,
        });
      }
    });
    const layout = {
      title: { text: `Lit sphere, radius ${format(request.radius)} ${unitNow}, ${what}: exitance per unit power meeting it`, font: { size: 14 }, x: 0.01, xanchor: 'left' },
      xaxis: { title: { text: 'ψ from the lit pole  [degrees]' }, range: [0, 180], dtick: 30 },
      yaxis: { title: { text: `M(ψ)  [1/${unitNow}²]` }, type: 'log', exponentformat: 'power' },
      shapes: [{ type: 'line', x0: 90, x1: 90, yref: 'paper', y0: 0, y1: 1, line: { dash: 'dot', color: '#888' } }],
      legend: { x: 0.99, xanchor: 'right', y: 0.99, bgcolor: 'rgba(255,255,255,0.8)' },
      margin: { l: 80, r: 20, t: 40, b: 50 }, uirevision: 'sphere',
    };
    Plotly.react('sphere-plot', traces, layout, { responsive: true, displaylogo: false });
    window.explore.sphere = answer;
    window.explore.sphereUpdates += 1;
    reportFailure('sphere', null);
  } catch (error) {
    if (seq === state.sphereSeq) reportFailure('sphere', error, channel);
  }
}

// ---- presets and files ----

function buildPresets() {
  const select = $('preset');
  for (const library of state.presets) {
    const group = document.createElement('optgroup');
    group.label = library.id;
    for (const material of library.materials) {
      const option = document.createElement('option');
      option.value = `${library.id}/${material.name}`;
      option.textContent = material.name;
      group.appendChild(option);
    }
    select.appendChild(group);
  }
  select.addEventListener('change', () => applyPreset(select.value));
}

async function applyPreset(value) {
  if (!value) { $('preset-source').textContent = ''; return; }
  const [id, name] = value.split('/');
  const library = state.presets.find((l) => l.id === id);
  const material = library.materials.find((m) => m.name === name);
  material.sigma_a.forEach((_, c) => {
    Object.assign(state.channels[c], {
      sigma_a: material.sigma_a[c], sigma_s_reduced: material.sigma_s_reduced[c], g: material.g[c], R_dr: null, l_d: null,
    });
  });
  $('eta').value = library.eta;
  $('unit').value = library.length_unit;
  $('preset-source').textContent = library.citation;
  clearInversionFailures();  // the coefficients are the preset's now
  if (state.mode === 'appearance') setMode('coefficients');
  buildRows();
  update();
}

function setMode(mode) {
  state.mode = mode;
  if (mode !== 'appearance') clearInversionFailures();  // R_dr and l_d are no longer the inputs
  document.querySelector(`input[name=mode][value=${mode}]`).checked = true;
  buildRows();
}

async function buildFiles() {
  state.files = await api('/api/files');
  const box = $('files');
  if (state.files.length === 0) {
    box.innerHTML = state.info.open_folders.length
      ? `<p class="note">no searchlight or lit-sphere files (*.h5) in ${state.info.open_folders.join(', ')}</p>`
      : '<p class="note">none: start with --open FOLDER</p>';
    return;
  }
  box.innerHTML = '';
  for (const file of state.files) {
    const row = document.createElement('div');
    row.className = 'file-row';
    row.innerHTML = `<label title="${file.folder}"><input type="checkbox" data-path="${file.path}"> ${file.name}</label>`;
    row.querySelector('input').addEventListener('change', (event) => toggleFile(file, event.target.checked, row));
    box.appendChild(row);
  }
}

async function toggleFile(file, on, row) {
  if (!on) {
    delete state.openFiles[file.path];
    row.querySelectorAll('.tallies').forEach((e) => e.remove());
    update();
    return;
  }
  try {
    const answer = await api(`/api/file?path=${encodeURIComponent(file.path)}`);
    answer.name = file.name;
    state.openFiles[file.path] = answer;
    const box = document.createElement('div');
    box.className = 'tallies parameter';
    const m = answer.medium;
    box.innerHTML = answer.tallies.map((t) =>
      `<label title="${t.description}"><input type="checkbox" id="tally-${file.path}-${t.name}" ${t.name === (answer.kind === 'lit_sphere' ? 'exitance_multiple' : 'reflectance') ? 'checked' : ''}> ${t.name}</label>`).join(' ') +
      `<br><span class="note">${answer.kind === 'lit_sphere' ? `lit sphere, R = ${format(answer.radius)} ${m.length_unit}; ` : ''}σ<sub>a</sub> ${format(m.sigma_a)}, σ<sub>s</sub> ${format(m.sigma_s)}, g ${format(m.g)}, η ${format(m.eta)} (1/${m.length_unit})</span> ` +
      `<button type="button">use this medium${answer.kind === 'lit_sphere' ? ' and radius' : ''}</button>`;
    box.querySelectorAll('input').forEach((input) => input.addEventListener('change', update));
    box.querySelector('button').addEventListener('click', () => {
      for (const c of state.channels) Object.assign(c, { sigma_a: m.sigma_a, sigma_s_reduced: m.sigma_s * (1 - m.g), g: m.g, R_dr: null, l_d: null });
      clearInversionFailures();
      $('eta').value = m.eta;
      $('unit').value = m.length_unit;
      $('scale').value = 1;
      if (answer.kind === 'lit_sphere') $('sphere-radius').value = answer.radius;
      $('preset').value = '';
      setMode('coefficients');
      update();
    });
    row.appendChild(box);
    reportFailure(`file ${file.name}`, null);
    update();
  } catch (error) {
    reportFailure(`file ${file.name}`, error);
  }
}

// ---- start ----

async function start() {
  try {
    state.info = await api('/api/info');
    state.presets = await api('/api/presets');
    state.textModels = state.info.text_models;
  } catch (error) {
    reportFailure('server', error);
    return;
  }
  $('version').textContent = `scatterlab ${state.info.version}`;
  for (const name of state.info.inversion_models) {
    const option = document.createElement('option');
    option.value = name;
    option.textContent = name;
    $('inversion-model').appendChild(option);
  }
  buildPresets();
  buildModels();
  document.querySelectorAll('input[name=mode]').forEach((input) => input.addEventListener('change', () => setMode(input.value)));
  for (const id of ['eta', 'scale', 'r-max', 'points', 'unit']) $(id).addEventListener('input', update);
  for (const id of ['channel', 'plot-mode']) $(id).addEventListener('change', update);
  for (const id of ['sphere-radius', 'sphere-samples']) $(id).addEventListener('input', updateSphere);
  $('sphere-on').addEventListener('change', updateSphere);
  $('inversion-model').addEventListener('change', async () => {
    for (let c = 0; c < 3; ++c) await invertChannel(c);
    update();
  });
  $('reload-models').addEventListener('click', reloadModels);
  buildRows();
  await buildFiles();
  $('preset').value = 'jensen2001/marble';
  await applyPreset($('preset').value);
  state.started = true;
  showProblems();  // the status: ready, or what was refused on the way
  window.explore.ready = true;
}

start();
