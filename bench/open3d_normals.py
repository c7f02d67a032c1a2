"""Open3D's normal estimation on the same cloud, timed the same way (a peer for comparison only).

usage: /usr/bin/python3 bench/open3d_normals.py CLOUD.ply K [REPEATS]
Prints the best wall time of estimate_normals(KDTreeSearchParamKNN(K)) over REPEATS runs and,
for the accuracy comparison, nothing else (see bench/run.sh).
"""
import sys
import time

import numpy as np
import open3d as o3d


def main():
    path, k = sys.argv[1], int(sys.argv[2])
    repeats = int(sys.argv[3]) if len(sys.argv) > 3 else 3
    pcd = o3d.io.read_point_cloud(path)
    n = len(pcd.points)
    best = float("inf")
    for _ in range(repeats):
        pcd.normals = o3d.utility.Vector3dVector(np.zeros((0, 3)))
        t0 = time.perf_counter()
        pcd.estimate_normals(o3d.geometry.KDTreeSearchParamKNN(knn=k))
        best = min(best, time.perf_counter() - t0)
    print(f"OPEN3D_VERSION {o3d.__version__}")
    print(f"OPEN3D_POINTS {n}")
    print(f"OPEN3D_NORMALS_SECONDS {best:.3f}")


if __name__ == "__main__":
    main()
