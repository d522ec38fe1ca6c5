// The live view's page: reads the stream at /stream (one binary message per
// frame; format in src/view/view_message.hpp) and draws the newest frame.
'use strict';

// What the page has shown, for whoever watches it (and the browser test).
const view = {
  framesShown: 0,      // distinct frames drawn
  counts: null,        // the run's counts, as the last message gave them
  ended: false,        // the run is over (the counts are final)
  frame: null,         // the newest frame: header, labels, shade, points
  history: [],         // {t, p50, p99} of the end-to-end latency, the last minute
};
window.lccpView = view;

const $ = (id) => document.getElementById(id);
const align4 = (n) => (n + 3) & ~3;
let lastDrawn = null;
let drawPending = false;

function parse(buffer) {
  const headerBytes = new DataView(buffer).getUint32(0, true);
  const header = JSON.parse(new TextDecoder().decode(new Uint8Array(buffer, 4, headerBytes)));
  if (header.index === undefined) return { header };
  let offset = align4(4 + headerBytes);
  const pixels = header.width * header.height;
  const runs = new DataView(buffer, offset);
  const labels = new Uint16Array(pixels);
  let pixel = 0;
  for (let r = 0; r < runs.getUint32(0, true); ++r) {
    const value = runs.getUint16(4 + 4 * r, true);
    const length = runs.getUint16(6 + 4 * r, true);
    labels.fill(value, pixel, pixel + length);
    pixel += length;
  }
  offset += 4 + 4 * runs.getUint32(0, true);
  const shade = new Uint8Array(buffer, offset, pixels);
  offset = align4(offset + pixels);
  const points = new DataView(buffer, offset, 8 * header.points);
  return { header, labels, shade, points };
}

function receive(buffer) {
  const message = parse(buffer);
  const header = message.header;
  if (message.labels) view.frame = message;
  view.counts = header.counts;
  view.ended = header.ended;
  view.history.push({ t: performance.now() / 1000, p50: header.latency.end_to_end.p50, p99: header.latency.end_to_end.p99 });
  while (view.history.length && view.history[view.history.length - 1].t - view.history[0].t > 60) view.history.shift();
  showFigures(header);
  if (!drawPending) {
    drawPending = true;
    requestAnimationFrame(draw);
  }
}

function showFigures(header) {
  for (const key of ['received', 'completed', 'failed', 'dropped']) $(key).textContent = header.counts[`frames_${key}`];
  $('fps').textContent = header.fps.toFixed(1);
  const status = $('status');
  status.textContent = header.ended ? 'ended' : 'live';
  status.className = 'status ' + status.textContent;
  const rows = header.latency.stages.map((s) => `<tr><td>${s.name}</td><td>${s.p50.toFixed(2)}</td><td>${s.p99.toFixed(2)}</td></tr>`);
  rows.unshift(`<tr><td><b>end to end</b></td><td>${header.latency.end_to_end.p50.toFixed(1)}</td><td>${header.latency.end_to_end.p99.toFixed(1)}</td></tr>`);
  $('stages').tBodies[0].innerHTML = rows.join('');
}

function draw() {
  drawPending = false;
  drawChart();
  const frame = view.frame;
  if (!frame || frame === lastDrawn) return;
  lastDrawn = frame;
  view.framesShown += 1;
  $('frame').textContent = frame.header.index;
  $('segments').textContent = frame.header.segments.length;
  drawLabels(frame);
  drawPoints(frame);
}

// The colour of segment index + 1 (0: none): its label colour, the support dimmed.
function colorOf(header, index) {
  if (index === 0) return null;
  if (index === header.support) return [60, 70, 90];
  const segment = header.segments[index - 1];
  return segment ? segment.color : null;
}

function drawLabels(frame) {
  const { header, labels, shade } = frame;
  const canvas = $('labels');
  if (header.width === 0) return;
  canvas.width = header.width;
  canvas.height = header.height;
  const context = canvas.getContext('2d');
  const image = context.createImageData(header.width, header.height);
  for (let i = 0; i < labels.length; ++i) {
    const grey = shade[i];
    const color = colorOf(header, labels[i]);
    const o = 4 * i;
    image.data[o] = color ? (grey + color[0]) >> 1 : grey;
    image.data[o + 1] = color ? (grey + color[1]) >> 1 : grey;
    image.data[o + 2] = color ? (grey + color[2]) >> 1 : grey;
    image.data[o + 3] = 255;
  }
  context.putImageData(image, 0, 0);
}

function describe(header, index) {
  if (index === 0) return null;
  if (index === header.support) return `support plane (id ${header.support_id})`;
  const s = header.segments[index - 1];
  const cm = s.size.map((v) => (100 * v).toFixed(1)).join(' x ');
  const lines = [`id ${s.id}`, `${s.points} points`, `size ${cm} cm`];
  if (s.part) lines.push(`part of object ${s.object}`);
  lines.push(`grasp: ${s.grasp}`);
  return lines.join('\n');
}

$('labels').addEventListener('mousemove', (event) => {
  const frame = view.frame;
  const tooltip = $('tooltip');
  const canvas = event.target;
  if (!frame || frame.header.width === 0) return;
  const x = Math.floor((event.offsetX * frame.header.width) / canvas.clientWidth);
  const y = Math.floor((event.offsetY * frame.header.height) / canvas.clientHeight);
  const text = describe(frame.header, frame.labels[y * frame.header.width + x] || 0);
  tooltip.hidden = !text;
  tooltip.textContent = text || '';
  tooltip.style.left = `${event.offsetX + 14}px`;
  tooltip.style.top = `${event.offsetY + 14}px`;
});
$('labels').addEventListener('mouseleave', () => { $('tooltip').hidden = true; });

// The 3D view: an orbit around the points' centre, perspective, drawn back to front.
const orbit = { yaw: 0, pitch: 0, zoom: 1 };
function drawPoints(frame) {
  const { header, points } = frame;
  const canvas = $('points');
  const context = canvas.getContext('2d');
  context.fillStyle = '#000';
  context.fillRect(0, 0, canvas.width, canvas.height);
  const n = header.points;
  if (n === 0) return;
  const xyz = new Float32Array(3 * n);
  const centre = [0, 0, 0];
  for (let i = 0; i < n; ++i) {
    for (let k = 0; k < 3; ++k) {
      xyz[3 * i + k] = points.getInt16(8 * i + 2 * k, true) / 1000;
      centre[k] += xyz[3 * i + k] / n;
    }
  }
  const [cy, sy, cp, sp] = [Math.cos(orbit.yaw), Math.sin(orbit.yaw), Math.cos(orbit.pitch), Math.sin(orbit.pitch)];
  const distance = centre[2] / orbit.zoom;
  const focal = canvas.height * 1.1;
  const screen = [];
  for (let i = 0; i < n; ++i) {
    const x = xyz[3 * i] - centre[0], y = xyz[3 * i + 1] - centre[1], z = xyz[3 * i + 2] - centre[2];
    const x1 = cy * x + sy * z, z1 = -sy * x + cy * z;
    const y2 = cp * y - sp * z1, z2 = sp * y + cp * z1 + distance;
    if (z2 <= 0.05) continue;
    screen.push([z2, canvas.width / 2 + (focal * x1) / z2, canvas.height / 2 + (focal * y2) / z2, points.getUint16(8 * i + 6, true)]);
  }
  screen.sort((a, b) => b[0] - a[0]);
  for (const [, u, v, index] of screen) {
    const color = colorOf(header, index) || [150, 150, 150];
    context.fillStyle = `rgb(${color[0]},${color[1]},${color[2]})`;
    context.fillRect(Math.round(u) - 1, Math.round(v) - 1, 3, 3);  // whole pixels: no blending at the edges
  }
}

(function orbitWithTheMouse() {
  const canvas = $('points');
  let last = null;
  const redraw = () => { if (view.frame) drawPoints(view.frame); };
  canvas.addEventListener('mousedown', (event) => { last = [event.clientX, event.clientY]; });
  window.addEventListener('mouseup', () => { last = null; });
  window.addEventListener('mousemove', (event) => {
    if (!last) return;
    orbit.yaw += (event.clientX - last[0]) * 0.01;
    orbit.pitch = Math.max(-1.5, Math.min(1.5, orbit.pitch - (event.clientY - last[1]) * 0.01));
    last = [event.clientX, event.clientY];
    redraw();
  });
  canvas.addEventListener('wheel', (event) => {
    event.preventDefault();
    orbit.zoom = Math.max(0.2, Math.min(10, orbit.zoom * Math.exp(-event.deltaY * 0.001)));
    redraw();
  }, { passive: false });
  canvas.addEventListener('dblclick', () => { Object.assign(orbit, { yaw: 0, pitch: 0, zoom: 1 }); redraw(); });
})();

function drawChart() {
  const canvas = $('chart');
  const context = canvas.getContext('2d');
  context.fillStyle = '#000';
  context.fillRect(0, 0, canvas.width, canvas.height);
  const history = view.history;
  if (history.length === 0) return;
  const now = history[history.length - 1].t;
  const top = Math.max(10, ...history.map((h) => h.p99)) * 1.1;
  const x = (t) => canvas.width - ((now - t) / 60) * canvas.width;
  const y = (ms) => canvas.height - (ms / top) * (canvas.height - 16);
  context.fillStyle = '#9aa';
  context.font = '11px sans-serif';
  context.fillText(`${top.toFixed(0)} ms`, 4, 12);
  context.fillText('-60 s', 4, canvas.height - 4);
  for (const [key, color] of [['p99', '#f0a04b'], ['p50', '#5fd38d']]) {
    context.strokeStyle = color;
    context.beginPath();
    history.forEach((h, i) => (i ? context.lineTo(x(h.t), y(h[key])) : context.moveTo(x(h.t), y(h[key]))));
    context.stroke();
  }
}

function connect() {
  const socket = new WebSocket(`${location.protocol === 'https:' ? 'wss' : 'ws'}://${location.host}/stream`);
  socket.binaryType = 'arraybuffer';
  socket.onmessage = (event) => receive(event.data);
  socket.onclose = () => {
    const status = $('status');
    if (view.ended) return;
    status.textContent = 'disconnected';
    status.className = 'status';
    setTimeout(connect, 1000);
  };
}
connect();
