// PCL's NormalEstimationOMP (k nearest neighbours, FLANN kd-tree) on the cloud that bench_features
// writes: the feature benchmark's second peer, for comparison only (bench/run.sh, `make bench`).
// Usage: normals_pcl CLOUD.ply K THREADS [REPEATS]
// Prints PCL_VERSION, PCL_POINTS and PCL_NORMALS_SECONDS (the best of REPEATS timed compute()
// calls; each builds its kd-tree, as our pipeline does, so both sides time the same work).
#include <pointnpr/io.h>

#include <pcl/features/normal_3d_omp.h>
#include <pcl/pcl_config.h>
#include <pcl/point_types.h>
#include <pcl/search/kdtree.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>

int main(int argc, char **argv)
{
    if (argc < 4) { std::fprintf(stderr, "usage: normals_pcl CLOUD.ply K THREADS [REPEATS]\n"); return 2; }
    const int k = std::atoi(argv[2]), threads = std::atoi(argv[3]);
    const int repeats = argc > 4 ? std::atoi(argv[4]) : 1;
    pnpr_cloud c = {};
    pnpr_error err = {};
    if (pnpr_read_file(argv[1], nullptr, &c, &err) != PNPR_OK) { std::fprintf(stderr, "%s\n", err.message); return 1; }
    pcl::PointCloud<pcl::PointXYZ>::Ptr cloud(new pcl::PointCloud<pcl::PointXYZ>);
    cloud->resize(c.count);
    for (size_t i = 0; i < c.count; i++) {
        pcl::PointXYZ &q = (*cloud)[i];
        q.x = c.xyz[3 * i]; q.y = c.xyz[3 * i + 1]; q.z = c.xyz[3 * i + 2];
    }
    pnpr_cloud_free(&c);
    double best = 1e30;
    for (int r = 0; r < repeats; r++) {
        pcl::PointCloud<pcl::Normal> normals;
        auto t0 = std::chrono::steady_clock::now();
        pcl::NormalEstimationOMP<pcl::PointXYZ, pcl::Normal> ne(threads);
        pcl::search::KdTree<pcl::PointXYZ>::Ptr tree(new pcl::search::KdTree<pcl::PointXYZ>);
        ne.setInputCloud(cloud);
        ne.setSearchMethod(tree);
        ne.setKSearch(k);
        ne.compute(normals);
        double t = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
        if (t < best) best = t;
        if (normals.size() != cloud->size()) { std::fprintf(stderr, "normals_pcl: %zu normals\n", normals.size()); return 1; }
    }
    std::printf("PCL_VERSION %s\n", PCL_VERSION_PRETTY);
    std::printf("PCL_POINTS %zu\n", cloud->size());
    std::printf("PCL_NORMALS_SECONDS %.3f\n", best);
    return 0;
}
