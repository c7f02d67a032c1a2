#!/usr/bin/env python3
"""A generated road for the level-of-detail views (docs/rendering.md, docs/tiles.md): 2 km x 40 m,
asphalt 8 m wide with a dashed white centre line, grass either side with tufts of colour, a grey
pole every 50 m (6 m high), on a ground 0.3 m below the road at its edges; jittered grid, coloured,
written as a binary little-endian PLY (float x y z, uchar red green blue).

    python3 bench/road_scene.py OUT.ply [STEP]     (STEP 0.14: about 4.2M points)

Seen from just above its start looking along it, everything is in view and the near ground is
hundreds of times larger on screen than the far end: the case where one uniform thinning of the
whole cloud thins the foreground. Deterministic (seeded); plain Python 3, no packages."""
import math, random, struct, sys

random.seed(11)
if len(sys.argv) < 2: sys.exit(__doc__)
out = sys.argv[1]; step = float(sys.argv[2]) if len(sys.argv) > 2 else 0.14
L, W = 2000.0, 40.0
rec = struct.Struct('<fffBBB')
buf = bytearray()
count = 0
def put(x, y, z, c):
    global count
    buf.extend(rec.pack(x, y, z, *c))
    count += 1
nx, ny = int(L / step), int(W / step)
for i in range(nx):
    for j in range(ny):
        x = (i + random.random()) * step; y = -W / 2 + (j + random.random()) * step
        a = abs(y)
        if a < 4:
            z = 0.0
            g = 70 + random.randint(-8, 8)
            c = (g, g, g + 4)
            if a < 0.1 and (x % 6.0) < 3.0: c = (235, 235, 225)
        else:
            z = -0.3 * min(1.0, (a - 4) / 2) + 0.05 * math.sin(x / 7) * math.cos(y / 3)
            t = random.randint(-20, 20)
            c = (max(0, 60 + t), max(0, min(255, 130 + t)), max(0, 50 + t // 2))
        put(x, y, z + random.gauss(0, 0.01), c)
for k in range(int(L / 50)):
    px, py = 25.0 + 50.0 * k, 5.0
    for h in range(int(6.0 / step)):
        for s in range(12):
            ang = 2 * math.pi * s / 12
            put(px + 0.15 * math.cos(ang), py + 0.15 * math.sin(ang), -0.3 + h * step, (150, 150, 155))
with open(out, 'wb') as f:
    f.write(('ply\nformat binary_little_endian 1.0\nelement vertex %d\nproperty float x\nproperty float y\n'
             'property float z\nproperty uchar red\nproperty uchar green\nproperty uchar blue\nend_header\n' % count).encode())
    f.write(buf)
print('%s: %d points' % (out, count))
