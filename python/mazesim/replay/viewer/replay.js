/* mazesim replay viewer: draws a recorded run (the JSON in #scene) as SVG and steps through it.
   The state of the view is published as window.mazesimReplay for scripts and tests. */
(function () {
  "use strict";
  var NS = "http://www.w3.org/2000/svg";
  var scene = JSON.parse(document.getElementById("scene").textContent);
  var run = scene.run;
  var world = scene.world;
  var robot = scene.robot;
  // A run of several robots lists them all (robot 0 first); each episode holds the others' tracks.
  var fleet = scene.robots || null;
  var ROBOT_COLOURS = ["#1f77b4", "#ff7f0e", "#9467bd", "#8c564b", "#e377c2", "#17becf", "#bcbd22", "#7f7f7f"];
  var stepSeconds = run.control_step_ms / 1000;
  var SUBTASK_COLOURS = ["#7f7f7f", "#d62728", "#1f77b4", "#2ca02c", "#9467bd", "#8c564b"];
  var LEVEL_COLOURS = ["#d62728", "#ff7f0e", "#e6c000", "#2ca02c"];
  var SPEEDS = [0.25, 0.5, 1, 2, 4, 8, 16];

  function el(name, attributes, parent) {
    var node = document.createElementNS(NS, name);
    for (var key in attributes) { node.setAttribute(key, attributes[key]); }
    if (parent) { parent.appendChild(node); }
    return node;
  }
  function text(id, value) { document.getElementById(id).textContent = value; }
  function fixed(value, digits) { return Number(value).toFixed(digits); }
  function degrees(radians) { return radians * 180 / Math.PI; }

  // -- the episodes, decoded from their whole units -------------------------------------------
  function decode(values) {
    var frames = values.frames;
    var episode = {
      number: values.number, outcome: values.outcome, frames: frames,
      x: values.x.map(function (v) { return v * 1e-4; }),
      y: values.y.map(function (v) { return v * 1e-4; }),
      yaw: values.yaw.map(function (v) { return v * 1e-3; }),
      readings: values.readings.map(function (row) {
        return row.map(function (v) { return v / run.reading_scale; });
      }),
      rays: values.rays.map(function (row) { return row.map(function (v) { return v * 1e-3; }); }),
      contacts: {}, events: {}, eventFrames: [], decisions: values.decisions || [],
      actions: values.actions || null, wheelSpeeds: values.wheel_speeds || null,
      subtasks: values.subtasks || null, levels: values.levels || null,
      others: (values.robots || []).map(decode),
      // Each change of the walls (a supervisor moved, imported or removed some): its frame
      // and the walls from then on, as the world's are given.
      wallFrames: (values.walls || []).map(function (pair) { return pair[0]; }),
      walls: (values.walls || []).map(function (pair) {
        return pair[1].map(function (b) { return [b[0] * 1e-4, b[1] * 1e-4, b[2] * 1e-4, b[3] * 1e-4, b[4] * 1e-3]; });
      })
    };
    values.contacts.forEach(function (frame) { episode.contacts[frame] = true; });
    values.events.forEach(function (pair) {
      episode.events[pair[0]] = pair[1];
      episode.eventFrames.push(pair[0]);
    });
    return episode;
  }
  var episodes = run.episodes.map(decode);

  // -- the world ------------------------------------------------------------------------------
  var map = document.getElementById("map");
  var bounds = world.bounds;
  var margin = 0.04 * Math.max(bounds[2] - bounds[0], bounds[3] - bounds[1], 0.1);
  map.setAttribute("viewBox", [bounds[0] - margin, -bounds[3] - margin,
    bounds[2] - bounds[0] + 2 * margin, bounds[3] - bounds[1] + 2 * margin].join(" "));
  var unit = Math.max(bounds[2] - bounds[0], bounds[3] - bounds[1], 0.1) / 600;

  function grey(level) {
    var v = Math.round(255 * Math.min(Math.max(level, 0), 1));
    return "rgb(" + v + "," + v + "," + v + ")";
  }
  function box(parent, cx, cy, sx, sy, yaw, style) {
    var attributes = { x: -sx / 2, y: -sy / 2, width: sx, height: sy,
      transform: "translate(" + cx + "," + (-cy) + ") rotate(" + (-degrees(yaw)) + ")" };
    for (var key in style) { attributes[key] = style[key]; }
    return el("rect", attributes, parent);
  }
  var floor = el("g", { id: "floor" }, map);
  el("rect", { x: bounds[0], y: -bounds[3], width: bounds[2] - bounds[0],
    height: bounds[3] - bounds[1], fill: grey(world.floor) }, floor);
  world.paint.forEach(function (region) {
    var fill = grey(region.reflectance);
    if (region.shape === "rect") {
      box(floor, region.center[0], region.center[1], region.size[0], region.size[1],
        region.yaw || 0, { fill: fill });
    } else if (region.shape === "circle") {
      el("circle", { cx: region.center[0], cy: -region.center[1], r: region.radius, fill: fill }, floor);
    } else if (region.shape === "capsule") {
      el("line", { x1: region.a[0], y1: -region.a[1], x2: region.b[0], y2: -region.b[1],
        stroke: fill, "stroke-width": 2 * region.radius, "stroke-linecap": "round" }, floor);
    }
  });
  if (world.grid) {
    var grid = el("g", { id: "grid", stroke: "#9ecae1", "stroke-width": unit, "stroke-dasharray": 4 * unit + " " + 4 * unit }, map);
    for (var col = 0; col <= world.grid.cols; col++) {
      var gx = world.grid.origin[0] + col * world.grid.cell;
      el("line", { x1: gx, x2: gx, y1: -world.grid.origin[1], y2: -(world.grid.origin[1] + world.grid.rows * world.grid.cell) }, grid);
    }
    for (var row = 0; row <= world.grid.rows; row++) {
      var gy = world.grid.origin[1] + row * world.grid.cell;
      el("line", { y1: -gy, y2: -gy, x1: world.grid.origin[0], x2: world.grid.origin[0] + world.grid.cols * world.grid.cell }, grid);
    }
  }
  var walls = el("g", { id: "walls", fill: "#8c3b1f" }, map);
  var wallsDrawn = null;
  // Draws the walls standing at a frame of an episode (the world's before any change).
  function drawWalls(episode, frame) {
    var change = 0;
    for (var i = 0; i < episode.wallFrames.length && episode.wallFrames[i] <= frame; i++) { change = i + 1; }
    var boxes = change ? episode.walls[change - 1] : world.walls;
    if (boxes === wallsDrawn) { return; }
    wallsDrawn = boxes;
    while (walls.firstChild) { walls.removeChild(walls.firstChild); }
    boxes.forEach(function (w) { box(walls, w[0], w[1], w[2], w[3], w[4], {}); });
  }
  drawWalls({ wallFrames: [], walls: [] }, 0);
  var marks = el("g", { id: "checkpoints" }, map);
  world.checkpoints.forEach(function (c) {
    box(marks, c.x, c.y, 0.085, c.width, c.yaw, { fill: "none", stroke: "#e6b800", "stroke-width": 2 * unit });
    var lx = c.x + 0.075 * Math.cos(c.yaw), ly = c.y + 0.075 * Math.sin(c.yaw);
    var label = el("g", { "class": "checkpoint-label" }, marks);
    el("circle", { cx: lx, cy: -ly, r: 9 * unit, fill: "#ffd92f", stroke: "#000", "stroke-width": unit }, label);
    var t = el("text", { x: lx, y: -ly + 4 * unit, "text-anchor": "middle", "font-size": 11 * unit }, label);
    t.textContent = c.id;
    var title = el("title", {}, label);
    title.textContent = "checkpoint " + c.id + ", code " + c.code + " read along the arrow (arrival)";
    var ax = c.x + 0.03 * Math.cos(c.yaw), ay = c.y + 0.03 * Math.sin(c.yaw);
    el("line", { x1: c.x - 0.03 * Math.cos(c.yaw), y1: -(c.y - 0.03 * Math.sin(c.yaw)), x2: ax, y2: -ay,
      stroke: "#000", "stroke-width": 1.2 * unit, "marker-end": "url(#arrow)" }, marks);
  });
  var defs = el("defs", {}, map);
  var arrow = el("marker", { id: "arrow", viewBox: "0 0 10 10", refX: 8, refY: 5, markerWidth: 5, markerHeight: 5, orient: "auto-start-reverse" }, defs);
  el("path", { d: "M 0 0 L 10 5 L 0 10 z", fill: "#000" }, arrow);
  if (world.goal) {
    el("circle", { id: "goal", cx: world.goal[0], cy: -world.goal[1], r: world.goal[2], fill: "#2ca02c", "fill-opacity": 0.45 }, map);
    var goalText = el("text", { x: world.goal[0], y: -world.goal[1] + 4 * unit, "text-anchor": "middle", "font-size": 11 * unit }, map);
    goalText.textContent = "GOAL";
  }
  var start = world.start;
  el("circle", { id: "start", cx: start[0], cy: -start[1], r: robot.radius, fill: "none", stroke: "#1f77b4", "stroke-width": 2 * unit }, map);
  el("line", { x1: start[0], y1: -start[1], x2: start[0] + 1.6 * robot.radius * Math.cos(start[2]),
    y2: -(start[1] + 1.6 * robot.radius * Math.sin(start[2])), stroke: "#1f77b4", "stroke-width": 2 * unit }, map);
  var trail = el("polyline", { id: "trail", fill: "none", stroke: fleet ? ROBOT_COLOURS[0] : "#d62728", "stroke-width": 2 * unit, "stroke-opacity": 0.8 }, map);
  var decisionMarks = el("g", { id: "decision-marks" }, map);
  var rays = el("g", { id: "rays", "stroke-width": 1.5 * unit }, map);
  var rayLines = robot.sensors.map(function () { return el("line", {}, rays); });
  var body = el("g", { id: "robot" }, map);
  var bodyDisc = el("circle", { cx: 0, cy: 0, r: robot.radius, fill: "#1f77b4", stroke: "#0b3c5d", "stroke-width": unit }, body);
  el("line", { x1: 0, y1: 0, x2: robot.radius * 1.15, y2: 0, stroke: "#fff", "stroke-width": 3.5 * unit, "stroke-linecap": "round" }, body);
  // What is drawn of each robot: robot 0's elements above, then one set per other robot.
  var views = [{ profile: robot, body: body, disc: bodyDisc, trail: trail, rays: rayLines, colour: "#1f77b4", name: robot.name }];
  if (fleet) {
    views[0].name = fleet[0].robot_name;
    fleet.slice(1).forEach(function (profile, i) {
      var k = i + 1, colour = ROBOT_COLOURS[k % ROBOT_COLOURS.length];
      var otherTrail = el("polyline", { id: "trail-" + k, fill: "none", stroke: colour, "stroke-width": 2 * unit, "stroke-opacity": 0.8 }, map);
      map.insertBefore(otherTrail, decisionMarks);
      var otherRays = el("g", { id: "rays-" + k, "stroke-width": 1.5 * unit }, map);
      var otherBody = el("g", { id: "robot-" + k, "class": "robot" }, map);
      var disc = el("circle", { cx: 0, cy: 0, r: profile.radius, fill: colour, stroke: "#0b3c5d", "stroke-width": unit }, otherBody);
      el("line", { x1: 0, y1: 0, x2: profile.radius * 1.15, y2: 0, stroke: "#fff", "stroke-width": 3.5 * unit, "stroke-linecap": "round" }, otherBody);
      el("title", {}, otherBody).textContent = profile.robot_name;
      views.push({ profile: profile, body: otherBody, disc: disc, trail: otherTrail, colour: colour, name: profile.robot_name,
        rays: profile.sensors.map(function () { return el("line", {}, otherRays); }) });
    });
    el("title", {}, body).textContent = fleet[0].robot_name;
  }
  // The frames each robot is in the world: a robot a supervisor imports or removes is drawn
  // only from its from_frame to its until_frame (run format 1.2).
  views.forEach(function (view, k) {
    var entry = run.robots ? run.robots[k] : null;
    view.from = entry && entry.from_frame ? entry.from_frame : 0;
    view.until = entry && entry.until_frame != null ? entry.until_frame : Infinity;
  });

  var legend = document.getElementById("legend");
  var robotItems = fleet ? views.map(function (view) { return [view.colour, "robot " + view.name + " and its trail (red when touching)"]; }) :
    [["#1f77b4", "start / robot (white line: heading)"]];
  [["#8c3b1f", "walls"], [grey(0.2), "floor paint (grey = reflectance)"], ["#ffd92f", "checkpoint (id; arrow: arrival direction)"]].concat(robotItems,
   [["#2ca02c", "goal"]], fleet ? [] : [["#d62728", "trail"]], [
   ["linear-gradient(90deg,#d62728,#2ca02c)", "sensor rays: red near, green far"],
   ["#08519c", "D1, D2...: decisions of the higher level (not checkpoint ids)"]]).forEach(function (item) {
    var li = document.createElement("li");
    var swatch = document.createElement("span");
    swatch.className = "swatch";
    swatch.style.background = item[0];
    li.appendChild(swatch);
    li.appendChild(document.createTextNode(item[1]));
    legend.appendChild(li);
  });

  // -- the state of the view -------------------------------------------------------------------
  var state = { episode: 0, frame: 0, playing: false, speed: 1, robot: { x: 0, y: 0, yaw: 0 }, robots: [], selected: 0, frames: 0, draws: 0 };
  window.mazesimReplay = state;
  var slider = document.getElementById("slider");
  var timeline = document.getElementById("timeline");

  function subtaskName(index) {
    return index >= 0 && index < run.subtask_names.length ? run.subtask_names[index] : "none";
  }
  function subtaskChip(index) {
    return '<span class="chip" style="background:' + SUBTASK_COLOURS[index % SUBTASK_COLOURS.length] + '">' +
      escapeHtml(subtaskName(index)) + "</span>";
  }
  function escapeHtml(value) {
    return String(value).replace(/[&<>"]/g, function (c) { return { "&": "&amp;", "<": "&lt;", ">": "&gt;", '"': "&quot;" }[c]; });
  }
  function turnWords(index) {
    var name = subtaskName(index).toLowerCase();
    return name.replace(" on a door", "").replace("going forward", "straight on");
  }
  function decisionLabel(d) {
    return "D" + d.number + ": " + turnWords(d.chosen);
  }

  function selectEpisode(index) {
    state.episode = index;
    var episode = episodes[index];
    state.frames = episode.frames;
    slider.max = Math.max(episode.frames - 1, 0);
    while (decisionMarks.firstChild) { decisionMarks.removeChild(decisionMarks.firstChild); }
    episode.decisions.forEach(function (d) {
      var g = el("g", { "class": "decision-mark" }, decisionMarks);
      var x = episode.x[d.frame], y = episode.y[d.frame];
      el("rect", { x: x - 11 * unit, y: -y - 20 * unit, width: 22 * unit, height: 12 * unit, rx: 3 * unit, fill: "#08519c" }, g);
      var t = el("text", { x: x, y: -y - 11 * unit, "text-anchor": "middle", "font-size": 9 * unit, fill: "#fff" }, g);
      t.textContent = "D" + d.number;
      var title = el("title", {}, g);
      title.textContent = decisionLabel(d) + " at checkpoint " + d.checkpoint;
    });
    var list = document.getElementById("decisions");
    list.innerHTML = "";
    episode.decisions.forEach(function (d) {
      var li = document.createElement("li");
      li.id = "decision-" + d.number;
      li.textContent = decisionLabel(d) + " (checkpoint " + d.checkpoint + ", " + d.direction + ", step " + d.frame + ")";
      li.addEventListener("click", function () { show(d.frame); });
      list.appendChild(li);
    });
    document.getElementById("decision-box").style.display = run.subtask_names.length ? "" : "none";
    document.getElementById("intro").style.display = run.subtask_names.length ? "" : "none";
    document.getElementById("subtask-box").style.display = episode.subtasks ? "" : "none";
    drawTimeline(episode);
    show(0);
  }

  function drawTimelineKey(episode) {
    var parts = [];
    if (episode.subtasks) {
      parts.push("band: sub-task running (" + run.subtask_names.map(function (name, k) {
        return '<span style="background:' + SUBTASK_COLOURS[k % SUBTASK_COLOURS.length] + '"></span>' + escapeHtml(name);
      }).join(", ") + ")");
    }
    parts.push('<span style="background:#e6b800"></span>barcode read');
    if (run.subtask_names.length) { parts.push('<span style="background:#08519c"></span>decision D1, D2...'); }
    parts.push('<span style="background:#000"></span>step shown');
    document.getElementById("timeline-key").innerHTML = "Timeline: " + parts.join(" &middot; ");
  }

  function drawTimeline(episode) {
    drawTimelineKey(episode);
    while (timeline.firstChild) { timeline.removeChild(timeline.firstChild); }
    var frames = Math.max(episode.frames, 1);
    timeline.setAttribute("viewBox", "0 0 " + frames + " 46");
    if (episode.subtasks) {
      var begin = 0;
      for (var i = 1; i <= episode.subtasks.length; i++) {
        if (i === episode.subtasks.length || episode.subtasks[i] !== episode.subtasks[begin]) {
          var code = episode.subtasks[begin];
          var index = code === "-" ? -1 : Number(code);
          if (index >= 0) {
            var band = el("rect", { x: begin, y: 0, width: i - begin, height: 14, fill: SUBTASK_COLOURS[index % SUBTASK_COLOURS.length] }, timeline);
            el("title", {}, band).textContent = subtaskName(index) + ", steps " + begin + "-" + (i - 1);
          }
          begin = i;
        }
      }
    }
    episode.eventFrames.forEach(function (frame) {
      var tick = el("rect", { x: frame, y: 15, width: Math.max(frames / 400, 1), height: 12, fill: "#e6b800", "class": "event-tick" }, timeline);
      var event = episode.events[frame];
      el("title", {}, tick).textContent = "barcode of checkpoint " + Math.abs(event) + " (" + (event > 0 ? "arrival" : "departure") + "), step " + frame;
    });
    episode.decisions.forEach(function (d) {
      var flag = el("rect", { x: d.frame, y: 28, width: Math.max(frames / 250, 1), height: 16, fill: "#08519c", "class": "decision-tick" }, timeline);
      el("title", {}, flag).textContent = decisionLabel(d);
    });
    el("rect", { id: "cursor", x: 0, y: 0, width: Math.max(frames / 300, 1), height: 46, fill: "#000", "fill-opacity": 0.6 }, timeline);
  }

  function rayColour(episode, frame, sensor, profile) {
    if (episode.levels) { return LEVEL_COLOURS[Number(episode.levels[frame][sensor])]; }
    var near = Math.min(Math.max(episode.readings[frame][sensor] / profile.distance_max, 0), 1);
    var hue = Math.round(120 * (1 - Math.pow(near, 0.5)));
    return "hsl(" + hue + ",80%,45%)";
  }

  function lastAtOrBefore(frames, frame) {
    var found = -1;
    for (var i = 0; i < frames.length && frames[i] <= frame; i++) { found = i; }
    return found;
  }

  function drawRobot(view, track, frame) {
    var x = track.x[frame], y = track.y[frame], yaw = track.yaw[frame];
    var present = frame >= view.from && frame <= view.until, shown = present ? "visible" : "hidden";
    view.body.setAttribute("transform", "translate(" + x + "," + (-y) + ") rotate(" + (-degrees(yaw)) + ")");
    view.body.setAttribute("data-x", fixed(x, 4));
    view.body.setAttribute("data-y", fixed(y, 4));
    view.body.setAttribute("visibility", shown);
    view.disc.setAttribute("fill", track.contacts[frame] ? "#d62728" : view.colour);
    // Its trail runs from where it joined the world to where it is, or where it left it.
    var points = [], last = Math.min(frame, view.until);
    var stride = Math.max(1, Math.floor((last - view.from) / 2000));
    for (var i = view.from; i <= last; i += stride) { points.push(fixed(track.x[i], 4) + "," + fixed(-track.y[i], 4)); }
    if (last >= view.from) { points.push(fixed(track.x[last], 4) + "," + fixed(-track.y[last], 4)); }
    view.trail.setAttribute("points", points.join(" "));
    view.rays.forEach(function (line) { line.setAttribute("visibility", shown); });
    view.profile.sensors.forEach(function (sensor, k) {
      var c = Math.cos(yaw), s = Math.sin(yaw);
      var ox = x + c * sensor[0] - s * sensor[1], oy = y + s * sensor[0] + c * sensor[1];
      var reach = track.rays[frame][k];
      var line = view.rays[k];
      line.setAttribute("x1", ox); line.setAttribute("y1", -oy);
      line.setAttribute("x2", ox + reach * Math.cos(yaw + sensor[2]));
      line.setAttribute("y2", -(oy + reach * Math.sin(yaw + sensor[2])));
      line.setAttribute("stroke", rayColour(track, frame, k, view.profile));
    });
    return { name: view.name, x: x, y: y, yaw: yaw, touching: !!track.contacts[frame], present: present };
  }

  function drawRobotsTable(episode, frame) {
    if (!fleet) { return; }
    var rows = views.map(function (view, k) {
      var track = k ? episode.others[k - 1] : episode, where = state.robots[k];
      var speeds = track.wheelSpeeds ? track.wheelSpeeds[frame] : null;
      return '<tr id="robot-row-' + k + '" class="' + (k === state.selected ? "selected" : "") + '"><td><span class="swatch" style="background:' +
        view.colour + '"></span>' + escapeHtml(view.name) + '</td><td class="num">' + fixed(where.x, 3) + ", " +
        fixed(where.y, 3) + '</td><td class="num">' + fixed(degrees(where.yaw), 0) + '&deg;</td><td class="num">' +
        (speeds ? fixed(speeds[0] / 100, 1) + " / " + fixed(speeds[1] / 100, 1) : "\u2014") + "</td><td>" +
        (!where.present ? "not in the world" : where.touching ? "touching" : "") + "</td></tr>";
    });
    var tableBody = document.querySelector("#robots tbody");
    tableBody.innerHTML = rows.join("");
    Array.prototype.forEach.call(tableBody.querySelectorAll("tr"), function (row, k) {
      row.addEventListener("click", function () { selectRobot(k); });
    });
  }

  function selectRobot(index) {
    state.selected = Math.max(0, Math.min(index, views.length - 1));
    show(state.frame);
  }

  function show(frame) {
    var episode = episodes[state.episode];
    frame = Math.max(0, Math.min(Math.round(frame), episode.frames - 1));
    state.frame = frame;
    drawWalls(episode, frame);
    state.robots = views.map(function (view, k) { return drawRobot(view, k ? episode.others[k - 1] : episode, frame); });
    state.robot = state.robots[0];
    slider.value = frame;
    text("frame-label", "step " + frame + " / " + (episode.frames - 1) + "   t = " + fixed(frame * stepSeconds, 2) + " s");
    text("clock", "t = " + fixed(frame * stepSeconds, 2) + " s, step " + frame + " of " + (episode.frames - 1) +
      (episode.contacts[frame] ? "  (touching a wall)" : "") +
      (frame === episode.frames - 1 ? "  \u2014 " + episode.outcome : ""));
    drawRobotsTable(episode, frame);
    drawPanel(episode, frame);
    var cursor = document.getElementById("cursor");
    if (cursor) { cursor.setAttribute("x", frame); }
    state.draws += 1;
  }

  function drawPanel(robotZero, frame) {
    var episode = state.selected ? robotZero.others[state.selected - 1] : robotZero;
    var robot = views[state.selected].profile;
    if (fleet) { text("sensors-of", "of " + views[state.selected].name); }
    var body = document.querySelector("#readings tbody");
    var rows = [];
    robot.names.forEach(function (name, k) {
      var value = episode.readings[frame][k];
      var distance = k < robot.distance_count;
      var level = distance && episode.levels ? episode.levels[frame][k] : "\u2014";
      var ray = distance ? fixed(100 * episode.rays[frame][k], 1) + " cm" : "";
      var shown = robot.unit === "volts" && distance ? fixed(value, 3) + " V" : fixed(value, 0);
      rows.push('<tr><td>' + escapeHtml(name) + '</td><td class="num" id="reading-' + k + '">' + shown +
        '</td><td class="num" id="level-' + k + '">' + level + '</td><td class="num">' + ray + "</td></tr>");
    });
    body.innerHTML = rows.join("");
    text("levels-note", episode.levels ? "level: Table 4.1 of the report (Integration of a Webots Mobile Robot Simulation in ROS), 0 (< 7 cm), 1 (< 13 cm), 2 (< 20 cm), 3 (farther); ray: distance to the wall the sensor faces" :
      (fleet ? "ray: distance to the wall or robot the sensor faces" : "ray: distance to the wall the sensor faces") +
      " (Table 4.1 levels apply to the six Sharp sensors of the seed robot)");
    var action = "\u2014";
    if (episode.actions && episode.actions[frame]) {
      var code = episode.actions[frame];
      action = "<b>" + escapeHtml(code) + "</b> " + escapeHtml(scene.actions[code] || "");
    } else if (episode.wheelSpeeds) {
      var speeds = episode.wheelSpeeds[frame];
      action = "wheels left " + fixed(speeds[0] / 100, 2) + ", right " + fixed(speeds[1] / 100, 2) + " rad/s";
    }
    document.getElementById("action").innerHTML = action;
    if (episode.subtasks) {
      var code2 = episode.subtasks[frame];
      document.getElementById("subtask").innerHTML = code2 === "-" || code2 === undefined ? "none" : subtaskChip(Number(code2));
    }
    var seen = lastAtOrBefore(episode.eventFrames, frame);
    if (seen >= 0) {
      var at = episode.eventFrames[seen], event = episode.events[at];
      var cp = world.checkpoints.filter(function (c) { return c.id === Math.abs(event); })[0];
      var bars = cp ? (event > 0 ? cp.code : cp.code.split("").reverse().join("")) : "?";
      document.getElementById("barcode").innerHTML = "checkpoint <b>" + Math.abs(event) + "</b>, " +
        (event > 0 ? "arrival (read along its arrow)" : "departure (read backwards)") + ", bars <code>" + bars +
        "</code>, at step " + at + (at === frame ? " <b>(this step)</b>" : "");
    } else {
      text("barcode", "none yet");
    }
    var decisions = robotZero.decisions;
    var current = -1;
    for (var i = 0; i < decisions.length && decisions[i].frame <= frame; i++) { current = i; }
    Array.prototype.forEach.call(document.querySelectorAll("#decisions li"), function (li, k) {
      li.className = k === current ? "current" : "";
    });
    var box = document.getElementById("decision");
    if (current < 0) { box.textContent = "none yet: the higher level chooses when a barcode is read"; return; }
    var d = decisions[current];
    var best = Math.max.apply(null, d.q_values), worst = Math.min.apply(null, d.q_values);
    var rowsQ = d.q_values.map(function (q, k) {
      var width = best > worst ? 3 * (q - worst) / (best - worst) : 3;
      return '<tr class="' + (k === d.chosen ? "chosen" : "") + '"><td>' + (k === d.chosen ? "&#x25B6; " : "") + subtaskChip(k) +
        '</td><td class="num">' + fixed(q, 2) + '</td><td><span class="qbar" style="width:' + fixed(width, 2) + 'em"></span></td></tr>';
    });
    var why = d.greedy ? "it has the highest value of the four in this state (greedy choice)" :
      "exploring: a random choice, not the highest value";
    box.innerHTML = '<p class="why"><b>D' + d.number + "</b> (decision " + d.number + ", at step " + d.frame + (d.frame === frame ? ", this step" : "") +
      "): the robot read the barcode <code>" + escapeHtml(d.code) + "</code> of <b>checkpoint " + d.checkpoint + "</b> (" + d.direction +
      "), so the higher level looked up the state <b>" + (d.direction === "arrival" ? "+" : "\u2212") + d.checkpoint +
      "</b> and chose <b>" + escapeHtml(subtaskName(d.chosen)) + "</b>: " + why + ".</p>" +
      "<table><thead><tr><th>sub-task (&#x25B6; chosen)</th><th class=\"num\">Q-value</th><th></th></tr></thead><tbody>" + rowsQ.join("") + "</tbody></table>" +
      '<p class="note why">Q-value: the reward the higher level learned to expect, from this checkpoint and direction to the goal, ' +
      "if it starts that sub-task here (each step costs a little, touching a wall a lot, the goal pays 100). The turn on the map follows from the chosen sub-task.</p>";
  }

  // -- controls --------------------------------------------------------------------------------
  var episodeSelect = document.getElementById("episode");
  episodes.forEach(function (episode, index) {
    var option = document.createElement("option");
    option.value = index;
    option.textContent = "episode " + episode.number + " (" + (episode.frames - 1) + " steps, " + episode.outcome + ")";
    episodeSelect.appendChild(option);
  });
  episodeSelect.addEventListener("change", function () { pause(); selectEpisode(Number(episodeSelect.value)); });
  var speedSelect = document.getElementById("speed");
  SPEEDS.forEach(function (speed) {
    var option = document.createElement("option");
    option.value = speed;
    option.textContent = speed + "x";
    if (speed === 1) { option.selected = true; }
    speedSelect.appendChild(option);
  });
  speedSelect.addEventListener("change", function () { state.speed = Number(speedSelect.value); });
  function setSpeed(direction) {
    var index = SPEEDS.indexOf(state.speed) + direction;
    index = Math.max(0, Math.min(SPEEDS.length - 1, index));
    state.speed = SPEEDS[index];
    speedSelect.value = state.speed;
  }

  var playButton = document.getElementById("play");
  var lastTime = null, carried = 0;
  function tick(now) {
    if (!state.playing) { return; }
    if (lastTime !== null) {
      carried += (now - lastTime) / 1000 * state.speed / stepSeconds;
      var whole = Math.floor(carried);
      if (whole > 0) {
        carried -= whole;
        show(state.frame + whole);
        if (state.frame >= state.frames - 1) { pause(); return; }
      }
    }
    lastTime = now;
    window.requestAnimationFrame(tick);
  }
  function play() {
    if (state.frame >= state.frames - 1) { show(0); }
    state.playing = true;
    lastTime = null; carried = 0;
    playButton.textContent = "pause";
    window.requestAnimationFrame(tick);
  }
  function pause() {
    state.playing = false;
    playButton.innerHTML = "&#x25B6; play";
  }
  function toggle() { if (state.playing) { pause(); } else { play(); } }
  function jumpDecision(direction) {
    var decisions = episodes[state.episode].decisions;
    var target = null;
    decisions.forEach(function (d) {
      if (direction > 0 && d.frame > state.frame && target === null) { target = d.frame; }
      if (direction < 0 && d.frame < state.frame) { target = d.frame; }
    });
    if (target !== null) { show(target); }
  }
  playButton.addEventListener("click", toggle);
  document.getElementById("back").addEventListener("click", function () { pause(); show(state.frame - 1); });
  document.getElementById("forward").addEventListener("click", function () { pause(); show(state.frame + 1); });
  document.getElementById("first").addEventListener("click", function () { pause(); show(0); });
  document.getElementById("last").addEventListener("click", function () { pause(); show(state.frames - 1); });
  slider.addEventListener("input", function () { pause(); show(Number(slider.value)); });
  timeline.addEventListener("click", function (event) {
    var rect = timeline.getBoundingClientRect();
    pause();
    show((event.clientX - rect.left) / rect.width * state.frames);
  });
  document.addEventListener("keydown", function (event) {
    if (event.target && event.target.tagName === "SELECT") { return; }
    var step = event.shiftKey ? 10 : 1;
    if (event.key === " ") { toggle(); }
    else if (event.key === "ArrowRight") { pause(); show(state.frame + step); }
    else if (event.key === "ArrowLeft") { pause(); show(state.frame - step); }
    else if (event.key === "Home") { pause(); show(0); }
    else if (event.key === "End") { pause(); show(state.frames - 1); }
    else if (event.key === "+" || event.key === "=") { setSpeed(1); }
    else if (event.key === "-") { setSpeed(-1); }
    else if (event.key === "n" || event.key === "N") { pause(); jumpDecision(1); }
    else if (event.key === "p" || event.key === "P") { pause(); jumpDecision(-1); }
    else { return; }
    event.preventDefault();
  });
  state.show = show;
  state.play = play;
  state.pause = pause;
  state.selectEpisode = selectEpisode;
  state.selectRobot = selectRobot;
  if (fleet) { document.getElementById("robots-box").style.display = ""; }
  selectEpisode(0);
})();
