// The viewer of eomgen's animation page: reads the scene of docs/animation.md from #scene and
// draws it with three.js (r111) beside two plots of the coordinates and energies. Plain
// JavaScript, no modules: the page is opened from disk and loads nothing.
(function () {
  'use strict';

  var statusElement = document.getElementById('status');
  var status = { ready: false, errors: window.eomgenErrors, drawn: 0, t: null, requests: 0, missingMeshes: 0 };
  var testHook = null;  // what the URL's #t=...&layers=... asked for (the browser test's hook)

  // #status always holds the state; the title says "ready" or "error: ..." only for the test hook
  function report() {
    status.requests = performance.getEntriesByType('resource').length;
    statusElement.textContent = JSON.stringify(status);
    if (testHook === null || !status.ready) return;
    document.title = status.errors.length > 0 ? 'error: ' + status.errors[0] : 'ready t=' + status.t;
  }
  window.eomgenOnError = report;

  function showMessage(text) {
    var m = document.getElementById('message');
    m.textContent = text;
    m.hidden = false;
  }

  // ---- the scene's data, read defensively: a missing array is an empty one --------------------

  var scene;
  try {
    scene = JSON.parse(document.getElementById('scene').textContent);
  } catch (e) {
    window.eomgenErrors.push('the scene is not JSON: ' + e.message);
    showMessage('This page\'s scene cannot be read (' + e.message + '): it is damaged; write it again with eomgen.');
    scene = {};
  }
  function list(value) { return Array.isArray(value) ? value : []; }
  function vector3(value, fallback) {
    return Array.isArray(value) && value.length === 3 ? new THREE.Vector3(value[0], value[1], value[2]) : fallback;
  }
  var times = list(scene.times);
  var n = times.length;
  var t0 = n > 0 ? times[0] : 0, t1 = n > 0 ? times[n - 1] : 0;
  var points = list(scene.points), frames = list(scene.frames), shapes = list(scene.shapes);
  var particles = list(scene.particles), links = list(scene.links), forces = list(scene.forces);
  var series = list(scene.series), trailDefaults = list(scene.trails);
  var meshes = list(scene.meshes), missingMeshes = list(scene.missing_meshes);
  var up = vector3(scene.up, new THREE.Vector3(0, 0, 1)).normalize();

  document.getElementById('model-name').textContent = scene.model || '';
  document.getElementById('model-description').textContent =
      (scene.description || '') + (scene.source ? ' (' + scene.source + ')' : '');
  if (n === 0 && document.getElementById('message').hidden) showMessage('The scene has no samples.');

  // ---- meshes: the triangles of STL files, 9 little-endian float32 per triangle in base64 -----

  // a mesh decoded once, however many shapes draw it: { positions, box } (box: the vertices'
  // [xmin, ymin, zmin, xmax, ymax, zmax], null without triangles) or { error }
  var littleEndianHost = new Uint8Array(new Uint16Array([1]).buffer)[0] === 1;
  var decodedMeshes = {};
  function decodeMesh(k) {
    if (typeof k !== 'number' || !(k >= 0 && k < meshes.length) || Math.floor(k) !== k) {
      return { error: 'no mesh ' + JSON.stringify(k) + ' (the scene has ' + meshes.length + ')' };
    }
    if (!(k in decodedMeshes)) {
      try {
        decodedMeshes[k] = meshVertices(meshes[k]);
      } catch (e) {
        decodedMeshes[k] = { error: 'mesh ' + k + ': ' + e.message };
      }
    }
    return decodedMeshes[k];
  }
  function meshVertices(m) {
    if (!m || typeof m !== 'object') throw new Error('it is not an object');
    var triangles = m.triangles;
    if (typeof triangles !== 'number' || !(triangles >= 0) || Math.floor(triangles) !== triangles) {
      throw new Error('its number of triangles is ' + JSON.stringify(triangles));
    }
    if (typeof m.vertices !== 'string') throw new Error('its vertices are not a base64 string');
    var text;
    try {
      text = atob(m.vertices);
    } catch (e) {
      throw new Error('its vertices are not base64');
    }
    if (text.length !== 36 * triangles) {
      throw new Error(text.length + ' bytes of vertices where ' + triangles + ' triangles need ' + 36 * triangles);
    }
    var bytes = new Uint8Array(text.length);
    for (var i = 0; i < text.length; ++i) bytes[i] = text.charCodeAt(i);
    var x;
    if (littleEndianHost) {
      x = new Float32Array(bytes.buffer);
    } else {
      var data = new DataView(bytes.buffer);
      x = new Float32Array(9 * triangles);
      for (i = 0; i < x.length; ++i) x[i] = data.getFloat32(4 * i, true);
    }
    var box = x.length > 0 ? [Infinity, Infinity, Infinity, -Infinity, -Infinity, -Infinity] : null;
    for (i = 0; i < x.length; ++i) {
      if (!isFinite(x[i])) throw new Error('coordinate ' + i + ' of its vertices is not a finite number');
      var j = i % 3;
      if (x[i] < box[j]) box[j] = x[i];
      if (x[i] > box[3 + j]) box[3 + j] = x[i];
    }
    return { positions: x, box: box };
  }
  // A mesh shape whose mesh cannot be drawn is an error, and is left out (drawn nowhere, sizing
  // nothing). The box of a mesh shape, in its frame's components from its point: its `bounds`
  // and its vertices' box together (the two are the same unless the scene is damaged)
  var shapeBounds = new Map(), sceneShapes = shapes;
  shapes = shapes.filter(function (s) {
    if (!s || s.kind !== 'mesh') return true;
    var d = decodeMesh(s.mesh);
    if (d.error) {
      window.eomgenErrors.push('shape ' + s.name + ': ' + d.error);
      return false;
    }
    var b = list(s.bounds), box = d.box ? d.box.slice() : null;
    var valid = b.length === 6 && b.every(function (v, i) { return typeof v === 'number' && isFinite(v) && (i >= 3 || v <= b[i + 3]); });
    if (valid && box) {
      for (var j = 0; j < 3; ++j) { box[j] = Math.min(box[j], b[j]); box[3 + j] = Math.max(box[3 + j], b[3 + j]); }
    }
    shapeBounds.set(s, box);
    return true;
  });
  function meshBox(s) { return shapeBounds.get(s) || null; }

  // The meshes the scene could not draw (not found, not STL, too large for the page), said
  // quietly above the view: a line with all of them, and the list in full when opened
  (function () {
    var notice = document.getElementById('missing-meshes');
    if (missingMeshes.length === 0 || !notice) return;
    var entries = missingMeshes.map(function (m) {
      var field = function (name) {
        var v = m && typeof m === 'object' ? m[name] : undefined;
        return v === undefined || v === null ? '?' : String(v);
      };
      return { shape: field('shape'), file: field('file'), reason: field('reason') };
    });
    var line = entries.length + (entries.length === 1 ? ' mesh' : ' meshes') + ' not drawn: ' +
               entries.map(function (e) { return e.file + ': ' + e.reason; }).join('; ');
    var summary = document.getElementById('missing-meshes-summary');
    summary.textContent = line;
    summary.title = line;
    var items = document.getElementById('missing-meshes-list');
    entries.forEach(function (e) {
      var item = document.createElement('li');
      item.textContent = 'shape ' + e.shape + ', ' + e.file + ': ' + e.reason;
      items.appendChild(item);
    });
    notice.hidden = false;
    status.missingMeshes = items.children.length;
  })();

  // the sample interval holding t and the fraction of the way through it
  function locate(t) {
    if (n < 2 || t <= t0) return { k: 0, f: 0 };
    if (t >= t1) return { k: n - 2, f: 1 };
    var lo = 0, hi = n - 1;
    while (hi - lo > 1) {
      var mid = (lo + hi) >> 1;
      if (times[mid] <= t) lo = mid; else hi = mid;
    }
    var span = times[hi] - times[lo];
    return { k: lo, f: span > 0 ? (t - times[lo]) / span : 0 };
  }

  // a point's position at the located time, linearly interpolated (the origin if it has none)
  function pointAt(index, at, out) {
    var p = points[index] ? list(points[index].positions) : [];
    if (p.length < 3 * n || n === 0) return out.set(0, 0, 0);
    var a = 3 * at.k, b = n > 1 ? 3 * (at.k + 1) : a;
    return out.set(p[a] + at.f * (p[b] - p[a]), p[a + 1] + at.f * (p[b + 1] - p[a + 1]),
                   p[a + 2] + at.f * (p[b + 2] - p[a + 2]));
  }

  // a frame's orientation: the rotation matrices' columns are its unit vectors in inertial
  // components, so the matrix maps frame components to inertial ones; slerp between samples
  var matrix = new THREE.Matrix4(), qa = new THREE.Quaternion(), qb = new THREE.Quaternion();
  function quaternionAtSample(r, k, out) {
    var i = 9 * k;
    matrix.set(r[i], r[i + 1], r[i + 2], 0, r[i + 3], r[i + 4], r[i + 5], 0, r[i + 6], r[i + 7], r[i + 8], 0, 0, 0, 0, 1);
    return out.setFromRotationMatrix(matrix);
  }
  function frameAt(index, at, out) {
    var r = index >= 0 && frames[index] ? list(frames[index].rotations) : [];
    if (r.length < 9 * n || n === 0) return out.set(0, 0, 0, 1);
    quaternionAtSample(r, at.k, qa);
    if (n > 1 && at.f > 0) qa.slerp(quaternionAtSample(r, at.k + 1, qb), at.f);
    return out.copy(qa);
  }

  // ---- the size of the scene: the box of every point over the run, which sizes what has no size
  // of its own (particles, axes, arrows, shapes without dimensions) ----------------------------

  var box = new THREE.Box3();
  points.forEach(function (p) {
    var x = list(p.positions);
    for (var i = 0; i + 2 < x.length; i += 3) box.expandByPoint(new THREE.Vector3(x[i], x[i + 1], x[i + 2]));
  });
  if (box.isEmpty()) box.set(new THREE.Vector3(-0.5, -0.5, -0.5), new THREE.Vector3(0.5, 0.5, 0.5));
  var centre = box.getCenter(new THREE.Vector3());
  var size = Math.max(box.getSize(new THREE.Vector3()).length(), centre.length() * 0.5, 1e-3);
  // a body that does not travel (a free body turning about its centre) is as large as its shapes'
  // largest diameter; scenery that belongs to no body (a rail, a wall) does not count (the view
  // frames it all the same, below)
  var shapeSize = 0;
  shapes.forEach(function (s) {
    if (!s.body) return;
    if (s.radius > 0 && s.kind !== 'rod') shapeSize = Math.max(shapeSize, 2 * s.radius);
    if (s.length > 0) shapeSize = Math.max(shapeSize, s.length);
    var e = list(s.size);
    if (e.length === 3) shapeSize = Math.max(shapeSize, Math.hypot(e[0], e[1], e[2]));
    var b = s.kind === 'mesh' ? meshBox(s) : null;
    if (b) shapeSize = Math.max(shapeSize, Math.hypot(b[3] - b[0], b[4] - b[1], b[5] - b[2]));
  });
  size = Math.max(size, shapeSize);

  // A mechanism that travels far beyond its own size (a bicycle riding 25 m) would be drawn with
  // shapes, particles and arrows the size of its whole run: then things are sized by the
  // mechanism (its largest extent at one instant) instead. The mechanism is its moving points
  // and the fixed points linked to them (a pendulum's pivot), not a fixed point that is only
  // the origin of the coordinates.
  var wholeSize = size;
  function positionsOf(index) {
    var x = points[index] ? list(points[index].positions) : [];
    return x.length >= 3 * n ? x : [];
  }
  var moving = [], isMoving = points.map(function () { return false; });
  points.forEach(function (p, index) {
    var x = positionsOf(index);
    for (var i = 3; i < x.length; ++i) {
      if (Math.abs(x[i] - x[i % 3]) > 1e-9 * wholeSize) { moving.push(index); isMoving[index] = true; return; }
    }
  });
  var inMechanism = isMoving.slice();
  function linked(i, j) {
    if (isMoving[i] && typeof j === 'number' && j >= 0 && j < points.length) inMechanism[j] = true;
    if (isMoving[j] && typeof i === 'number' && i >= 0 && i < points.length) inMechanism[i] = true;
  }
  links.forEach(function (l) { if (Array.isArray(l)) linked(l[0], l[1]); });
  shapes.forEach(function (s) { if (s.kind === 'rod') linked(s.at, s.to); });
  var mechanismPoints = [];
  inMechanism.forEach(function (on, index) { if (on) mechanismPoints.push(index); });
  if (moving.length === 0) {
    moving = points.map(function (p, index) { return index; });
    mechanismPoints = moving;
  }
  var mechanism = shapeSize;
  for (var i = 0; i < n; i += Math.max(1, Math.floor(n / 200))) {
    var instant = new THREE.Box3();
    mechanismPoints.forEach(function (index) {
      var x = positionsOf(index);
      if (x.length > 0) instant.expandByPoint(new THREE.Vector3(x[3 * i], x[3 * i + 1], x[3 * i + 2]));
    });
    if (!instant.isEmpty()) mechanism = Math.max(mechanism, instant.getSize(new THREE.Vector3()).length());
  }
  var travels = mechanism > 0 && wholeSize > 3 * mechanism;
  if (travels) size = mechanism;

  // how far each point's drawing reaches beyond the point: the shapes centred there (their
  // bounding spheres), the rods ending there, the particle drawn there
  var masses = particles.map(function (p) { return p.mass > 0 ? p.mass : 0; });
  var heaviest = Math.max.apply(null, masses.concat([0]));
  function particleRadius(p) {
    var relative = heaviest > 0 && p.mass > 0 ? Math.cbrt(p.mass / heaviest) : 1;
    return 0.03 * size * Math.max(relative, 0.4);
  }
  function shapeRadius(s) {
    return s.radius > 0 ? s.radius : (s.kind === 'rod' ? 0.004 : 0.02) * size;
  }
  // a frame's unit vectors at sample k in inertial components (the columns of its rotation), or
  // the inertial frame's
  function frameAxesAt(index, k) {
    var r = typeof index === 'number' && index >= 0 && frames[index] ? list(frames[index].rotations) : [];
    if (r.length < 9 * n || k >= n) return [new THREE.Vector3(1, 0, 0), new THREE.Vector3(0, 1, 0), new THREE.Vector3(0, 0, 1)];
    var i = 9 * k;
    return [new THREE.Vector3(r[i], r[i + 3], r[i + 6]), new THREE.Vector3(r[i + 1], r[i + 4], r[i + 7]),
            new THREE.Vector3(r[i + 2], r[i + 5], r[i + 8])];
  }
  function shapeLength(s, r) { return s.length > 0 ? s.length : (s.kind === 'disk' ? 0.1 * r : 2 * r); }
  function boxEdges(s, r) { var e = list(s.size); return e.length === 3 ? e : [r, r, r]; }
  // how far a shape centred at its point reaches along the unit vector u at sample k (its
  // support); a rod reaches its radius beyond its two points, a mesh its box's farthest corner
  // (its box is about its point, not centred there: the support can be negative)
  function shapeSupport(s, k, u) {
    var r = shapeRadius(s), axes, c;
    switch (s.kind) {
      case 'sphere': case 'rod': return r;
      case 'box':
        axes = frameAxesAt(s.frame, k);
        var e = boxEdges(s, r);
        return 0.5 * (Math.abs(u.dot(axes[0])) * e[0] + Math.abs(u.dot(axes[1])) * e[1] + Math.abs(u.dot(axes[2])) * e[2]);
      case 'cylinder': case 'disk':
        axes = frameAxesAt(s.frame, k);
        var a = vector3(s.axis, new THREE.Vector3(0, 0, 1)).normalize();
        c = u.dot(axes[0]) * a.x + u.dot(axes[1]) * a.y + u.dot(axes[2]) * a.z;  // u along the shape's axis
        return 0.5 * shapeLength(s, r) * Math.abs(c) + r * Math.sqrt(Math.max(0, 1 - c * c));
      case 'mesh':
        var b = meshBox(s);
        if (!b) return 0;
        axes = frameAxesAt(s.frame, k);
        var most = 0;
        for (var j = 0; j < 3; ++j) {
          var w = u.dot(axes[j]);  // u's component along the frame's axis j
          most += Math.max(w * b[j], w * b[3 + j]);
        }
        return most;
      default: return 0;
    }
  }
  function isPoint(index) { return typeof index === 'number' && index >= 0 && index < points.length; }

  // what is drawn about each point whatever the attitude: rods' ends, particles' spheres; a
  // particle is drawn unless a shape (other than a rod) names it as its body
  var shownAsBody = {};
  shapes.forEach(function (s) { if (s.body && s.kind !== 'rod') shownAsBody[s.body] = true; });
  var pointRadius = points.map(function () { return 0; });
  function widens(index, r) { if (isPoint(index) && r > 0) pointRadius[index] = Math.max(pointRadius[index], r); }
  shapes.forEach(function (s) { if (s.kind === 'rod') { widens(s.at, shapeRadius(s)); widens(s.to, shapeRadius(s)); } });
  particles.forEach(function (p) { if (!shownAsBody[p.name]) widens(p.point, particleRadius(p)); });
  // and the sphere about each point that holds everything drawn there in any attitude (for a
  // following camera)
  var reach = pointRadius.slice();
  shapes.forEach(function (s) {
    if (!isPoint(s.at) || s.kind === 'rod') return;
    var r = shapeRadius(s), e = boxEdges(s, r), b = meshBox(s);
    var around = s.kind === 'box' ? 0.5 * Math.hypot(e[0], e[1], e[2]) :
                 s.kind === 'sphere' ? r :
                 s.kind === 'mesh' ? (b ? Math.hypot(Math.max(-b[0], b[3]), Math.max(-b[1], b[4]), Math.max(-b[2], b[5])) : 0) :
                 Math.hypot(r, 0.5 * shapeLength(s, r));
    reach[s.at] = Math.max(reach[s.at], around);
  });

  // how far the run as drawn reaches along the unit vector u: every point at every sample with
  // what is drawn about it, every shape in its attitude at every sample, and the origin
  function runExtent(u) {
    var most = 0, p = new THREE.Vector3();
    points.forEach(function (q, index) {
      var x = positionsOf(index);
      for (var i = 0; i + 2 < x.length; i += 3) most = Math.max(most, x[i] * u.x + x[i + 1] * u.y + x[i + 2] * u.z + pointRadius[index]);
    });
    shapes.forEach(function (s) {
      var x = isPoint(s.at) && s.kind !== 'rod' ? positionsOf(s.at) : [];
      for (var k = 0; 3 * k + 2 < x.length; ++k) {
        most = Math.max(most, p.set(x[3 * k], x[3 * k + 1], x[3 * k + 2]).dot(u) + shapeSupport(s, k, u));
      }
    });
    return most;
  }
  // the box of the run as drawn; the grid covers it, and the fixed camera frames it with the
  // axes (viewBox)
  var runBox = new THREE.Box3(), corner = new THREE.Vector3();
  if (n > 0 && points.length > 0) {
    var extents = [0, 1, 2].map(function (k) {
      return [-runExtent(new THREE.Vector3().setComponent(k, -1)), runExtent(new THREE.Vector3().setComponent(k, 1))];
    });
    runBox.set(new THREE.Vector3(extents[0][0], extents[1][0], extents[2][0]),
               new THREE.Vector3(extents[0][1], extents[1][1], extents[2][1]));
  } else {
    runBox.copy(box);
  }
  runBox.expandByPoint(new THREE.Vector3());
  var viewBox = runBox.clone();
  function boxCorner(b, k, out) {
    return out.set(k & 1 ? b.max.x : b.min.x, k & 2 ? b.max.y : b.min.y, k & 4 ? b.max.z : b.min.z);
  }

  // ---- renderer, camera, lights ---------------------------------------------------------------

  var view = document.getElementById('view');
  var background = new THREE.Color(0xf3f4f6);
  var renderer = new THREE.WebGLRenderer({ antialias: true });
  renderer.setPixelRatio(window.devicePixelRatio || 1);
  renderer.setClearColor(background, 1);
  view.appendChild(renderer.domElement);
  var world = new THREE.Scene();
  var camera = new THREE.PerspectiveCamera(40, 1, size * 1e-3, size * 100);
  camera.up.copy(up);
  world.add(new THREE.HemisphereLight(0xffffff, 0x8a8f99, 0.75));
  var sun = new THREE.DirectionalLight(0xffffff, 0.6);
  world.add(sun);
  var controls = new THREE.OrbitControls(camera, renderer.domElement);

  // What the camera does: "" (the default) a fixed camera that frames the whole run,
  // "mechanism" one that follows the mean of the moving points, "body:NAME" one that follows a
  // body (where it is drawn: its shape's point, else its particle's). A following camera frames
  // the sphere about what it follows that holds the whole mechanism at every sample.
  var follow = '';
  function bodyPoint(name) {
    var at = -1;
    shapes.forEach(function (s) { if (at < 0 && s.body === name && s.kind !== 'rod' && typeof s.at === 'number') at = s.at; });
    shapes.forEach(function (s) { if (at < 0 && s.body === name && typeof s.at === 'number') at = s.at; });
    particles.forEach(function (p) { if (at < 0 && p.name === name && typeof p.point === 'number') at = p.point; });
    return at >= 0 && at < points.length ? at : -1;
  }
  var followedBodies = [];
  shapes.map(function (s) { return s.body; }).concat(particles.map(function (p) { return p.name; }))
      .concat(frames.map(function (f) { return f.body; })).forEach(function (name) {
        if (typeof name === 'string' && name !== '' && followedBodies.indexOf(name) < 0 && bodyPoint(name) >= 0) followedBodies.push(name);
      });
  // the followed point at a located time
  function followedAt(at, out) {
    if (follow.indexOf('body:') === 0) return pointAt(bodyPoint(follow.slice(5)), at, out);
    return centroidAt(at, out);
  }
  function centroidAt(at, out) {
    out.set(0, 0, 0);
    if (moving.length === 0) return out;
    var p = new THREE.Vector3();
    moving.forEach(function (index) { out.add(pointAt(index, at, p)); });
    return out.divideScalar(moving.length);
  }
  // the radius about the followed point that holds the mechanism (and what is drawn around its
  // points) at every sample; between samples both move linearly, so the samples bound it
  var followRadii = {};
  function followRadius() {
    if (follow in followRadii) return followRadii[follow];
    var r = 0.5 * shapeSize, f = new THREE.Vector3(), p = new THREE.Vector3();
    for (var k = 0; k < n; ++k) {
      var at = { k: Math.min(k, Math.max(n - 2, 0)), f: n > 1 && k === n - 1 ? 1 : 0 };
      followedAt(at, f);
      mechanismPoints.forEach(function (index) {
        if (positionsOf(index).length > 0) r = Math.max(r, pointAt(index, at, p).distanceTo(f) + reach[index]);
      });
    }
    followRadii[follow] = r > 0 ? r : 0.5 * size;
    return followRadii[follow];
  }

  // the view from the front, a little from the side and above: "front" is inertial z made
  // perpendicular to up (or -y when up is along z); the unit vector from the target to the camera
  function viewDirection() {
    var front = new THREE.Vector3(0, 0, 1);
    if (Math.abs(front.dot(up)) > 0.9) front.set(0, -1, 0);
    front.addScaledVector(up, -front.dot(up)).normalize();
    var side = new THREE.Vector3().crossVectors(up, front);
    var azimuth = 0.45, elevation = 0.3;
    return front.multiplyScalar(Math.cos(azimuth)).addScaledVector(side, Math.sin(azimuth))
        .multiplyScalar(Math.cos(elevation)).addScaledVector(up, Math.sin(elevation)).normalize();
  }
  // the tangents of half the field of view, vertical and horizontal, with a margin of 6 %
  function halfViews() {
    var v = Math.tan(camera.fov / 2 * Math.PI / 180) / 1.06;
    return { v: v, h: v * camera.aspect };
  }
  function placeCamera(target, direction, distance, extent) {
    camera.position.copy(target).addScaledVector(direction, distance);
    // near enough to zoom in on the smallest part, far enough to zoom out a long way
    camera.near = 1e-3 * Math.max(distance, extent);
    camera.far = 20 * (distance + extent);
    controls.maxDistance = 10 * (distance + extent);
    camera.updateProjectionMatrix();
    controls.target.copy(target);
    controls.update();
    sun.position.copy(camera.position).addScaledVector(up, extent);
  }
  // The fixed camera: every corner of the box of the run and the axes inside the view. With the
  // camera's axes x, y and z (z from the target to the camera), a corner at c from the target is
  // inside at the distance d when |c.x| <= h (d - c.z) and |c.y| <= v (d - c.z); the box holds
  // every point of the run, so they all are. The target is moved to centre the corners' image.
  function frameTheRun() {
    var z = viewDirection(), x = new THREE.Vector3().crossVectors(up, z).normalize(), y = new THREE.Vector3().crossVectors(z, x);
    var target = viewBox.getCenter(new THREE.Vector3()), half = halfViews();
    var extent = viewBox.getSize(new THREE.Vector3()).length(), c = new THREE.Vector3();
    var corners = function () {
      var out = [];
      for (var k = 0; k < 8; ++k) {
        boxCorner(viewBox, k, c).sub(target);
        out.push([c.dot(x), c.dot(y), c.dot(z)]);
      }
      return out;
    };
    var distanceFor = function (cs) {
      var d = 0.05 * extent;
      cs.forEach(function (p) {
        d = Math.max(d, p[2] + Math.abs(p[0]) / half.h, p[2] + Math.abs(p[1]) / half.v, p[2] + 0.05 * extent);
      });
      return d;
    };
    for (var pass = 0; pass < 3; ++pass) {
      var cs = corners(), distance = distanceFor(cs), lo = [Infinity, Infinity], hi = [-Infinity, -Infinity];
      cs.forEach(function (p) {
        for (var j = 0; j < 2; ++j) {
          var u = p[j] / (distance - p[2]);  // the tangent of the corner's angle from the view's centre
          lo[j] = Math.min(lo[j], u); hi[j] = Math.max(hi[j], u);
        }
      });
      target.addScaledVector(x, 0.5 * (lo[0] + hi[0]) * distance).addScaledVector(y, 0.5 * (lo[1] + hi[1]) * distance);
    }
    placeCamera(target, z, distanceFor(corners()), extent);
  }
  // a following camera: the sphere of the followed radius about the followed point in the view
  function frameTheFollowed(t) {
    var half = halfViews(), r = followRadius();
    var distance = r / Math.sin(Math.atan(Math.min(half.v, half.h)));
    placeCamera(followedAt(locate(t), new THREE.Vector3()), viewDirection(), distance, 2 * r);
  }
  function frameTheMotion(t) {
    if (follow) frameTheFollowed(t); else frameTheRun();
    userMoved = false;
  }
  // a following camera keeps its place relative to what it follows: both move with it
  function followTo(t) {
    var shift = followedAt(locate(t), new THREE.Vector3()).sub(controls.target);
    camera.position.add(shift);
    controls.target.add(shift);
    controls.update();
    sun.position.add(shift);
  }
  // until the camera is moved by hand, a new size of the view frames again
  var userMoved = false;
  controls.addEventListener('start', function () { userMoved = true; });

  // ---- what is always drawn: the ground grid, the inertial axes, shapes, particles, links -----

  // The grid lies in the scene's ground when it has one, else in the plane normal to up
  // (against gravity; the a.1-a.2 plane without gravity) at the lowest height the run reaches,
  // or the origin's when that is lower. Its lines run along u and v in the plane, at multiples
  // of a round cell (1, 2 or 5 times a power of 10, a tenth to a 25th of the run) from the
  // origin's foot, every fifth darker, and cover the run with a cell to spare.
  var gridNormal, gridPoint;
  if (scene.ground && typeof scene.ground === 'object') {
    gridNormal = vector3(scene.ground.normal, up.clone()).normalize();
    if (!(gridNormal.lengthSq() > 0.5)) gridNormal = up.clone();
    gridPoint = vector3(scene.ground.point, new THREE.Vector3());
  } else {
    gridNormal = up.clone();
    gridPoint = up.clone().multiplyScalar(n > 0 && points.length > 0 ? -runExtent(up.clone().negate()) : 0);
  }
  var gridU = new THREE.Vector3(1, 0, 0);
  if (Math.abs(gridU.dot(gridNormal)) > 0.9) gridU.set(0, 1, 0);
  gridU.addScaledVector(gridNormal, -gridU.dot(gridNormal)).normalize();
  var gridV = new THREE.Vector3().crossVectors(gridNormal, gridU);
  var grid = (function () {
    var foot = new THREE.Vector3().sub(gridPoint);  // the origin from the grid's point
    var o = [foot.dot(gridU), foot.dot(gridV)];
    var lo = [o[0], o[1]], hi = [o[0], o[1]];
    for (var k = 0; k < 8; ++k) {
      boxCorner(runBox, k, corner).sub(gridPoint);
      var u = corner.dot(gridU), v = corner.dot(gridV);
      lo = [Math.min(lo[0], u), Math.min(lo[1], v)];
      hi = [Math.max(hi[0], u), Math.max(hi[1], v)];
    }
    // a run in a vertical plane (a planar pendulum) would have a strip: at least half as wide as long
    var span = Math.max(hi[0] - lo[0], hi[1] - lo[1], 1e-3);
    for (var j = 0; j < 2; ++j) {
      var pad = Math.max(0, 0.5 * span - (hi[j] - lo[j])) / 2;
      lo[j] -= pad; hi[j] += pad;
    }
    var cell = Math.pow(10, Math.floor(Math.log10(span / 10)));
    if (span / cell > 50) cell *= 5; else if (span / cell > 20) cell *= 2;
    var first = [], last = [];
    for (j = 0; j < 2; ++j) {
      first.push(Math.floor((lo[j] - o[j]) / cell) - 1);
      last.push(Math.ceil((hi[j] - o[j]) / cell) + 1);
    }
    var positions = [], colours = [], minor = new THREE.Color(0xd3d7de), major = new THREE.Color(0xa3aab6);
    var a = new THREE.Vector3(), b = new THREE.Vector3();
    var along = function (u, v, out) { return out.copy(gridPoint).addScaledVector(gridU, u).addScaledVector(gridV, v); };
    // each line a segment per cell: a following camera stands on the grid, and a segment with
    // an end behind the camera is not always drawn (SwiftShader drops it)
    for (j = 0; j < 2; ++j) {
      for (var m = first[j]; m <= last[j]; ++m) {
        var s = o[j] + m * cell, colour = m % 5 === 0 ? major : minor;
        for (var c = first[1 - j]; c < last[1 - j]; ++c) {
          var from = o[1 - j] + c * cell, to = from + cell;
          if (j === 0) { along(s, from, a); along(s, to, b); } else { along(from, s, a); along(to, s, b); }
          positions.push(a.x, a.y, a.z, b.x, b.y, b.z);
          colours.push(colour.r, colour.g, colour.b, colour.r, colour.g, colour.b);
        }
      }
    }
    var geometry = new THREE.BufferGeometry();
    geometry.setAttribute('position', new THREE.Float32BufferAttribute(positions, 3));
    geometry.setAttribute('color', new THREE.Float32BufferAttribute(colours, 3));
    var lines = new THREE.LineSegments(geometry, new THREE.LineBasicMaterial({ vertexColors: THREE.VertexColors }));
    lines.name = 'grid';
    lines.userData.cell = cell;
    world.add(lines);
    return lines;
  })();

  // the inertial frame a: a.1 red, a.2 green, a.3 blue, at the origin, labelled; as long as a
  // fifth of the mechanism, or a cell of the grid when that is longer (a run far beyond the
  // mechanism's size); the fixed camera frames them too
  var axisLength = Math.max(0.2 * size, grid.userData.cell), labelHeight = 0.3 * axisLength;
  var axisColours = [0xd62728, 0x2ca02c, 0x1f5fd6];
  [0, 1, 2].forEach(function (k) {
    var direction = new THREE.Vector3().setComponent(k, 1);
    var arrow = new THREE.ArrowHelper(direction, new THREE.Vector3(), axisLength, axisColours[k],
                                      0.14 * axisLength, 0.07 * axisLength);
    arrow.name = 'axis a.' + (k + 1);
    world.add(arrow);
    var label = textSprite('a.' + (k + 1), '#' + new THREE.Color(axisColours[k]).getHexString(), labelHeight);
    label.name = 'label a.' + (k + 1);
    label.position.copy(direction).multiplyScalar(axisLength + 0.7 * labelHeight);
    world.add(label);
    viewBox.expandByPoint(corner.copy(label.position).addScalar(labelHeight));
    viewBox.expandByPoint(corner.copy(label.position).addScalar(-labelHeight));
  });
  function textSprite(text, colour, height) {
    var canvas = document.createElement('canvas');
    canvas.width = 128; canvas.height = 64;
    var c = canvas.getContext('2d');
    c.font = 'bold 44px sans-serif'; c.textAlign = 'center'; c.textBaseline = 'middle';
    c.fillStyle = colour; c.fillText(text, 64, 34);
    var sprite = new THREE.Sprite(new THREE.SpriteMaterial({ map: new THREE.CanvasTexture(canvas), depthTest: false }));
    sprite.scale.set(2 * height, height, 1);
    sprite.renderOrder = 2;
    sprite.userData.text = text;
    return sprite;
  }

  // one colour per body, in the order bodies first appear: a fixed palette, so the same scene
  // looks the same every time
  var palette = [0x1f77b4, 0xff7f0e, 0x2ca02c, 0xd62728, 0x9467bd, 0x8c564b, 0xe377c2, 0x17becf, 0xbcbd22, 0x7f7f7f];
  var bodyColours = {};
  function colourOf(body) {
    if (body === null || body === undefined) return 0x9aa0a8;
    if (!(body in bodyColours)) bodyColours[body] = palette[Object.keys(bodyColours).length % palette.length];
    return bodyColours[body];
  }

  var unitY = new THREE.Vector3(0, 1, 0);
  // one geometry per mesh, however many shapes draw it; its normals per triangle
  var meshGeometries = {};
  function meshGeometry(k) {
    if (!(k in meshGeometries)) {
      var geometry = new THREE.BufferGeometry();
      geometry.setAttribute('position', new THREE.BufferAttribute(decodeMesh(k).positions, 3));
      geometry.computeVertexNormals();
      meshGeometries[k] = geometry;
    }
    return meshGeometries[k];
  }
  var drawnShapes = shapes.map(function (s) {
    // (a mesh is seen from both sides: STL files often wind their triangles either way)
    var material = new THREE.MeshStandardMaterial({ color: colourOf(s.body), roughness: 0.6, metalness: 0.1,
                                                    transparent: !!s.inferred, opacity: s.inferred ? 0.55 : 1,
                                                    side: s.kind === 'mesh' ? THREE.DoubleSide : THREE.FrontSide });
    // a rod without a radius is a line, drawn thin; other kinds always have one
    var r = shapeRadius(s), geometry = null, turn = null;
    var axis = vector3(s.axis, new THREE.Vector3(0, 0, 1)).normalize();
    switch (s.kind) {
      case 'sphere': geometry = new THREE.SphereBufferGeometry(r, 32, 16); break;
      case 'box':
        var e = Array.isArray(s.size) ? s.size : [r, r, r];
        geometry = new THREE.BoxBufferGeometry(e[0], e[1], e[2]);
        break;
      case 'cylinder': case 'disk':
        var length = s.length > 0 ? s.length : (s.kind === 'disk' ? 0.1 * r : 2 * r);
        geometry = new THREE.CylinderBufferGeometry(r, r, length, 40);
        turn = new THREE.Quaternion().setFromUnitVectors(unitY, axis);  // three's cylinder is along y
        break;
      case 'rod': geometry = new THREE.CylinderBufferGeometry(r, r, 1, 16); break;  // scaled to the points' distance
      case 'mesh': geometry = meshGeometry(s.mesh); break;  // in the frame's components from the point, as placed
      default: window.eomgenErrors.push('shape ' + s.name + ': unknown kind ' + s.kind); return null;
    }
    var mesh = new THREE.Mesh(geometry, material);
    if (turn) mesh.quaternion.copy(turn);
    var group = new THREE.Group();
    group.add(mesh);
    world.add(group);
    return { shape: s, group: group, mesh: mesh };
  });

  // (a rod only takes its body's colour: the body is still drawn, docs/model-language.md)
  var drawnParticles = particles.filter(function (p) { return !shownAsBody[p.name]; }).map(function (p) {
    var mesh = new THREE.Mesh(new THREE.SphereBufferGeometry(particleRadius(p), 32, 16),
                              new THREE.MeshStandardMaterial({ color: colourOf(p.name), roughness: 0.5 }));
    world.add(mesh);
    return { point: p.point, mesh: mesh };
  });

  function dynamicLine(count, material, segments) {
    var geometry = new THREE.BufferGeometry();
    geometry.setAttribute('position', new THREE.BufferAttribute(new Float32Array(3 * count), 3));
    var line = segments ? new THREE.LineSegments(geometry, material) : new THREE.Line(geometry, material);
    line.frustumCulled = false;  // its vertices move; its bounding sphere is never recomputed
    world.add(line);
    return line;
  }
  var linkLines = dynamicLine(2 * links.length, new THREE.LineBasicMaterial({ color: 0x2b303a }), true);

  // ---- optional layers: body frames, trails, constraint forces --------------------------------

  var frameAxes = [];
  frames.forEach(function (f, index) {
    if (f.body === null || f.body === undefined) return;
    // drawn where the body is drawn: its shape's point, else its particle's, else the origin
    var at = -1;
    shapes.forEach(function (s) { if (at < 0 && s.body === f.body) at = s.at; });
    particles.forEach(function (p) { if (at < 0 && p.name === f.body) at = p.point; });
    var axes = new THREE.AxesHelper(0.15 * size);
    axes.material.depthTest = false;
    axes.renderOrder = 1;
    world.add(axes);
    frameAxes.push({ frame: index, point: at, axes: axes });
  });

  var trails = points.map(function (p, index) {
    var line = dynamicLine(n, new THREE.LineBasicMaterial({ color: 0x6b4fbb, transparent: true, opacity: 0.7 }), false);
    var x = line.geometry.attributes.position.array, source = list(p.positions);
    for (var i = 0; i < 3 * n && i < source.length; ++i) x[i] = source[i];
    line.geometry.attributes.position.needsUpdate = true;
    line.userData.wanted = trailDefaults.indexOf(index) >= 0;
    return line;
  });

  var largestForce = 0;
  forces.forEach(function (f) {
    var v = list(f.vectors);
    for (var i = 0; i + 2 < v.length; i += 3) largestForce = Math.max(largestForce, Math.hypot(v[i], v[i + 1], v[i + 2]));
  });
  var forceScale = largestForce > 0 ? 0.3 * size / largestForce : 0;
  var forceArrows = forces.map(function (f) {
    var arrow = new THREE.ArrowHelper(new THREE.Vector3(0, 0, 1), new THREE.Vector3(), 1, 0xc0392b);
    world.add(arrow);
    return { force: f, arrow: arrow };
  });

  var layers = { frames: false, trails: true, forces: false };

  // ---- the state at time t --------------------------------------------------------------------

  var current = t0, scratch = new THREE.Vector3(), other = new THREE.Vector3(), q = new THREE.Quaternion();
  function place(t) {
    var at = locate(t);
    drawnShapes.forEach(function (d) {
      if (!d) return;
      var s = d.shape;
      if (s.kind === 'rod') {
        pointAt(s.at, at, scratch);
        pointAt(s.to, at, other);
        var length = scratch.distanceTo(other);
        d.group.position.copy(scratch).add(other).multiplyScalar(0.5);
        d.mesh.scale.set(1, Math.max(length, 1e-9), 1);
        if (length > 0) d.mesh.quaternion.setFromUnitVectors(unitY, other.sub(scratch).divideScalar(length));
        return;
      }
      pointAt(s.at, at, d.group.position);
      frameAt(typeof s.frame === 'number' ? s.frame : -1, at, d.group.quaternion);
    });
    drawnParticles.forEach(function (d) { pointAt(d.point, at, d.mesh.position); });
    var x = linkLines.geometry.attributes.position.array;
    links.forEach(function (l, i) {
      pointAt(l[0], at, scratch).toArray(x, 6 * i);
      pointAt(l[1], at, scratch).toArray(x, 6 * i + 3);
    });
    linkLines.geometry.attributes.position.needsUpdate = true;
    frameAxes.forEach(function (d) {
      d.axes.visible = layers.frames;
      if (d.point >= 0) pointAt(d.point, at, d.axes.position);
      frameAt(d.frame, at, d.axes.quaternion);
    });
    var shownSamples = n === 0 ? 0 : at.k + (at.f > 0 ? 2 : 1);
    trails.forEach(function (line) {
      line.visible = layers.trails && line.userData.wanted;
      line.geometry.setDrawRange(0, shownSamples);
    });
    forceArrows.forEach(function (d) {
      var v = list(d.force.vectors);
      var k = at.f < 0.5 || n < 2 ? at.k : at.k + 1;  // nearest sample: a force can jump
      if (v.length < 3 * n || n === 0) { d.arrow.visible = false; return; }
      scratch.set(v[3 * k], v[3 * k + 1], v[3 * k + 2]);
      var length = scratch.length() * forceScale;
      d.arrow.visible = layers.forces && length > 1e-6 * size;
      if (!d.arrow.visible) return;
      pointAt(d.force.point, at, d.arrow.position);
      d.arrow.setDirection(scratch.normalize());
      d.arrow.setLength(length, Math.min(0.25 * length, 0.05 * size), Math.min(0.12 * length, 0.025 * size));
    });
  }

  // ---- plots: coordinates and energies against time, with a cursor ----------------------------

  var plotColours = ['#1f77b4', '#ff7f0e', '#2ca02c', '#d62728', '#9467bd', '#8c564b', '#e377c2', '#17becf',
                     '#bcbd22', '#7f7f7f'];
  var plots = ['coordinates', 'energy'].map(function (group) {
    var canvas = document.getElementById('plot-' + group);
    var members = series.filter(function (s) { return s.group === group; });
    var legend = document.getElementById('legend-' + group);
    members.forEach(function (s, i) {
      var entry = document.createElement('span');
      entry.textContent = s.name;
      entry.style.setProperty('--colour', plotColours[i % plotColours.length]);
      legend.appendChild(entry);
    });
    var plot = { canvas: canvas, members: members, image: null, margin: { left: 46, right: 8, top: 6, bottom: 18 } };
    // clicking or dragging in a plot seeks there
    var seekFrom = function (event) {
      var r = canvas.getBoundingClientRect(), m = plot.margin;
      var u = (event.clientX - r.left - m.left) / Math.max(r.width - m.left - m.right, 1);
      seek(t0 + Math.min(Math.max(u, 0), 1) * (t1 - t0));
    };
    canvas.addEventListener('pointerdown', function (e) { canvas.setPointerCapture(e.pointerId); seekFrom(e); });
    canvas.addEventListener('pointermove', function (e) { if (e.buttons & 1) seekFrom(e); });
    return plot;
  });

  function niceTicks(lo, hi, count) {
    var step = Math.pow(10, Math.floor(Math.log10((hi - lo) / count)));
    var err = (hi - lo) / count / step;
    step *= err >= 7.5 ? 10 : err >= 3.5 ? 5 : err >= 1.5 ? 2 : 1;
    var ticks = [];
    for (var v = Math.ceil(lo / step) * step; v <= hi + 1e-9 * step; v += step) ticks.push(Math.abs(v) < 1e-12 * step ? 0 : v);
    return ticks;
  }

  // the curves are drawn once per size into an image; each frame copies it and adds the cursor
  function drawPlot(plot) {
    var canvas = plot.canvas, ratio = window.devicePixelRatio || 1;
    var w = Math.max(canvas.clientWidth, 1), h = Math.max(canvas.clientHeight, 1);
    canvas.width = Math.round(w * ratio); canvas.height = Math.round(h * ratio);
    var c = canvas.getContext('2d'), m = plot.margin;
    c.setTransform(ratio, 0, 0, ratio, 0, 0);
    c.clearRect(0, 0, w, h);
    c.font = '11px sans-serif'; c.fillStyle = '#555d6b'; c.strokeStyle = '#c9cdd3'; c.lineWidth = 1;
    var lo = Infinity, hi = -Infinity;
    plot.members.forEach(function (s) { list(s.values).forEach(function (v) { if (v < lo) lo = v; if (v > hi) hi = v; }); });
    if (!(lo <= hi) || n === 0) {
      c.fillText('no data', m.left, 20);
      plot.image = c.getImageData(0, 0, canvas.width, canvas.height);
      plot.x = function () { return m.left; };
      return;
    }
    if (hi - lo < 1e-12 * Math.max(1, Math.abs(hi))) { lo -= 0.5; hi += 0.5; }
    var pad = 0.05 * (hi - lo); lo -= pad; hi += pad;
    var pw = w - m.left - m.right, ph = h - m.top - m.bottom;
    var span = t1 > t0 ? t1 - t0 : 1;
    plot.x = function (t) { return m.left + (t - t0) / span * pw; };
    var y = function (v) { return m.top + (hi - v) / (hi - lo) * ph; };
    c.strokeRect(m.left, m.top, pw, ph);
    c.textAlign = 'right'; c.textBaseline = 'middle';
    niceTicks(lo, hi, Math.max(2, Math.floor(ph / 30))).forEach(function (v) {
      c.fillText(Number(v.toPrecision(6)).toString(), m.left - 4, y(v));
      c.beginPath(); c.moveTo(m.left, y(v)); c.lineTo(m.left + pw, y(v)); c.globalAlpha = 0.4; c.stroke(); c.globalAlpha = 1;
    });
    c.textAlign = 'center'; c.textBaseline = 'top';
    if (t1 > t0) niceTicks(t0, t1, Math.max(2, Math.floor(pw / 70))).forEach(function (t) {
      c.fillText(Number(t.toPrecision(6)) + (t === t0 ? ' s' : ''), plot.x(t), m.top + ph + 3);
    });
    plot.members.forEach(function (s, i) {
      var v = list(s.values);
      c.strokeStyle = plotColours[i % plotColours.length]; c.lineWidth = 1.5;
      c.beginPath();
      for (var k = 0; k < v.length && k < n; ++k) {
        if (k === 0) c.moveTo(plot.x(times[k]), y(v[k])); else c.lineTo(plot.x(times[k]), y(v[k]));
      }
      c.stroke();
    });
    plot.image = c.getImageData(0, 0, canvas.width, canvas.height);
  }

  function drawCursor(plot) {
    if (!plot.image) return;
    var c = plot.canvas.getContext('2d'), ratio = window.devicePixelRatio || 1;
    c.putImageData(plot.image, 0, 0);
    var x = plot.x(current);
    c.setTransform(ratio, 0, 0, ratio, 0, 0);
    c.strokeStyle = '#1d2330'; c.lineWidth = 1;
    c.beginPath(); c.moveTo(x, plot.margin.top); c.lineTo(x, plot.canvas.clientHeight - plot.margin.bottom); c.stroke();
  }

  // ---- controls -------------------------------------------------------------------------------

  var playButton = document.getElementById('play'), speedSelect = document.getElementById('speed');
  var slider = document.getElementById('time'), readout = document.getElementById('time-readout');
  var playing = n > 1, dirty = true;
  slider.max = String(Math.max(n - 1, 0));

  function seek(t) {
    current = Math.min(Math.max(t, t0), t1);
    dirty = true;
  }
  function setPlaying(on) {
    playing = on && n > 1;
    playButton.textContent = playing ? 'pause' : 'play';
  }
  playButton.addEventListener('click', function () {
    if (!playing && current >= t1) current = t0;
    setPlaying(!playing);
  });
  slider.addEventListener('input', function () { setPlaying(false); seek(times[Number(slider.value)] || t0); });
  document.getElementById('reset-view').addEventListener('click', function () { frameTheMotion(current); dirty = true; });
  // the camera's choices: the whole run, the mechanism, each body that is drawn at a point
  var followSelect = document.getElementById('follow');
  followedBodies.forEach(function (name) {
    var option = document.createElement('option');
    option.value = 'body:' + name;
    option.textContent = 'follow ' + name;
    followSelect.appendChild(option);
  });
  followSelect.value = follow;
  followSelect.addEventListener('change', function () { follow = followSelect.value; frameTheMotion(current); dirty = true; });
  document.addEventListener('keydown', function (e) {
    if (e.code === 'Space' && e.target.tagName !== 'INPUT' && e.target.tagName !== 'SELECT') {
      e.preventDefault(); playButton.click();
    }
  });
  controls.addEventListener('change', function () { dirty = true; });

  var layerBoxes = { frames: 'layer-frames', trails: 'layer-trails', forces: 'layer-forces' };
  Object.keys(layerBoxes).forEach(function (name) {
    var box = document.getElementById(layerBoxes[name]);
    box.addEventListener('change', function () { layers[name] = box.checked; dirty = true; });
  });
  var trailList = document.getElementById('trail-points');
  points.forEach(function (p, index) {
    var label = document.createElement('label'), box = document.createElement('input');
    box.type = 'checkbox';
    box.checked = trails[index].userData.wanted;
    box.addEventListener('change', function () { trails[index].userData.wanted = box.checked; dirty = true; });
    label.appendChild(box);
    label.appendChild(document.createTextNode(' ' + p.name));
    trailList.appendChild(label);
  });
  if (points.length === 0) trailList.textContent = 'no points';
  function syncLayerBoxes() {
    Object.keys(layerBoxes).forEach(function (name) { document.getElementById(layerBoxes[name]).checked = layers[name]; });
  }

  function resize() {
    var w = Math.max(view.clientWidth, 1), h = Math.max(view.clientHeight, 1);
    renderer.setSize(w, h, false);
    camera.aspect = w / h;
    camera.updateProjectionMatrix();
    if (!userMoved) frameTheMotion(current);
    plots.forEach(drawPlot);
    dirty = true;
  }
  window.addEventListener('resize', resize);

  // ---- drawing --------------------------------------------------------------------------------

  function draw() {
    if (follow) followTo(current);
    place(current);
    renderer.render(world, camera);
    plots.forEach(drawCursor);
    var k = locate(current);
    if (n > 0) slider.value = String(k.f >= 0.5 && n > 1 ? k.k + 1 : k.k);
    readout.textContent = 't = ' + current.toFixed(3) + ' s of ' + t1.toFixed(3) + ' s';
    dirty = false;
  }

  // pixels that differ from the background, read back right after rendering (for #status)
  function drawnPixels() {
    var gl = renderer.getContext(), w = gl.drawingBufferWidth, h = gl.drawingBufferHeight;
    var pixels = new Uint8Array(4 * w * h);
    gl.readPixels(0, 0, w, h, gl.RGBA, gl.UNSIGNED_BYTE, pixels);
    var r = Math.round(background.r * 255), g = Math.round(background.g * 255), b = Math.round(background.b * 255);
    var count = 0;
    for (var i = 0; i < pixels.length; i += 4) {
      if (Math.abs(pixels[i] - r) > 8 || Math.abs(pixels[i + 1] - g) > 8 || Math.abs(pixels[i + 2] - b) > 8) ++count;
    }
    return count;
  }

  // what the browser test checks of the view (with the hook only): the camera as drawn (its
  // matrices, column-major as three.js holds them), the camera's choice, the grid's and the
  // axes' geometry in inertial components, and each drawn shape's place, attitude and number of
  // vertices (its index in the scene's shapes), read back from the drawn objects
  function describeView() {
    var array = function (v) { return v.toArray(); };
    var drawnGrid = world.getObjectByName('grid');
    var axes = [1, 2, 3].map(function (k) {
      var arrow = world.getObjectByName('axis a.' + k), label = world.getObjectByName('label a.' + k);
      if (!arrow) return null;
      arrow.updateMatrixWorld(true);
      return { name: 'a.' + k, visible: arrow.visible, start: array(arrow.localToWorld(new THREE.Vector3())),
               tip: array(arrow.localToWorld(new THREE.Vector3(0, arrow.cone.position.y, 0))),
               colour: arrow.line.material.color.getHexString(),
               label: label ? { text: label.userData.text, visible: label.visible, position: array(label.position) } : null };
    });
    return {
      follow: follow, choice: followSelect.value,
      choices: Array.prototype.map.call(followSelect.options, function (o) { return o.value; }),
      canvas: [renderer.domElement.width, renderer.domElement.height],
      camera: { position: array(camera.position), target: array(controls.target), up: array(camera.up), fov: camera.fov,
                aspect: camera.aspect, near: camera.near, far: camera.far,
                projection: camera.projectionMatrix.elements.slice(), view: camera.matrixWorldInverse.elements.slice() },
      moving: moving.slice(),
      grid: drawnGrid ? { visible: drawnGrid.visible, cell: drawnGrid.userData.cell,
                          vertices: Array.prototype.slice.call(drawnGrid.geometry.attributes.position.array) } : null,
      axes: axes,
      shapes: drawnShapes.filter(Boolean).map(function (d) {
        return { index: sceneShapes.indexOf(d.shape), name: d.shape.name, kind: d.shape.kind, visible: d.mesh.visible,
                 position: array(d.group.position), quaternion: d.group.quaternion.toArray(),
                 vertices: d.mesh.geometry.attributes.position.count };
      })
    };
  }

  var last = null;
  function frame(now) {
    if (playing && last !== null) {
      current += (now - last) / 1000 * Number(speedSelect.value);
      if (current > t1) current = t0 + (current - t1) % Math.max(t1 - t0, 1e-9);
      dirty = true;
    }
    last = now;
    if (dirty) draw();
    requestAnimationFrame(frame);
  }

  // ---- start: at the hash's time, paused (the browser test), or playing from the start --------

  var hash = new URLSearchParams(location.hash.replace(/^#/, ''));
  if (hash.has('t')) {
    testHook = { t: Number(hash.get('t')) };
    setPlaying(false);
    seek(isFinite(testHook.t) ? testHook.t : t0);
    if (hash.has('layers')) {
      var asked = hash.get('layers').split(',');
      Object.keys(layers).forEach(function (name) { layers[name] = asked.indexOf(name) >= 0; });
    }
    // the camera's choice, made as a user makes it: the select's value and its change event
    if (hash.has('follow')) {
      followSelect.value = hash.get('follow');
      if (followSelect.value !== hash.get('follow')) window.eomgenErrors.push('no camera choice "' + hash.get('follow') + '"');
      followSelect.dispatchEvent(new Event('change'));
    }
  } else {
    setPlaying(playing);
  }
  syncLayerBoxes();
  resize();
  draw();
  status.drawn = drawnPixels();
  status.t = current;
  if (testHook !== null) status.view = describeView();
  status.ready = true;
  report();
  requestAnimationFrame(frame);
})();
