# ruff: noqa: E501  (the JavaScript and Lua sources keep their own line lengths)
"""The helper modules procedural PROTO templates import, written for mazesim from the API that
Webots documents (``docs/reference/javascript-procedural-proto.md``: ``wbrandom``,
``wbrotation``, ``wbvector2``, ``wbvector3``, ``wbgeometry``, ``wbutility``; the Lua templates
of earlier versions ``require`` modules of the same names). The random generator is a linear
congruential generator, as documented; its constants are the C standard's example ones."""

from __future__ import annotations

__all__ = ["JAVASCRIPT_MODULES", "LUA_MODULES"]

#: JavaScript source of each module: an expression whose value is the module object.
JAVASCRIPT_MODULES: dict[str, str] = {
    "wbrandom": """(function () {
  let state = 0;
  const next = () => { state = (state * 1103515245 + 12345) % 2147483648; return state; };
  return {
    seed: (s) => { state = Math.abs(Math.floor(s)) % 2147483648; },
    real: (min, max) => {
      if (min === undefined) { min = 0; max = 1; } else if (max === undefined) { max = min; min = 0; }
      return min + (next() / 2147483647) * (max - min);
    },
    integer: (min, max) => {
      if (min === undefined) { min = 0; max = 16777215; } else if (max === undefined) { max = min; min = 0; }
      return min + (next() % (max - min + 1));
    },
  };
})()""",
    "wbvector2": """({
  equal: (a, b) => a.x === b.x && a.y === b.y,
  add: (a, b) => ({x: a.x + b.x, y: a.y + b.y}),
  minus: (a, b) => ({x: a.x - b.x, y: a.y - b.y}),
  multiply: (v, s) => ({x: v.x * s, y: v.y * s}),
  norm: (v) => Math.hypot(v.x, v.y),
  distance: (a, b) => Math.hypot(a.x - b.x, a.y - b.y),
  angle: (a, b) => Math.atan2(b.y - a.y, b.x - a.x),
  cross: (a, b) => a.x * b.y - a.y * b.x,
  dot: (a, b) => a.x * b.x + a.y * b.y,
  normalize: (v) => { const n = Math.hypot(v.x, v.y); return n === 0 ? {x: 0, y: 0} : {x: v.x / n, y: v.y / n}; },
  intersection: (p1, p2, p3, p4) => {
    const d = (p4.y - p3.y) * (p2.x - p1.x) - (p4.x - p3.x) * (p2.y - p1.y);
    if (d === 0) return null;
    const ua = ((p4.x - p3.x) * (p1.y - p3.y) - (p4.y - p3.y) * (p1.x - p3.x)) / d;
    const ub = ((p2.x - p1.x) * (p1.y - p3.y) - (p2.y - p1.y) * (p1.x - p3.x)) / d;
    if (ua < 0 || ua > 1 || ub < 0 || ub > 1) return null;
    return {x: p1.x + ua * (p2.x - p1.x), y: p1.y + ua * (p2.y - p1.y)};
  },
})""",
    "wbvector3": """({
  equal: (a, b) => a.x === b.x && a.y === b.y && a.z === b.z,
  add: (a, b) => ({x: a.x + b.x, y: a.y + b.y, z: a.z + b.z}),
  minus: (a, b) => ({x: a.x - b.x, y: a.y - b.y, z: a.z - b.z}),
  multiply: (v, s) => ({x: v.x * s, y: v.y * s, z: v.z * s}),
  norm: (v) => Math.hypot(v.x, v.y, v.z),
  distance: (a, b) => Math.hypot(a.x - b.x, a.y - b.y, a.z - b.z),
  cross: (a, b) => ({x: a.y * b.z - a.z * b.y, y: a.z * b.x - a.x * b.z, z: a.x * b.y - a.y * b.x}),
  dot: (a, b) => a.x * b.x + a.y * b.y + a.z * b.z,
  normalize: (v) => { const n = Math.hypot(v.x, v.y, v.z); return n === 0 ? {x: 0, y: 0, z: 0} : {x: v.x / n, y: v.y / n, z: v.z / n}; },
})""",
    "wbrotation": """(function () {
  const toQuaternion = (r) => {
    const n = Math.hypot(r.x, r.y, r.z) || 1, h = r.a / 2, s = Math.sin(h) / n;
    return {w: Math.cos(h), x: r.x * s, y: r.y * s, z: r.z * s};
  };
  const fromQuaternion = (q) => {
    const n = Math.hypot(q.w, q.x, q.y, q.z) || 1;
    const w = Math.max(-1, Math.min(1, q.w / n)), s = Math.sqrt(1 - w * w);
    if (s < 1e-12) return {x: 0, y: 0, z: 1, a: 0};
    return {x: q.x / n / s, y: q.y / n / s, z: q.z / n / s, a: 2 * Math.acos(w)};
  };
  const toMatrix3 = (r) => {
    const q = toQuaternion(r), {w, x, y, z} = q;
    return [1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w),
            2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w),
            2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)];
  };
  const fromMatrix3 = (m) => {
    const w = Math.sqrt(Math.max(0, 1 + m[0] + m[4] + m[8])) / 2;
    const x = Math.sqrt(Math.max(0, 1 + m[0] - m[4] - m[8])) / 2 * Math.sign(m[7] - m[5] || 1);
    const y = Math.sqrt(Math.max(0, 1 - m[0] + m[4] - m[8])) / 2 * Math.sign(m[2] - m[6] || 1);
    const z = Math.sqrt(Math.max(0, 1 - m[0] - m[4] + m[8])) / 2 * Math.sign(m[3] - m[1] || 1);
    return fromQuaternion({w, x, y, z});
  };
  const multiply = (a, b) => ({
    w: a.w * b.w - a.x * b.x - a.y * b.y - a.z * b.z,
    x: a.w * b.x + a.x * b.w + a.y * b.z - a.z * b.y,
    y: a.w * b.y - a.x * b.z + a.y * b.w + a.z * b.x,
    z: a.w * b.z + a.x * b.y - a.y * b.x + a.z * b.w,
  });
  const byMatrix = (m, v) => ({x: m[0] * v.x + m[1] * v.y + m[2] * v.z,
    y: m[3] * v.x + m[4] * v.y + m[5] * v.z, z: m[6] * v.x + m[7] * v.y + m[8] * v.z});
  return {
    equal: (a, b) => a.x === b.x && a.y === b.y && a.z === b.z && a.a === b.a,
    toQuaternion, fromQuaternion, toMatrix3, fromMatrix3,
    isIdentity: (r) => Math.abs(r.a % (2 * Math.PI)) < 1e-12,
    normalize: (r) => { const n = Math.hypot(r.x, r.y, r.z) || 1;
      return {x: r.x / n, y: r.y / n, z: r.z / n, a: r.a % (2 * Math.PI)}; },
    combine: (a, b) => fromQuaternion(multiply(toQuaternion(b), toQuaternion(a))),
    rotateVector3ByMatrix3: byMatrix,
    rotateVector3ByRotation: (r, v) => byMatrix(toMatrix3(r), v),
    rotateVector3ByQuaternion: (q, v) => byMatrix(toMatrix3(fromQuaternion(q)), v),
  };
})()""",
    "wbgeometry": """(function () {
  const spline = (points, subdivision, keys) => {
    if (points.length < 3) return points.slice();
    const result = [];
    const at = (i) => points[Math.max(0, Math.min(points.length - 1, i))];
    for (let i = -1; i < points.length; ++i) {
      const p = [at(i - 1), at(i), at(i + 1), at(i + 2)];
      for (let k = 0; k < subdivision; ++k) {
        const t = k / subdivision, t2 = t * t, t3 = t2 * t;
        const b = [(1 - t) ** 3 / 6, (3 * t3 - 6 * t2 + 4) / 6, (-3 * t3 + 3 * t2 + 3 * t + 1) / 6, t3 / 6];
        const point = {};
        for (const key of keys) point[key] = b[0] * p[0][key] + b[1] * p[1][key] + b[2] * p[2][key] + b[3] * p[3][key];
        result.push(point);
      }
    }
    return result;
  };
  return {
    circle: (radius, div, c, shift) => {
      const points = [];
      for (let i = 0; i < div; ++i) {
        const a = shift + 2 * Math.PI * i / div;
        points.push({x: c.x + radius * Math.cos(a), y: c.y + radius * Math.sin(a)});
      }
      return points;
    },
    isPoint2InPolygon: (p, polygon) => {
      let inside = false;
      for (let i = 0, j = polygon.length - 1; i < polygon.length; j = i++) {
        const a = polygon[i], b = polygon[j];
        if ((a.y > p.y) !== (b.y > p.y) && p.x < (b.x - a.x) * (p.y - a.y) / (b.y - a.y) + a.x) inside = !inside;
      }
      return inside;
    },
    findClosestPoint2InArray: (reference, points) => points.reduce((best, p) =>
      Math.hypot(p.x - reference.x, p.y - reference.y) < Math.hypot(best.x - reference.x, best.y - reference.y) ? p : best),
    isPoint2ArrayClockwise: (points) => {
      let sum = 0;
      for (let i = 0; i < points.length; ++i) {
        const a = points[i], b = points[(i + 1) % points.length];
        sum += (b.x - a.x) * (b.y + a.y);
      }
      return sum > 0;
    },
    bSpline2: (points, subdivision) => spline(points, subdivision, ['x', 'y']),
    bSpline3: (points, subdivision) => spline(points, subdivision, ['x', 'y', 'z']),
  };
})()""",
    "wbutility": """({
  assert: (statement, message) => { if (!statement) console.error(message); },
  error: (message) => console.error(message),
  info: (message) => console.log(message),
  deepCopy: (o) => JSON.parse(JSON.stringify(o)),
  degreesToRadians: (a) => a * Math.PI / 180,
  radiansToDegrees: (a) => a * 180 / Math.PI,
  isScalar: (s) => typeof s === 'number',
  isVector2: (v) => v !== null && typeof v === 'object' && Object.keys(v).length === 2 && 'x' in v && 'y' in v,
  isVector3: (v) => v !== null && typeof v === 'object' && Object.keys(v).length === 3 && 'x' in v && 'y' in v && 'z' in v,
  isAxisAngle: (r) => r !== null && typeof r === 'object' && Object.keys(r).length === 4 && 'a' in r,
  isQuaternion: (q) => q !== null && typeof q === 'object' && Object.keys(q).length === 4 && 'w' in q,
  isMatrix3: (m) => m !== null && typeof m === 'object' && Object.keys(m).length === 9,
  isArrayOfPoints: (a, dim) => Array.isArray(a) && a.every((p) => Object.keys(p).length === dim),
})""",
}

#: Lua source of each module: a chunk that returns the module table.
LUA_MODULES: dict[str, str] = {
    "wbrandom": """local m, state = {}, 0
local function next_value() state = (state * 1103515245 + 12345) % 2147483648; return state end
function m.seed(s) state = math.floor(math.abs(s)) % 2147483648 end
function m.real(min, max)
  if min == nil then min, max = 0, 1 elseif max == nil then min, max = 0, min end
  return min + next_value() / 2147483647 * (max - min)
end
function m.integer(min, max)
  if min == nil then min, max = 0, 16777215 elseif max == nil then min, max = 0, min end
  return min + next_value() % (max - min + 1)
end
return m""",
    "wbvector2": """local m = {}
function m.add(a, b) return {x = a.x + b.x, y = a.y + b.y} end
function m.minus(a, b) return {x = a.x - b.x, y = a.y - b.y} end
function m.multiply(v, s) return {x = v.x * s, y = v.y * s} end
function m.norm(v) return math.sqrt(v.x * v.x + v.y * v.y) end
function m.distance(a, b) return m.norm(m.minus(a, b)) end
function m.angle(a, b) return math.atan(b.y - a.y, b.x - a.x) end
function m.dot(a, b) return a.x * b.x + a.y * b.y end
function m.cross(a, b) return a.x * b.y - a.y * b.x end
function m.normalize(v) local n = m.norm(v); if n == 0 then return {x = 0, y = 0} end; return {x = v.x / n, y = v.y / n} end
function m.equal(a, b) return a.x == b.x and a.y == b.y end
return m""",
    "wbvector3": """local m = {}
function m.add(a, b) return {x = a.x + b.x, y = a.y + b.y, z = a.z + b.z} end
function m.minus(a, b) return {x = a.x - b.x, y = a.y - b.y, z = a.z - b.z} end
function m.multiply(v, s) return {x = v.x * s, y = v.y * s, z = v.z * s} end
function m.norm(v) return math.sqrt(v.x * v.x + v.y * v.y + v.z * v.z) end
function m.distance(a, b) return m.norm(m.minus(a, b)) end
function m.dot(a, b) return a.x * b.x + a.y * b.y + a.z * b.z end
function m.cross(a, b) return {x = a.y * b.z - a.z * b.y, y = a.z * b.x - a.x * b.z, z = a.x * b.y - a.y * b.x} end
function m.normalize(v) local n = m.norm(v); if n == 0 then return {x = 0, y = 0, z = 0} end; return m.multiply(v, 1 / n) end
function m.equal(a, b) return a.x == b.x and a.y == b.y and a.z == b.z end
return m""",
    "wbgeometry": """local m = {}
function m.circle(radius, div, c, shift)
  local points = {}
  for i = 0, div - 1 do
    local a = shift + 2 * math.pi * i / div
    points[#points + 1] = {x = c.x + radius * math.cos(a), y = c.y + radius * math.sin(a)}
  end
  return points
end
return m""",
    # lua-gd, which Webots' Lua bundles for templates that draw a texture (RoboCup Junior's
    # victims write a letter into a PNG): its images here draw and save nothing, so such a
    # template runs and its texture file is missing.
    "gd": """local m, image = {}, {}
image.__index = image
function image.colorAllocate() return 0 end
function image.colorAllocateAlpha() return 0 end
function image.colorResolve() return 0 end
function image.filledRectangle() end
function image.rectangle() end
function image.filledEllipse() end
function image.line() end
function image.setPixel() end
function image.fill() end
function image.stringFT() return {0, 0, 0, 0, 0, 0, 0, 0} end
function image.string() end
function image.copy() end
function image.copyResampled() end
function image.saveAlpha() end
function image.png() return false end
function image.jpeg() return false end
function image.gif() return false end
function image.sizeXY(im) return im.width, im.height end
function image.sizeX(im) return im.width end
function image.sizeY(im) return im.height end
local function create(width, height) return setmetatable({width = width, height = height}, image) end
m.create, m.createTrueColor, m.createPalette = create, create, create
function m.createFromPng() return nil end
function m.createFromJpeg() return nil end
function m.fontCacheSetup() return true end
function m.fontCacheShutdown() end
return m""",
    "wbcore": """local m = {}
function m.tablelength(t) local n = 0; for _ in pairs(t) do n = n + 1 end; return n end
return m""",
}
