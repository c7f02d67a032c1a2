"""Open3D's normals of the same sphere at growing coordinate offsets (a peer for comparison only).

usage: /usr/bin/python3 bench/open3d_offset.py [POINTS]
The sphere (radius 1, coordinates on a 2^-20 grid so that every moved copy is exactly the same
cloud) is moved by 1e3 .. 1e8 along every axis; normals (KNN 16) are compared with those at the
origin. Prints one markdown row per offset. Our pipeline's rows come from tests/test_stability.c.
"""
import sys

import numpy as np
import open3d as o3d


def normals(points):
    pcd = o3d.geometry.PointCloud(o3d.utility.Vector3dVector(points))
    pcd.estimate_normals(o3d.geometry.KDTreeSearchParamKNN(knn=16))
    return np.asarray(pcd.normals)


def main():
    n = int(sys.argv[1]) if len(sys.argv) > 1 else 20000
    rng = np.random.default_rng(5)
    v = rng.normal(size=(n, 3))
    v /= np.linalg.norm(v, axis=1)[:, None]
    v = np.round(v * 1048576.0) / 1048576.0
    ref = normals(v)
    print("| offset | Open3D: largest normal difference (deg) | mean (deg) |")
    print("|---|---|---|")
    for off in (1e3, 1e4, 1e5, 1e6, 5e6, 1e7, 1e8):
        nn = normals(v + off)
        cross = np.linalg.norm(np.cross(ref, nn), axis=1)
        dot = np.abs(np.sum(ref * nn, axis=1))
        ang = np.degrees(np.arctan2(cross, dot))
        print(f"| {off:g} | {ang.max():.3g} | {ang.mean():.3g} |")


if __name__ == "__main__":
    main()
