#!/usr/bin/env python3
"""A generated aerial-like farm for the density and upload measurements (docs/rendering.md,
docs/benchmarks.md): 300 x 300 m of striped fields on a gently waving ground, 60 round trees and
3 pitched roofs, georeferenced (~5e5, 4.2e6), coloured, written as a binary little-endian PLY.

    python3 bench/farm_scene.py OUT.ply [STEP]     (STEP 0.45: 444k points; 0.3: 1M)

Deterministic (seeded); plain Python 3, no packages."""
import math, random, struct, sys
random.seed(7)
if len(sys.argv) < 2: sys.exit(__doc__)
out = sys.argv[1]; step = float(sys.argv[2]) if len(sys.argv) > 2 else 0.45
S = 300.0
fields = [((-150,-150,0,-20),(150,170,60)),((0,-150,150,-40),(200,180,90)),((-150,-20,-30,150),(90,140,50)),((-30,-40,150,150),(120,160,70))]
bld = [(-60,40,30,14,6),(20,70,18,10,5),(60,-80,40,20,8)]
trees = [(random.uniform(-140,140), random.uniform(-140,140), random.uniform(3,7)) for _ in range(60)]
pts = []
def field_col(x,y):
    for (x0,y0,x1,y1),c in fields:
        if x0<=x<x1 and y0<=y<y1:
            stripe = 15 if int((x+y)/4)%2 else -15
            return tuple(max(0,min(255,v+stripe+random.randint(-10,10))) for v in c)
    return (140,130,110)
n = int(S/step)
for i in range(n):
    for j in range(n):
        x = -S/2 + (i+random.random())*step; y = -S/2 + (j+random.random())*step
        z = 2*math.sin(x/60)*math.cos(y/45) + random.gauss(0,0.03)
        col = field_col(x,y)
        for bx,by,sx,sy,h in bld:
            if abs(x-bx)<sx/2 and abs(y-by)<sy/2:
                z += h - 1.5*abs(y-by)/(sy/2); col=(170,60,50)
                break
        else:
            for tx,ty,r in trees:
                d = math.hypot(x-tx,y-ty)
                if d < r:
                    z += math.sqrt(r*r-d*d)*1.2 + random.gauss(0,0.3); col=(40,80+random.randint(0,30),30); break
        pts.append((x+500000.0,y+4200000.0,z+120.0)+col)
with open(out,'wb') as f:
    f.write(("ply\nformat binary_little_endian 1.0\nelement vertex %d\nproperty double x\nproperty double y\nproperty double z\nproperty uchar red\nproperty uchar green\nproperty uchar blue\nend_header\n"%len(pts)).encode())
    for p in pts: f.write(struct.pack('<dddBBB',*p))
print(len(pts))
