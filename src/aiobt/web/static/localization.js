// aiobt web view: the localization's particles and estimate, and the simulation's truth
// beside it (the streams particles, amcl_pose, truth: see aiobt/web/sources.py). Drawn by
// app.js's draw(), with its canvas, state and toCanvas.
"use strict";

const PARTICLE = "#795548"; const TRUTH = "#00bcd4";

// the localization's particles: a dot each, with a short tick along its heading
function drawParticles(particles) {
  ctx.strokeStyle = ctx.fillStyle = PARTICLE; ctx.lineWidth = 1;
  for (const [x, y, yaw] of particles) {
    const [cx, cy] = toCanvas(x, y);
    ctx.fillRect(cx - 1.5, cy - 1.5, 3, 3);
    ctx.beginPath(); ctx.moveTo(cx, cy); ctx.lineTo(cx + 6 * Math.cos(yaw), cy - 6 * Math.sin(yaw));
    ctx.stroke();
  }
  state.drawn.particles = particles.length;
}
// amcl_pose's 2-sigma ellipse in x, y (the covariance's eigenvectors and eigenvalues)
function drawEllipse(estimate) {
  const [xx, xy, yy] = estimate.covariance;
  const mid = (xx + yy) / 2; const spread = Math.hypot((xx - yy) / 2, xy);
  const major = 2 * Math.sqrt(Math.max(mid + spread, 0)); const minor = 2 * Math.sqrt(Math.max(mid - spread, 0));
  const angle = 0.5 * Math.atan2(2 * xy, xx - yy); const perPixel = scale / state.map.resolution;
  const [cx, cy] = toCanvas(estimate.x, estimate.y);
  ctx.strokeStyle = PARTICLE; ctx.lineWidth = 1.5; ctx.beginPath();
  ctx.ellipse(cx, cy, Math.max(major * perPixel, 2), Math.max(minor * perPixel, 2), -angle, 0, 2 * Math.PI);
  ctx.stroke();
}
// the simulation's truth: a dashed ring and heading over the estimate's robot, and how far
// the estimate is off it, top left on the map (on the canvas: the page's layout stays put)
function drawTruth(truth) {
  ctx.setLineDash([4, 3]); arrow(truth, TRUTH, state.footprint.radius * 1.25); ctx.setLineDash([]);
  state.drawn.truth += 1;
  const error = truthError(truth, state.robot); state.truthError = error;
  if (!error) return;
  ctx.font = "13px system-ui, sans-serif"; const width = ctx.measureText(error).width;
  ctx.fillStyle = "rgba(255, 255, 255, 0.8)"; ctx.fillRect(6, 6, width + 12, 22);
  ctx.fillStyle = "#222"; ctx.fillText(error, 12, 22);
}
function truthError(t, r) {
  if (!r) return "";
  const turn = Math.abs(Math.atan2(Math.sin(r.yaw - t.yaw), Math.cos(r.yaw - t.yaw)));
  return `estimate off the truth by ${(100 * Math.hypot(r.x - t.x, r.y - t.y)).toFixed(1)} cm, ${(turn * 180 / Math.PI).toFixed(1)}°`;
}
