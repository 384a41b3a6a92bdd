#!/usr/bin/env python3
"""A sweep of turning-overlap scenes (issue 23): a circle against a segment or a fixed triangle's
edge, or a triangle's corner against a segment, starting overlapping by round-off, receding and
pressed back, its distance's maximum within a few ulps of touching (above, below, exactly).
The scenes carry no expected times: `pge check` judges each with the exact oracle, and robust
and certified must pass (reached-until, 0 ulps, no miss or phantom).

Usage (python3, standard library only):
    python3 scripts/turning-sweep.py MODE DIR    # MODE: double, ld (double inputs tuned for long
                                                 # double), float (inputs tuned for float)
    build/cli/pge check --table --scalar SCALAR DIR
"""
import math, json, random, struct, sys, os
from decimal import Decimal as D, getcontext
getcontext().prec = 90
mode = sys.argv[1]; out = sys.argv[2]; os.makedirs(out, exist_ok=True)


def sweep_double_ld():
    random.seed(11)
    def f32(x): return struct.unpack('f', struct.pack('f', x))[0]
    def nxt(x, up):
        if mode == 'float':
            b = struct.unpack('I', struct.pack('f', x))[0]
            b += 1 if (up == (x >= 0)) else -1
            return struct.unpack('f', struct.pack('I', b))[0]
        return math.nextafter(x, math.inf if up else -math.inf)
    rnd = f32 if mode == 'float' else (lambda x: x)
    s = {'float': 2.0**-10, 'double': 2.0**-24, 'ld': 2.0**-30}[mode]
    g = 0.25
    n = 0
    def emit(kind, bodies, mx):
        nonlocal n
        name = f"{kind}-{n:03d}"; n += 1
        sc = {"format": "pge-scene/1", "name": name, "bodies": bodies, "run": {"until": 0.01, "max_events": 50},
              "expect": {"note": "maximum minus touching %.3e" % mx, "stop": "reached-until"}}
        json.dump(sc, open(f"{out}/{name}.json", "w"))
    for dirn in [(1,1),(1,2),(2,3),(3,1)]:
        ex, ey = dirn
        L = D(ex*ex+ey*ey).sqrt()
        for trial in range(6):
            r = rnd(random.randint(1, 2**12) / 2**12 + 0.25)
            Kd = D(s)**2 * L / (2*D(g))       # distance gained up to the maximum
            for kind in ['seg', 'poly', 'vertex', 'corner']:
                y = 2.0
                reach = D(r) if kind != 'corner' else D(0)
                x_star = ((reach - Kd)*L + D(y)*ex)/ey      # centre/vertex x with the maximum exactly touching
                cands = []
                x = rnd(float(x_star))
                if mode == 'ld':
                    # search double x around x_star for a maximum within ~1e-19 of touching (r fixed)
                    best = []
                    xx = x
                    for _ in range(3000):
                        xx = nxt(xx, False)
                    lo = xx
                    xx = lo
                    for _ in range(6000):
                        dist = (D(xx)*ey - D(y)*ex)/L + Kd
                        rr = float(dist) if kind != 'corner' else 0.0
                        mx = dist - D(rr) if kind != 'corner' else dist
                        if abs(mx) < D('3e-19') and rr > 0.2 or (kind == 'corner' and abs(mx) < D('3e-19')): best.append((xx, rr))
                        xx = nxt(xx, True)
                    cands = best[:4]
                else:
                    for k in range(-2, 3):
                        xx = x
                        for _ in range(abs(k)): xx = nxt(xx, k > 0)
                        cands.append((xx, r))
                for xx, r in cands:
                    mx = (D(xx)*ey - D(y)*ex)/L + Kd - (D(r) if kind != 'corner' else D(0))
                    v = [s*ey, -s*ex]; a = [-g*ey, g*ex]
                    if kind == 'seg':
                        bodies = [{"id": "wall", "segment": {"a": [0, 0], "b": [8*ex, 8*ey]}, "fixed": True},
                                  {"id": "ball", "circle": {"radius": r}, "position": [xx, y], "velocity": v, "acceleration": a, "mass": 1, "restitution": 0.0}]
                    elif kind == 'poly':
                        third = [4*ex - 4*ey, 4*ey + 4*ex]
                        bodies = [{"id": "block", "polygon": {"vertices": [[0, 0], [8*ex, 8*ey], third]}, "fixed": True},
                                  {"id": "ball", "circle": {"radius": r}, "position": [xx, y], "velocity": v, "acceleration": a, "mass": 1, "restitution": 0.0}]
                    elif kind == 'corner':
                        # a moving diamond whose lowest-right vertex (relative (h, 0) after placement) meets the segment
                        h = 0.5
                        # vertex at (xx, y): the diamond's vertex pointing along the normal (ey,-ex)/L is approximated by
                        # a triangle with that vertex at its local (0,0) offset from position
                        bodies = [{"id": "wall", "segment": {"a": [0, 0], "b": [8*ex, 8*ey]}, "fixed": True},
                                  {"id": "tri", "polygon": {"vertices": [[0, 0], [ey*1.0 - ex*0.5, -ex*1.0 - ey*0.5], [ey*1.0 + ex*0.5, -ex*1.0 + ey*0.5]]},
                                   "position": [xx, y], "velocity": v, "acceleration": a, "mass": 1, "restitution": 0.0}]
                    else:  # vertex: the segment's end at the origin, the ball along the normal of the end... radial motion
                        # ball centre at distance d along unit u=(ey,-ex)/L from the segment end (0,0); segment points away
                        continue
                    emit(kind, bodies, mx)
    print(n)


def sweep_float():
    random.seed(12)
    def f32(x): return struct.unpack('f', struct.pack('f', x))[0]
    def nxt(x):
        b = struct.unpack('I', struct.pack('f', x))[0] + 1
        return struct.unpack('f', struct.pack('I', b))[0]
    def r20(x):  # 20 significant bits
        m, e = math.frexp(x); return math.ldexp(round(m * 2**20) / 2**20, e)
    n = 0
    s = 2.0**-12
    for dirn in [(1,1),(1,2),(2,3),(3,1)]:
        ex, ey = dirn
        L = D(ex*ex+ey*ey).sqrt()
        for kind in ['seg', 'poly', 'corner']:
            found = 0
            tries = 0
            while found < 10 and tries < 200000:
                tries += 1
                r = f32(random.randint(1, 2**12) / 2**12 + 0.25) if kind != 'corner' else 0.0
                y = 2.0
                x = f32(float(((D(r))*L + D(y)*ex)/ey)) 
                for _ in range(random.randint(-3, 3) + 3): x = nxt(x)
                d0 = (D(x)*ey - D(y)*ex)/L
                ov = D(r) - d0
                ref = D(r) if r > 0 else D(1)
                if not (0 < ov < D('0.8e-9') * ref): continue
                for delta in [-2, -1, 0, 1, 2]:
                    Kd = ov + D(delta) * D('1e-10') * ref
                    if Kd <= 0: continue
                    g = r20(float(D(s)**2 * L / (2*Kd)))
                    Kd = D(s)**2 * L / (2*D(g))
                    mx = d0 + Kd - D(r)
                    v = [s*ey, -s*ex]; a = [-g*ey, g*ex]
                    if kind == 'seg':
                        bodies = [{"id": "wall", "segment": {"a": [0, 0], "b": [8*ex, 8*ey]}, "fixed": True},
                                  {"id": "ball", "circle": {"radius": r}, "position": [x, y], "velocity": v, "acceleration": a, "mass": 1, "restitution": 0.0}]
                    elif kind == 'poly':
                        third = [4*ex - 4*ey, 4*ey + 4*ex]
                        bodies = [{"id": "block", "polygon": {"vertices": [[0, 0], [8*ex, 8*ey], third]}, "fixed": True},
                                  {"id": "ball", "circle": {"radius": r}, "position": [x, y], "velocity": v, "acceleration": a, "mass": 1, "restitution": 0.0}]
                    else:
                        bodies = [{"id": "wall", "segment": {"a": [0, 0], "b": [8*ex, 8*ey]}, "fixed": True},
                                  {"id": "tri", "polygon": {"vertices": [[0, 0], [ey*1.0 - ex*0.5, -ex*1.0 - ey*0.5], [ey*1.0 + ex*0.5, -ex*1.0 + ey*0.5]]},
                                   "position": [x, y], "velocity": v, "acceleration": a, "mass": 1, "restitution": 0.0}]
                    name = f"{kind}-{n:03d}"; n += 1
                    sc = {"format": "pge-scene/1", "name": name, "bodies": bodies, "run": {"until": 0.01, "max_events": 50},
                          "expect": {"note": "maximum minus touching %.3e" % mx, "stop": "reached-until"}}
                    json.dump(sc, open(f"{out}/{name}.json", "w"))
                found += 1
    print(n)


if mode == 'float':
    sweep_float()
else:
    sweep_double_ld()
