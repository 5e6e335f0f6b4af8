// aiobt web view: draws what the server's websocket sends (see aiobt/web/sources.py).
"use strict";

const state = {
  connected: false, frames: 0, updatesPerSecond: 0, poseUpdatesPerSecond: 0, poseUpdates: 0,
  robot: null, map: null, costmap: null, scan: [], plan: [], local: [], goals: [],
  scaleBar: null, zones: [],
  localPlan: [], localPlanUpdates: 0, localPlanMax: 0, localCostmap: null,
  footprint: { radius: 0.22 }, feedback: null, nav: null, tree: null, status: null,
  goalsSent: 0, goalReply: null, route: [], routeGraph: null, followed: null,
  particles: [], truth: null, amclPose: null, drawn: { particles: 0, truth: 0 }, truthError: "",
};
window.aiobtState = state;

const canvas = document.getElementById("map");
const ctx = canvas.getContext("2d");
const layers = { map: null, costmap: null, localCostmap: null };
const TARGET_WIDTH = 900; // canvas pixels across the map
let scale = 1; // canvas pixels per map cell
let dirty = true;

function setText(id, text) { document.getElementById(id).textContent = text; }

// ---- the websocket -------------------------------------------------------------------
let socket = null;
function connect() {
  const scheme = location.protocol === "https:" ? "wss" : "ws";
  socket = new WebSocket(`${scheme}://${location.host}/ws`);
  socket.onopen = () => { state.connected = true; showConnection(); };
  socket.onclose = () => {
    state.connected = false; showConnection(); setTimeout(connect, 1000);
  };
  socket.onmessage = (event) => receive(JSON.parse(event.data));
}
function showConnection() {
  const el = document.getElementById("connection");
  el.textContent = state.connected ? "connected" : "disconnected (retrying)";
  el.className = state.connected ? "good" : "bad";
}

const arrivals = []; const poseArrivals = [];
function countRate(list, now) {
  list.push(now);
  while (list.length && now - list[0] > 1000) list.shift();
  return list.length;
}

function receive(update) {
  const now = performance.now();
  state.frames += 1;
  state.updatesPerSecond = countRate(arrivals, now);
  if ("pose" in update) {
    state.robot = update.pose; state.poseUpdates += 1;
    state.poseUpdatesPerSecond = countRate(poseArrivals, now);
    canvas.dataset.robotX = update.pose.x; canvas.dataset.robotY = update.pose.y;
  }
  if ("route_graph" in update) state.routeGraph = update.route_graph;
  if ("particles" in update) state.particles = update.particles;
  if ("amcl_pose" in update) state.amclPose = update.amcl_pose;
  if ("truth" in update) state.truth = update.truth;
  if ("docks" in update) state.docks = update.docks;
  for (const key of ["scan", "plan", "route", "local", "footprint", "zones", "followed"]) {
    if (key in update) state[key] = update[key];
  }
  if ("map" in update) { state.map = update.map; layers.map = gridImage(update.map, mapColour); }
  if ("costmap" in update) {
    state.costmap = update.costmap; layers.costmap = gridImage(update.costmap, costColour);
  }
  if ("local_plan" in update) { // the controller's; empty when its goal ended
    state.localPlan = update.local_plan; state.localPlanUpdates += 1;
    state.localPlanMax = Math.max(state.localPlanMax, update.local_plan.length);
  }
  if ("local_costmap" in update) {
    state.localCostmap = update.local_costmap;
    layers.localCostmap = gridImage(update.local_costmap, localCostColour);
  }
  if ("tree" in update) buildTree(update.tree);
  if ("status" in update && update.status) paintStatus(update.status);
  if ("nav" in update) showNav(update.nav);
  if ("feedback" in update) showFeedback(update.feedback);
  if ("goal_reply" in update) showGoalReply(update.goal_reply);
  setText("rate", `${state.updatesPerSecond} ${state.updatesPerSecond === 1 ? "update" : "updates"}/s`);
  dirty = true;
}

// ---- grids ---------------------------------------------------------------------------
function mapColour(v) {
  if (v === 255) return [180, 180, 180, 255];
  const g = Math.round(255 - 2.55 * Math.min(v, 100));
  return [g, g, g, 255];
}
function costColour(v) {
  if (v === 255 || v === 0) return [0, 0, 0, 0];
  if (v >= 253) return [200, 0, 120, 150];
  return [41, 98, 255, Math.round(30 + 110 * v / 252)];
}
// Nav2's costmap as an OccupancyGrid: 0 free, 1..98 inflated, 99 inscribed, 100 lethal
function localCostColour(v) {
  if (v === 255 || v === 0) return [0, 0, 0, 0];
  if (v >= 99) return [230, 0, 90, 170];
  return [0, 170, 200, Math.round(40 + 110 * v / 98)];
}
function gridImage(grid, colour) {
  const cells = Uint8Array.from(atob(grid.cells), (c) => c.charCodeAt(0));
  const image = new ImageData(grid.width, grid.height);
  for (let row = 0; row < grid.height; row++) {
    const flipped = grid.height - 1 - row; // row 0 is the bottom of the map
    for (let col = 0; col < grid.width; col++) {
      const rgba = colour(cells[row * grid.width + col]);
      image.data.set(rgba, (flipped * grid.width + col) * 4);
    }
  }
  const layer = document.createElement("canvas");
  layer.width = grid.width; layer.height = grid.height;
  layer.getContext("2d").putImageData(image, 0, 0);
  return layer;
}

// ---- map frame <-> canvas ------------------------------------------------------------
function toCanvas(x, y) {
  const m = state.map;
  return [(x - m.origin[0]) / m.resolution * scale,
    (m.height - (y - m.origin[1]) / m.resolution) * scale];
}
function toWorld(cx, cy) {
  const m = state.map;
  return [cx / scale * m.resolution + m.origin[0],
    (m.height - cy / scale) * m.resolution + m.origin[1]];
}
function eventPoint(event) {
  const box = canvas.getBoundingClientRect();
  return [(event.clientX - box.left) * canvas.width / box.width,
    (event.clientY - box.top) * canvas.height / box.height];
}
// for tests and tools: where (x, y) of the map is, in CSS pixels from the canvas's centre
window.aiobtView = {
  offsetFromCenter(x, y) {
    const [cx, cy] = toCanvas(x, y); const box = canvas.getBoundingClientRect();
    return [cx * box.width / canvas.width - box.width / 2,
      cy * box.height / canvas.height - box.height / 2];
  },
};

// ---- drawing -------------------------------------------------------------------------
function polyline(points, colour, width) {
  if (!points || points.length < 2) return;
  ctx.strokeStyle = colour; ctx.lineWidth = width; ctx.beginPath();
  points.forEach(([x, y], i) => {
    const [cx, cy] = toCanvas(x, y);
    if (i === 0) ctx.moveTo(cx, cy); else ctx.lineTo(cx, cy);
  });
  ctx.stroke();
}
function arrow(pose, colour, radius) {
  const [cx, cy] = toCanvas(pose.x, pose.y);
  const r = radius / state.map.resolution * scale;
  ctx.strokeStyle = colour; ctx.lineWidth = 2.5;
  ctx.beginPath(); ctx.arc(cx, cy, r, 0, 2 * Math.PI); ctx.stroke();
  ctx.beginPath(); ctx.moveTo(cx, cy);
  ctx.lineTo(cx + 1.6 * r * Math.cos(pose.yaw), cy - 1.6 * r * Math.sin(pose.yaw)); ctx.stroke();
}
function drawGraph(graph) { // the route server's lanes and nodes
  for (const [x0, y0, x1, y1] of graph.edges) polyline([[x0, y0], [x1, y1]], "#81c784", 1.5);
  ctx.fillStyle = "#388e3c";
  for (const [x, y] of graph.nodes) {
    const [cx, cy] = toCanvas(x, y); ctx.beginPath(); ctx.arc(cx, cy, 3, 0, 2 * Math.PI); ctx.fill();
  }
}
function drawDocks() { // the docking server's docks (green, facing the dock) and staging poses
  for (const dock of state.docks || []) {
    arrow(dock, "#2e7d32", 0.22);
    if (dock.staging) arrow(dock.staging, "#81c784", 0.08);
  }
}
function draw() {
  requestAnimationFrame(draw);
  if (!dirty || !state.map) return;
  dirty = false;
  const m = state.map;
  scale = Math.max(1, TARGET_WIDTH / m.width);
  const w = Math.round(m.width * scale); const h = Math.round(m.height * scale);
  if (canvas.width !== w || canvas.height !== h) { canvas.width = w; canvas.height = h; }
  ctx.imageSmoothingEnabled = false;
  ctx.drawImage(layers.map, 0, 0, w, h);
  if (document.getElementById("show-costmap").checked && layers.costmap) {
    ctx.drawImage(layers.costmap, 0, 0, w, h);
  }
  if (document.getElementById("show-local-costmap").checked && layers.localCostmap) {
    const g = state.localCostmap; const [left, top] = toCanvas(g.origin[0], g.origin[1] + g.height * g.resolution);
    const cells = g.resolution / m.resolution * scale;
    ctx.drawImage(layers.localCostmap, left, top, g.width * cells, g.height * cells);
  }
  if (document.getElementById("show-scan").checked) {
    ctx.fillStyle = "#e53935";
    for (const [x, y] of state.scan) { const [cx, cy] = toCanvas(x, y); ctx.fillRect(cx - 1.5, cy - 1.5, 3, 3); }
  }
  if (document.getElementById("show-route-graph").checked && state.routeGraph) drawGraph(state.routeGraph);
  polyline(state.route, "#2e7d32", 3);
  drawDocks();
  for (const zone of state.zones || []) { // the collision monitor's; the acting one red
    if (zone.acting) polyline(zone.points, "#d50000", 3.5);
    else polyline(zone.points, zone.action === "approach" ? "#2979ff" : "#ff9100", 1.5);
  }
  polyline(state.plan, "#2962ff", 2.5);
  polyline(state.local, "#00a86b", 3);
  polyline(state.localPlan, "#e6007a", 3);
  drawGoals();
  if (document.getElementById("show-particles").checked) {
    drawParticles(state.particles);
    if (state.amclPose) drawEllipse(state.amclPose);
  }
  drawFollowed();
  if (state.robot) arrow(state.robot, "#ff9800", state.footprint.radius);
  if (state.truth) drawTruth(state.truth);
  drawScaleBar();
}
// the navigator's goal (however it was sent): purple while driven to, grey once ended;
// the via-points of navigate_through_poses as small circles
function drawGoals() {
  const goals = state.goals; if (!goals.length) return;
  const active = state.nav && state.nav.state === "navigating";
  const colour = active ? "#8e24aa" : "#9e9e9e";
  for (const via of goals.slice(0, -1)) {
    const [cx, cy] = toCanvas(via.x, via.y);
    ctx.strokeStyle = colour; ctx.lineWidth = 2;
    ctx.beginPath(); ctx.arc(cx, cy, 5, 0, 2 * Math.PI); ctx.stroke();
  }
  arrow(goals[goals.length - 1], colour, 0.15);
}
// the object the following server follows (its filtered pose), while it is fresh
function drawFollowed() {
  const f = state.followed;
  if (!f || !state.robot || state.robot.stamp - f.stamp > 2.0) return;
  const [cx, cy] = toCanvas(f.x, f.y); const half = 0.2 / state.map.resolution * scale;
  ctx.strokeStyle = "#00838f"; ctx.lineWidth = 2.5; ctx.strokeRect(cx - half, cy - half, 2 * half, 2 * half);
}
// a bar of 1, 2 or 5 x 10^k metres, about a fifth of the map's width, bottom left
function drawScaleBar() {
  const m = state.map; const across = m.width * m.resolution / 5;
  const power = 10 ** Math.floor(Math.log10(across));
  const metres = [5, 2, 1].map((f) => f * power).find((v) => v <= across) || power;
  const pixels = metres / m.resolution * scale;
  const x = 12; const y = canvas.height - 14;
  ctx.fillStyle = "rgba(255, 255, 255, 0.8)"; ctx.fillRect(x - 6, y - 20, pixels + 12, 28);
  ctx.strokeStyle = "#222"; ctx.lineWidth = 3;
  ctx.beginPath(); ctx.moveTo(x, y - 5); ctx.lineTo(x, y); ctx.lineTo(x + pixels, y);
  ctx.lineTo(x + pixels, y - 5); ctx.stroke();
  ctx.fillStyle = "#222"; ctx.font = "13px system-ui, sans-serif";
  ctx.fillText(`${metres} m`, x + 4, y - 7);
  state.scaleBar = { metres, pixels };
}

// ---- goals ---------------------------------------------------------------------------
let pressed = null;
canvas.addEventListener("mousedown", (event) => { if (state.map) pressed = eventPoint(event); });
canvas.addEventListener("mouseup", (event) => {
  if (!pressed || !state.map) return;
  const [x, y] = toWorld(...pressed);
  const [ex, ey] = toWorld(...eventPoint(event));
  const dragged = Math.hypot(ex - x, ey - y) > 3 * state.map.resolution;
  const from = state.robot || { x, y };
  const yaw = dragged ? Math.atan2(ey - y, ex - x) : Math.atan2(y - from.y, x - from.x);
  pressed = null;
  sendGoal(x, y, yaw);
});
function sendGoal(x, y, yaw) {
  if (!socket || socket.readyState !== WebSocket.OPEN) { showGoalReply({ ok: false, error: "not connected" }); return; }
  socket.send(JSON.stringify({ goal: { x, y, yaw } }));
  state.goalsSent += 1;
  setText("goal-reply", `goal (${x.toFixed(2)}, ${y.toFixed(2)}) sent…`);
}
function showGoalReply(reply) {
  state.goalReply = reply;
  const el = document.getElementById("goal-reply");
  el.textContent = reply.ok ? `goal (${reply.goal[0].toFixed(2)}, ${reply.goal[1].toFixed(2)}) on goal_pose` : `goal refused: ${reply.error}`;
  el.className = reply.ok ? "" : "bad";
}

// ---- navigation and the tree ---------------------------------------------------------
function showNav(nav) {
  state.nav = nav; state.goals = nav.goals || [];
  let text = `${nav.state}, ${nav.distance_remaining.toFixed(2)} m to go`;
  if (nav.error_code) text += `, error ${nav.error_code} ${nav.error_msg}`;
  setText("nav", text);
  setText("recoveries", String(nav.recoveries));
}
function showFeedback(feedback) {
  state.feedback = feedback;
  setText("recoveries", String(feedback.recoveries));
  setText("nav", `navigating, ${feedback.distance_remaining.toFixed(2)} m to go`);
}
function buildTree(tree) {
  state.tree = tree; state.status = null;
  const depth = {}; const box = document.getElementById("tree");
  box.replaceChildren();
  for (const node of tree.nodes) {
    depth[node.uid] = node.parent === null ? 0 : depth[node.parent] + 1;
    const row = document.createElement("div");
    row.className = "node IDLE"; row.id = `node-${node.uid}`; row.dataset.status = "IDLE";
    row.style.marginLeft = `${depth[node.uid] * 14}px`;
    row.textContent = node.name === node.id ? node.id : `${node.id} [${node.name}]`;
    const kind = document.createElement("span"); kind.className = "kind"; kind.textContent = node.kind;
    row.appendChild(kind); box.appendChild(row);
  }
  const source = tree.source.split("/").pop();
  setText("tree-title", `${tree.tree_id} (run ${tree.run})${source ? ` from ${source}` : ""}`);
  document.getElementById("tree-title").title = tree.source;
}
function paintStatus(status) {
  if (!state.tree || status.run !== state.tree.run) return;
  state.status = status;
  for (const [uid, now] of Object.entries(status.status)) {
    const row = document.getElementById(`node-${uid}`);
    if (!row) continue;
    const was = status.last[uid];
    row.className = `node ${now}` + (now === "IDLE" && was ? ` was-${was}` : "");
    row.dataset.status = now;
  }
}

connect();
requestAnimationFrame(draw);
