#!/usr/bin/env python3
"""Draws the nine .poly outlines under core/shapes/ (run once; the output is committed).

The paper's meshes (Aupy, Park, Raghavan, Table 4) are not public, so each name gets an outline that
resembles it, with holes where the object has them. Coordinates span about 0..1000 so Triangle's
-a area switch stays in plain decimal notation. Boundaries are sampled coarsely (a few hundred
points per shape) so that meshes from 10^3 vertices upward are reachable. Pure Python, no numpy.
Format: https://www.cs.cmu.edu/~quake/triangle.poly.html
"""
import math
import os
import sys


def circle(cx, cy, r, n, start=0.0, stop=2 * math.pi, endpoint=False):
    k = n if not endpoint else n - 1
    return [(cx + r * math.cos(start + (stop - start) * i / k),
             cy + r * math.sin(start + (stop - start) * i / k)) for i in range(n)]


def polar(cx, cy, radius, n):
    return [(cx + radius(t) * math.cos(t), cy + radius(t) * math.sin(t))
            for t in (2 * math.pi * i / n for i in range(n))]


def bump(t, centre, width, height):
    d = math.atan2(math.sin(t - centre), math.cos(t - centre))
    return height * math.exp(-(d / width) ** 2)


def hull(points):
    pts = sorted(set(points))
    def cross(o, a, b):
        return (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0])
    lower, upper = [], []
    for p in pts:
        while len(lower) >= 2 and cross(lower[-2], lower[-1], p) <= 0:
            lower.pop()
        lower.append(p)
    for p in reversed(pts):
        while len(upper) >= 2 and cross(upper[-2], upper[-1], p) <= 0:
            upper.pop()
        upper.append(p)
    return lower[:-1] + upper[:-1]


def write_poly(path, loops, holes, comment):
    verts, segs = [], []
    for loop in loops:
        base = len(verts)
        verts.extend(loop)
        n = len(loop)
        segs.extend((base + i, base + (i + 1) % n) for i in range(n))
    with open(path, "w") as f:
        f.write(f"# {comment}\n# drawn by scripts/make_shapes.py\n")
        f.write(f"{len(verts)} 2 0 0\n")
        for i, (x, y) in enumerate(verts, 1):
            f.write(f"{i} {x:.6f} {y:.6f}\n")
        f.write(f"{len(segs)} 0\n")
        for i, (a, b) in enumerate(segs, 1):
            f.write(f"{i} {a + 1} {b + 1}\n")
        f.write(f"{len(holes)}\n")
        for i, (x, y) in enumerate(holes, 1):
            f.write(f"{i} {x:.6f} {y:.6f}\n")


def carabiner():
    outer = hull(circle(300, 350, 300, 90) + circle(780, 350, 210, 70))
    inner = hull(circle(300, 350, 200, 70) + circle(780, 350, 120, 50))
    return [outer, inner], [(300, 350)], "carabiner: pear-shaped ring"


def crake():
    def r(t):
        body = 260 * 170 / math.hypot(170 * math.cos(t), 260 * math.sin(t))
        return (body + bump(t, math.radians(35), 0.22, 150)     # neck and head
                + bump(t, math.radians(22), 0.06, 230)          # beak
                + bump(t, math.radians(185), 0.18, 140)         # tail
                + bump(t, math.radians(-95), 0.05, 200)         # legs
                + bump(t, math.radians(-75), 0.05, 210))
    outline = polar(450, 420, r, 260)
    head = (450 + 290 * math.cos(math.radians(36)), 420 + 290 * math.sin(math.radians(36)))
    eye = circle(head[0], head[1], 18, 12)
    return [outline, eye], [head], "crake: bird with beak, tail and legs; eye hole"


def dialog():
    def r(t):
        a, b, p = 480, 300, 5.0
        base = (abs(math.cos(t) / a) ** p + abs(math.sin(t) / b) ** p) ** (-1 / p)
        return base + bump(t, math.radians(-125), 0.07, 260)
    outline = polar(500, 450, r, 240)
    dots = [circle(500 + dx, 450, 35, 16) for dx in (-150, 0, 150)]
    return [outline] + dots, [(500 + dx, 450) for dx in (-150, 0, 150)], \
        "dialog: speech bubble with a tail; three dots"


def lake():
    waves = [(2, 0.10, 0.3), (3, 0.08, 1.1), (5, 0.05, 2.0), (7, 0.03, 0.7), (11, 0.02, 2.9)]
    def r(t):
        return 430 * (1 + sum(a * math.sin(k * t + p) for k, a, p in waves))
    outline = polar(500, 500, r, 300)
    islands = [(420, 560, 60), (620, 420, 45), (480, 330, 30)]
    loops = [outline] + [polar(x, y, lambda t, s=s: s * (1 + 0.25 * math.sin(3 * t + s)), 24)
                         for x, y, s in islands]
    return loops, [(x, y) for x, y, _ in islands], "lake: irregular shore with three islands"


def riverflow():
    n = 120
    def centre(x):
        return 350 + 170 * math.sin(2 * math.pi * x / 520)
    def width(x):
        return 140 + 80 * math.sin(2 * math.pi * x / 520) ** 2
    xs = [1000 * i / (n - 1) for i in range(n)]
    upper = [(x, centre(x) + width(x) / 2) for x in xs]
    lower = [(x, centre(x) - width(x) / 2) for x in reversed(xs)]
    islands = []
    for x in (390, 650):
        islands.append((x, centre(x), 40.0))
    loops = [upper + lower] + [polar(x, y, lambda t, s=s: s * 2.2 * s / math.hypot(2.2 * s * math.sin(t), s * math.cos(t)), 20)
                               for x, y, s in islands]
    return loops, [(x, y) for x, y, _ in islands], "riverflow: meandering channel with two islands"


def ocean():
    n = 100
    coast = [(1000 - 1000 * i / (n - 1),
              620 + 45 * math.sin(i / 6.0) + 25 * math.sin(i / 2.3 + 1) + 10 * math.sin(i * 1.7))
             for i in range(n)]
    outline = [(0, 0), (1000, 0)] + coast
    islands = [(180, 200, 50), (420, 330, 70), (700, 180, 40), (820, 420, 55), (300, 470, 30)]
    loops = [outline] + [polar(x, y, lambda t, s=s: s * (1 + 0.3 * math.sin(2 * t + s) + 0.1 * math.sin(5 * t)), 26)
                         for x, y, s in islands]
    return loops, [(x, y) for x, y, _ in islands], "ocean: below a wavy coastline, five islands"


def stress():
    n = 80
    def half_width(x):  # wide grips, narrow gauge, smooth fillets (tanh)
        grip, gauge = 170, 95
        s = 0.5 * (math.tanh((x - 230) / 35) - math.tanh((x - 770) / 35))
        return grip - (grip - gauge) * s
    xs = [1000 * i / (n - 1) for i in range(n)]
    outline = [(x, 300 + half_width(x)) for x in xs] + [(x, 300 - half_width(x)) for x in reversed(xs)]
    hole = circle(500, 300, 40, 36)
    return [outline, hole], [(500, 300)], "stress: dog-bone tensile specimen with a central hole"


def valve():
    d = 0.07  # half-angle of the key notch at the top
    outer = circle(500, 500, 480, 150, math.pi / 2 + d, math.pi / 2 - d + 2 * math.pi, endpoint=True)
    outer += [(500 + 480 * math.cos(math.pi / 2 - d), 500 + 480 * math.sin(math.pi / 2 - d) - 60),
              (500 + 480 * math.cos(math.pi / 2 + d), 500 + 480 * math.sin(math.pi / 2 + d) - 60)]
    centres = [(500 + 330 * math.cos(k * math.pi / 3 + math.pi / 6),
                500 + 330 * math.sin(k * math.pi / 3 + math.pi / 6)) for k in range(6)]
    bore = circle(500, 500, 150, 60)
    bolts = [circle(x, y, 40, 18) for x, y in centres]
    return [outer, bore] + bolts, [(500, 500)] + centres, \
        "valve: flange with bore, six bolt holes and a key notch"


def wrench():
    lc, lr = (150, 300), 150
    rc, rr = (880, 300), 120
    hw, slot, depth = 45, 55, 170
    a1 = math.asin(hw / lr)
    a2 = math.pi - math.asin(slot / lr)
    a3 = math.pi + math.asin(slot / lr)
    b1 = math.pi + math.asin(hw / rr)
    b2 = math.pi - math.asin(hw / rr) + 2 * math.pi
    pts = circle(lc[0], lc[1], lr, 40, a1, a2, endpoint=True)
    pts += [(depth, lc[1] + slot), (depth, lc[1] - slot)]
    pts += circle(lc[0], lc[1], lr, 40, a3, 2 * math.pi - a1, endpoint=True)
    pts += [(x, lc[1] - hw) for x in range(360, 740, 40)]
    pts += circle(rc[0], rc[1], rr, 60, b1, b2, endpoint=True)
    pts += [(x, lc[1] + hw) for x in range(740, 320, -40)]
    hexagon = circle(rc[0], rc[1], 60, 6)
    return [pts, hexagon], [rc], "wrench: open-end head, handle, ring end with a hexagonal hole"


SHAPES = [carabiner, crake, dialog, lake, riverflow, ocean, stress, valve, wrench]

if __name__ == "__main__":
    out = sys.argv[1] if len(sys.argv) > 1 else os.path.join(os.path.dirname(__file__), "..", "core", "shapes")
    os.makedirs(out, exist_ok=True)
    for make in SHAPES:
        loops, holes, comment = make()
        write_poly(os.path.join(out, make.__name__ + ".poly"), loops, holes, comment)
        print(make.__name__, sum(len(l) for l in loops), "boundary vertices")
