"""Shared pieces of the stroke-log generators (scripts/make-deform-log, make-sculpt-log,
make-sculpt-ops-log): cameras and their projection (modeling/camera.h), a writer of events in
stroke-log format v1 (docs/stroke-log.md), a Wavefront OBJ reader, and a small ray caster that
mirrors what the app computes from a stroke on the model (the extrusion's reference plane,
modeling/sculpt_extrude.cpp), so a generator can draw the silhouette on that plane."""
import json
import math

W, H = 1280, 800


def cam(eye, target, up, width=W, height=H):
    return {"eye": list(eye), "target": list(target), "up": list(up), "fov_y_deg": 40.0, "orthographic": False,
            "ortho_height": 4.0, "near": 0.01, "far": 100.0, "width": width, "height": height}


def add(a, b):
    return [a[i] + b[i] for i in range(3)]


def sub(a, b):
    return [a[i] - b[i] for i in range(3)]


def scale(s, a):
    return [s * x for x in a]


def dot(a, b):
    return sum(a[i] * b[i] for i in range(3))


def cross(a, b):
    return [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]


def norm(a):
    return math.sqrt(dot(a, a))


def unit(a):
    n = norm(a)
    return [x / n for x in a]


def rotate(v, axis, angle):
    """v turned by `angle` radians about the unit `axis` (right-handed, Rodrigues)."""
    c, s = math.cos(angle), math.sin(angle)
    k = axis
    return add(add(scale(c, v), scale(s, cross(k, v))), scale(dot(k, v) * (1 - c), k))


def _basis(c):
    f = unit(sub(c["target"], c["eye"]))
    s = unit(cross(f, c["up"]))
    return f, s, cross(s, f)


def project(c, p):
    """Window pixel of p under camera c (modeling/camera.h: perspective, y down)."""
    f, s, u = _basis(c)
    d = sub(p, c["eye"])
    depth = dot(d, f)
    tan = math.tan(math.radians(c["fov_y_deg"]) / 2)
    w, h = c["width"], c["height"]
    nx = dot(d, s) / (depth * tan * w / h)
    ny = dot(d, u) / (depth * tan)
    return ((nx + 1) * 0.5 * w, (1 - ny) * 0.5 * h)


def ray(c, px, py):
    """Origin and unit direction of the ray through a window pixel (Camera::ray)."""
    f, s, u = _basis(c)
    w, h = c["width"], c["height"]
    nx, ny = 2.0 * px / w - 1.0, 1.0 - 2.0 * py / h
    tan = math.tan(math.radians(c["fov_y_deg"]) / 2)
    return c["eye"], unit(add(f, add(scale(nx * tan * w / h, s), scale(ny * tan, u))))


class LogWriter:
    """Events in stroke-log format v1, one JSON object a line, at a running time t (ms)."""

    def __init__(self, lines=None, t=0.0):
        self.out = list(lines or [])
        self.t = t

    def ev(self, d):
        self.out.append(json.dumps(d, separators=(",", ":")))

    def step(self, ms):
        self.t += ms

    def stroke(self, points, digits=None):
        """A pen stroke: down, moves, up, 8 ms apart, then a 400 ms pause."""
        for i, (x, y) in enumerate(points):
            phase = "down" if i == 0 else ("up" if i == len(points) - 1 else "move")
            if digits is not None:
                x, y = round(x, digits), round(y, digits)
            self.ev({"t": self.t, "type": "pen", "x": x, "y": y, "pressure": 0.6, "tilt_x": 0.0, "tilt_y": 0.0,
                     "tool": "pen", "phase": phase})
            self.step(8)
        self.step(400)

    def write(self, path):
        open(path, "w").write("\n".join(self.out) + "\n")


def read_obj(path):
    vs, fs = [], []
    for line in open(path):
        if line.startswith("v "):
            vs.append([float(x) for x in line.split()[1:4]])
        elif line.startswith("f "):
            fs.append([int(x.split("/")[0]) - 1 for x in line.split()[1:4]])
    return vs, fs


def signed_volume(vs, fs):
    return sum(dot(vs[a], cross(vs[b], vs[c])) for a, b, c in fs) / 6.0


class RayCaster:
    """First hits of window rays on a mesh under one camera: the triangles are binned by their
    projected boxes (32 px cells), each ray tested against its cell's triangles exactly."""

    def __init__(self, vs, fs, camera, cell=32.0):
        self.vs, self.fs, self.camera, self.cell = vs, fs, camera, cell
        self.bins = {}
        px = [project(camera, v) for v in vs]
        for i, f in enumerate(fs):
            xs, ys = [px[k][0] for k in f], [px[k][1] for k in f]
            for gx in range(int(min(xs) // cell), int(max(xs) // cell) + 1):
                for gy in range(int(min(ys) // cell), int(max(ys) // cell) + 1):
                    self.bins.setdefault((gx, gy), []).append(i)

    def normal(self, f):
        a, b, c = (self.vs[k] for k in self.fs[f])
        return unit(cross(sub(b, a), sub(c, a)))

    def hit(self, px, py):
        """(point, face) of the nearest hit, or None."""
        o, d = ray(self.camera, px, py)
        best = None
        for f in self.bins.get((int(px // self.cell), int(py // self.cell)), []):
            a, b, c = (self.vs[k] for k in self.fs[f])
            e1, e2 = sub(b, a), sub(c, a)
            p = cross(d, e2)
            det = dot(e1, p)
            if abs(det) < 1e-15:
                continue
            s = sub(o, a)
            u = dot(s, p) / det
            q = cross(s, e1)
            v = dot(d, q) / det
            if u < 0 or v < 0 or u + v > 1:
                continue
            t = dot(e2, q) / det
            if t > 0 and (best is None or t < best[0]):
                best = (t, f)
        return None if best is None else (add(o, scale(best[0], d)), best[1])


def _inside(p, poly):
    inside = False
    for i in range(len(poly)):
        (x0, y0), (x1, y1) = poly[i], poly[(i + 1) % len(poly)]
        if (y0 > p[1]) != (y1 > p[1]) and p[0] < x0 + (p[1] - y0) * (x1 - x0) / (y1 - y0):
            inside = not inside
    return inside


def extrusion_plane(caster, stroke, spin=0.0, tilt=0.0, section_points=48):
    """The extrusion's reference plane for a closed base stroke (what extrusion_reference_plane
    in modeling/sculpt_extrude.cpp computes): centre, normal_axis, across, plane normal, and the
    base curve's extent along `across` (lo, hi, relative to the centre)."""
    loop = []
    for i in range(len(stroke)):
        (ax, ay), (bx, by) = stroke[i], stroke[(i + 1) % len(stroke)]
        n = max(1, math.ceil(math.hypot(bx - ax, by - ay) / 2.0))
        for k in range(n):
            h = caster.hit(ax + (bx - ax) * k / n, ay + (by - ay) * k / n)
            if h is None:
                raise ValueError(f"the base stroke misses the model near ({ax:.0f}, {ay:.0f})")
            loop.append(h[0])
    cum = [0.0]
    for i in range(len(loop)):
        cum.append(cum[-1] + norm(sub(loop[(i + 1) % len(loop)], loop[i])))
    base, seg = [], 0
    for k in range(section_points):
        s = cum[-1] * k / section_points
        while seg + 1 < len(loop) and cum[seg + 1] < s:
            seg += 1
        ln = cum[seg + 1] - cum[seg]
        t = min(1.0, max(0.0, (s - cum[seg]) / ln)) if ln > 0 else 0.0
        base.append(add(loop[seg], scale(t, sub(loop[(seg + 1) % len(loop)], loop[seg]))))
    centre = scale(1.0 / len(base), [sum(q[i] for q in base) for i in range(3)])
    lo = [min(p[0] for p in stroke), min(p[1] for p in stroke)]
    hi = [max(p[0] for p in stroke), max(p[1] for p in stroke)]
    total = [0.0, 0.0, 0.0]
    grid = 16
    probes = [(lo[0] + (i + 0.5) / grid * (hi[0] - lo[0]), lo[1] + (j + 0.5) / grid * (hi[1] - lo[1]))
              for i in range(grid) for j in range(grid)]
    for p in [p for p in probes if _inside(p, stroke)] + list(stroke):
        h = caster.hit(*p)
        if h is not None:
            total = add(total, caster.normal(h[1]))
    n = unit(total)
    first = base[0]
    far = max(base, key=lambda q: norm(sub(q, first)))
    d = sub(far, first)
    across = unit(rotate(unit(sub(d, scale(dot(d, n), n))), n, spin))
    axis = unit(rotate(n, across, tilt))
    us = [dot(sub(q, centre), across) for q in base]
    return {"centre": centre, "normal_axis": axis, "across": across, "normal": unit(cross(across, axis)),
            "region_normal": n, "lo": min(us), "hi": max(us), "base": base}


def on_plane(plane, u, v):
    return add(plane["centre"], add(scale(u, plane["across"]), scale(v, plane["normal_axis"])))
