#!/usr/bin/env python3
"""A sweep of bodies resting and sliding on tilted floors of two collinear tiles (issue 22):
a ball, a box or a triangle placed touching a ramp (the line 3x + 4y = 0, tiles from (-8, 6) to
the joint at (0, 0) and on to (8, -6), as segments or as fixed boxes) at decimal coordinates,
under gravity (0, -9.81), restitution 1 or 0.5, at rest, sliding down or sliding up. 36 scenes.
They carry no expected values: `pge check` judges each with the exact oracle, and robust and
certified must pass (no miss or phantom, 0 ulps). In double and float all 36 pass since the
refinement decides exactly the other vertex/edge pairs of an outline pair that may touch first
(engine/src/world_impl.hpp, earlier_outline_contact; 16 failed before in double, 8 in float).
In long double too, since the oracle takes the lower tile as the flush continuation of a resting
ball's face however its rounded acceleration leans (oracle/src/search.cpp, flush_with_support;
the 12 balls had one miss each before).

Usage (python3, standard library only):
    python3 scripts/tilted-tiles-sweep.py DIR
    build/cli/pge check --table DIR
"""
import json
import os
import sys

if len(sys.argv) != 2 or sys.argv[1] in ("-h", "--help"):
    print(__doc__)
    sys.exit(0 if len(sys.argv) == 2 else 2)
out = sys.argv[1]
os.makedirs(out, exist_ok=True)
segments = [{"id": "t1", "segment": {"a": [-8, 6], "b": [0, 0]}, "fixed": True},
            {"id": "t2", "segment": {"a": [0, 0], "b": [8, -6]}, "fixed": True}]
boxes = [{"id": "t1", "polygon": {"vertices": [[-8, 6], [-8.6, 5.2], [-0.6, -0.8], [0, 0]]}, "fixed": True},
         {"id": "t2", "polygon": {"vertices": [[0, 0], [-0.6, -0.8], [7.4, -6.8], [8, -6]]}, "fixed": True}]
# Each touches the ramp at (-4, 3), on the upper tile: the ball's centre is 0.5 along the unit
# normal (0.6, 0.8) from it; the polygons' first edge lies along the ramp from there.
movers = {
    "ball": {"id": "m", "circle": {"radius": 0.5}, "position": [-3.7, 3.4], "mass": 1},
    "box": {"id": "m", "polygon": {"vertices": [[0, 0], [0.8, -0.6], [1.4, 0.2], [0.6, 0.8]]}, "position": [-4, 3],
            "mass": 1},
    "tri": {"id": "m", "polygon": {"vertices": [[0, 0], [0.8, -0.6], [0.7, 0.5]]}, "position": [-4, 3], "mass": 1},
}
count = 0
for floor, tiles in (("seg", segments), ("boxes", boxes)):
    for name, mover in movers.items():
        for e in (1.0, 0.5):
            for v in ([0, 0], [0.8, -0.6], [-0.4, 0.3]):
                body = dict(mover, velocity=v)
                label = "%s-%s-%s-%s" % (floor, name, e, v[0])
                scene = {"format": "pge-scene/1", "name": label,
                         "world": {"gravity": [0, -9.81], "restitution": e}, "bodies": tiles + [body],
                         "run": {"until": 1.8, "max_events": 5000}}
                with open(os.path.join(out, label + ".json"), "w") as f:
                    json.dump(scene, f)
                count += 1
print("wrote %d scenes to %s" % (count, out))
