// PCL's RegionGrowingRGB (the colour region growing of Zhan et al., which stroke-based splatting
// uses) on the scenes that bench_segment writes; scored with our ARI. A thin peer, not part of
// the library. Usage: segment_pcl OUTDIR/scene_<name>.bin [distance]
#include <pointnpr/segment.h>

#include <pcl/point_types.h>
#include <pcl/search/kdtree.h>
#include <pcl/segmentation/region_growing_rgb.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <vector>

int main(int argc, char **argv)
{
    if (argc < 2) { std::fprintf(stderr, "usage: segment_pcl scene.bin [distance]\n"); return 2; }
    std::FILE *f = std::fopen(argv[1], "rb");
    if (!f) { std::perror(argv[1]); return 1; }
    uint64_t n = 0;
    if (std::fread(&n, sizeof n, 1, f) != 1) return 1;
    pcl::PointCloud<pcl::PointXYZRGB>::Ptr cloud(new pcl::PointCloud<pcl::PointXYZRGB>);
    cloud->resize(n);
    std::vector<uint32_t> truth(n);
    for (uint64_t i = 0; i < n; i++) {
        float p[3];
        uint8_t c[4];
        if (std::fread(p, sizeof(float), 3, f) != 3 || std::fread(c, 1, 4, f) != 4 ||
            std::fread(&truth[i], sizeof(uint32_t), 1, f) != 1) return 1;
        pcl::PointXYZRGB &q = (*cloud)[i];
        q.x = p[0]; q.y = p[1]; q.z = p[2]; q.r = c[0]; q.g = c[1]; q.b = c[2];
    }
    std::fclose(f);
    // the same neighbourhood as our rgbgrow defaults: 16 neighbours within 3 x the median spacing
    pnpr_kdtree *tree = nullptr;
    std::vector<float> xyz(3 * n);
    for (uint64_t i = 0; i < n; i++) { xyz[3 * i] = (*cloud)[i].x; xyz[3 * i + 1] = (*cloud)[i].y; xyz[3 * i + 2] = (*cloud)[i].z; }
    if (pnpr_kdtree_build(xyz.data(), n, 0, &tree) != PNPR_OK) { std::fprintf(stderr, "segment_pcl: kd-tree failed\n"); return 1; }
    float dist = argc > 2 ? (float)std::atof(argv[2]) : 3.0f * pnpr_segment_median_spacing(tree, xyz.data(), n);
    pnpr_kdtree_free(tree);

    double best = 1e30;
    std::vector<uint32_t> labels(n);
    size_t segments = 0;
    for (int rep = 0; rep < 3; rep++) {
        auto t0 = std::chrono::steady_clock::now();
        pcl::search::Search<pcl::PointXYZRGB>::Ptr search(new pcl::search::KdTree<pcl::PointXYZRGB>);
        pcl::RegionGrowingRGB<pcl::PointXYZRGB> reg;
        reg.setInputCloud(cloud);
        reg.setSearchMethod(search);
        reg.setNumberOfNeighbours(16);
        reg.setDistanceThreshold(dist);
        reg.setPointColorThreshold(25);
        reg.setRegionColorThreshold(10);
        reg.setMinClusterSize(10);
        std::vector<pcl::PointIndices> clusters;
        reg.extract(clusters);
        double t = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
        if (t < best) best = t;
        // points in no cluster (PCL drops clusters below the minimum size) form one extra segment
        for (auto &l : labels) l = (uint32_t)clusters.size();
        for (size_t c = 0; c < clusters.size(); c++)
            for (int idx : clusters[c].indices) labels[(size_t)idx] = (uint32_t)c;
        segments = clusters.size();
    }
    pnpr_segment_score sc{};
    if (pnpr_segment_score_labels(truth.data(), labels.data(), n, &sc) != PNPR_OK) { std::fprintf(stderr, "segment_pcl: scoring failed\n"); return 1; }
    std::printf("%-8s %9llu %8.4f %9zu %5u %5u %9.3f\n", "pcl-rgb", (unsigned long long)n, sc.ari, segments,
                sc.over_segmented, sc.under_segmented, best);
    return 0;
}
