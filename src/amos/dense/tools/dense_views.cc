// dense_views: pictures of a `run --dense` output folder for a person to look at, without a display (Open3D's
// renderer needs one): orthographic projections of mesh.ply's vertices in the floor's frame (occupancy.yaml's
// T_mw), drawn with their colours: a top view (the ceiling cut off above --ceiling m), a side view (the map's x
// axis horizontal), the same two of removed_points.ply (magenta over grey mesh), and occupancy.pgm enlarged.
//   dense_views RUN_DIR OUT_PREFIX [--ceiling 2.0] [--pixel 0.01]
// Writes OUT_PREFIX_top.png, _side.png, _removed_top.png, _removed_side.png, _occupancy.png.
#include <fmt/format.h>

#include <Eigen/Geometry>
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <limits>
#include <opencv2/imgproc.hpp>
#include <regex>
#include <string>
#include <vector>

#include <open3d/geometry/PointCloud.h>
#include <open3d/geometry/TriangleMesh.h>
#include <open3d/io/PointCloudIO.h>
#include <open3d/io/TriangleMeshIO.h>

#include "amos/io/image_codecs.h"

namespace {

Eigen::Matrix4d mapFrame(const std::string& yaml) {
  std::ifstream in(yaml);
  std::string line;
  const std::regex number(R"([-+]?[0-9]*\.?[0-9]+([eE][-+]?[0-9]+)?)");
  while (std::getline(in, line)) {
    if (line.find("T_mw:") == std::string::npos) continue;
    std::vector<double> v;
    const std::string values = line.substr(line.find('['));
    for (auto it = std::sregex_iterator(values.begin(), values.end(), number); it != std::sregex_iterator(); ++it)
      v.push_back(std::stod(it->str()));
    if (v.size() == 16) return Eigen::Map<Eigen::Matrix4d>(v.data());  // written column by column (Eigen's order)
  }
  return Eigen::Matrix4d::Identity();
}

struct View {
  int a, b;       // map axes drawn as image x and image up
  int depth;      // axis towards the viewer (larger = nearer)
};

// Points drawn nearest-last into an image covering all of them, `pixel` metres per pixel.
cv::Mat draw(const std::vector<Eigen::Vector3d>& points, const std::vector<cv::Vec3b>& colours, const View& view,
             double pixel, const Eigen::AlignedBox3d& box) {
  const int width = int((box.max()[view.a] - box.min()[view.a]) / pixel) + 3;
  const int height = int((box.max()[view.b] - box.min()[view.b]) / pixel) + 3;
  cv::Mat image(height, width, CV_8UC3, cv::Scalar(255, 255, 255));
  cv::Mat nearest(height, width, CV_64F, cv::Scalar(-std::numeric_limits<double>::infinity()));
  for (std::size_t i = 0; i < points.size(); ++i) {
    const Eigen::Vector3d& p = points[i];
    if (!box.contains(p)) continue;
    const int x = int((p[view.a] - box.min()[view.a]) / pixel) + 1;
    const int y = height - 2 - int((p[view.b] - box.min()[view.b]) / pixel);
    if (p[view.depth] <= nearest.at<double>(y, x)) continue;
    nearest.at<double>(y, x) = p[view.depth];
    image.at<cv::Vec3b>(y, x) = colours[i];
  }
  return image;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 3) {
    std::cerr << "usage: dense_views RUN_DIR OUT_PREFIX [--ceiling 2.0] [--pixel 0.01]\n";
    return 2;
  }
  const std::string dir = argv[1], prefix = argv[2];
  double ceiling = 2.0, pixel = 0.01;
  for (int i = 3; i + 1 < argc; i += 2) {
    if (std::string(argv[i]) == "--ceiling") ceiling = std::atof(argv[i + 1]);
    if (std::string(argv[i]) == "--pixel") pixel = std::atof(argv[i + 1]);
  }
  open3d::geometry::TriangleMesh mesh;
  open3d::geometry::PointCloud removed;
  if (!open3d::io::ReadTriangleMesh(dir + "/mesh.ply", mesh)) {
    std::cerr << "cannot read " << dir << "/mesh.ply\n";
    return 1;
  }
  open3d::io::ReadPointCloud(dir + "/removed_points.ply", removed);
  const Eigen::Matrix4d T_mw = mapFrame(dir + "/occupancy.yaml");
  auto toMap = [&](const Eigen::Vector3d& p) { return Eigen::Vector3d((T_mw * p.homogeneous()).head<3>()); };
  std::vector<Eigen::Vector3d> points, removed_points;
  std::vector<cv::Vec3b> colours, grey;
  Eigen::AlignedBox3d box;
  for (std::size_t i = 0; i < mesh.vertices_.size(); ++i) {
    const Eigen::Vector3d m = toMap(mesh.vertices_[i]);
    if (m.z() > ceiling) continue;
    points.push_back(m);
    box.extend(m);
    const Eigen::Vector3d c = mesh.HasVertexColors() ? mesh.vertex_colors_[i] : Eigen::Vector3d(0.6, 0.6, 0.6);
    colours.emplace_back(cv::saturate_cast<uchar>(255 * c.z()), cv::saturate_cast<uchar>(255 * c.y()),
                         cv::saturate_cast<uchar>(255 * c.x()));
    grey.emplace_back(200, 200, 200);
  }
  for (const auto& p : removed.points_) {
    const Eigen::Vector3d m = toMap(p);
    if (m.z() > ceiling || !box.contains(m)) continue;
    removed_points.push_back(m);
  }
  const View top{0, 1, 2}, side{0, 2, 1};
  amos::io::writeImage(prefix + "_top.png", draw(points, colours, top, pixel, box));
  amos::io::writeImage(prefix + "_side.png", draw(points, colours, side, pixel, box));
  // The removed points in magenta over the grey mesh, drawn last: they are what the reader looks for.
  cv::Mat removed_top = draw(points, grey, top, pixel, box), removed_side = draw(points, grey, side, pixel, box);
  for (const auto& m : removed_points) {
    const int x = int((m.x() - box.min().x()) / pixel) + 1;
    cv::circle(removed_top, {x, removed_top.rows - 2 - int((m.y() - box.min().y()) / pixel)}, 1, {255, 0, 255}, -1);
    cv::circle(removed_side, {x, removed_side.rows - 2 - int((m.z() - box.min().z()) / pixel)}, 1, {255, 0, 255}, -1);
  }
  amos::io::writeImage(prefix + "_removed_top.png", removed_top);
  amos::io::writeImage(prefix + "_removed_side.png", removed_side);
  const cv::Mat grid = amos::io::readImage(dir + "/occupancy.pgm", amos::io::kReadGrayscale);
  if (!grid.empty()) {
    cv::Mat big;
    cv::resize(grid, big, {}, 4, 4, cv::INTER_NEAREST);
    amos::io::writeImage(prefix + "_occupancy.png", big);
  }
  std::cout << fmt::format("{} mesh vertices below {} m, {} removed points -> {}_*.png\n", points.size(), ceiling,
                           removed_points.size(), prefix);
  return 0;
}
