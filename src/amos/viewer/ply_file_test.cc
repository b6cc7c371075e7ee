#include "amos/viewer/ply_file.h"

#include <gtest/gtest.h>

#include <tuple>

#include "amos/core/error.h"
#include "amos/testing/fuzz_corpus.h"
#include "amos/testing/scratch_dir.h"
#include "amos/viewer/test_run_folder.h"
#include "fuzz/ply_input.h"

namespace amos::viewer {
namespace {

namespace fs = std::filesystem;

TEST(ReadPly, ReadsABinaryMeshWithColoursAndFaces) {
  const fs::path dir = amos::testing::scratchDirForThisTest("viewer_ply_");
  const ColouredGeometry written = test::floorAndWall(-1, 1, 0, 2, 0.5f);
  test::writeBinaryPly(dir / "mesh.ply", written, true);
  const ColouredGeometry read = readPly(dir / "mesh.ply");
  EXPECT_EQ(read.xyz, written.xyz);
  EXPECT_EQ(read.rgb, written.rgb);
  EXPECT_EQ(read.triangles, written.triangles);
  EXPECT_EQ(read.vertexCount(), 8u);
  EXPECT_EQ(read.triangleCount(), 4u);
}

TEST(ReadPly, ReadsABinaryCloudWithoutFaces) {
  const fs::path dir = amos::testing::scratchDirForThisTest("viewer_ply_");
  const ColouredGeometry written = test::gridCloud(0, 1, 0, 1, 0, 10, 1, 2, 3);
  test::writeBinaryPly(dir / "cloud.ply", written, false);
  const ColouredGeometry read = readPly(dir / "cloud.ply");
  EXPECT_EQ(read.xyz, written.xyz);
  EXPECT_EQ(read.rgb, written.rgb);
  EXPECT_TRUE(read.triangles.empty());
}

TEST(ReadPly, ReadsAsciiSkipsOtherPropertiesAndSplitsPolygons) {
  const fs::path dir = amos::testing::scratchDirForThisTest("viewer_ply_");
  // Normals and an alpha between the wanted properties, double coordinates, a quad and a per-face property.
  test::writeText(dir / "a.ply",
                  "ply\nformat ascii 1.0\ncomment x\nelement vertex 4\nproperty double x\nproperty float nx\n"
                  "property double y\nproperty double z\nproperty uchar red\nproperty uchar green\nproperty uchar blue\n"
                  "property uchar alpha\nelement face 1\nproperty uchar flags\nproperty list uchar uint vertex_index\n"
                  "end_header\n0 9 0 0 10 20 30 255\n1 9 0 0 10 20 30 255\n1 9 1 0 10 20 30 255\n"
                  "0 9 1 0 10 20 30 255\n7 4 0 1 2 3\n");
  const ColouredGeometry g = readPly(dir / "a.ply");
  ASSERT_EQ(g.vertexCount(), 4u);
  EXPECT_EQ(g.xyz[6], 1.0f);
  EXPECT_EQ(g.xyz[7], 1.0f);
  EXPECT_EQ(g.rgb[3], 10);
  EXPECT_EQ(g.rgb[5], 30);
  EXPECT_EQ(g.triangles, (std::vector<std::uint32_t>{0, 1, 2, 0, 2, 3}));
}

TEST(ReadPly, ReadsTheSparseMapWithoutColourAsGrey) {
  const fs::path dir = amos::testing::scratchDirForThisTest("viewer_ply_");
  test::writeText(dir / "map.ply", "ply\nformat ascii 1.0\nelement vertex 2\nproperty float x\nproperty float y\n"
                                   "property float z\nend_header\n0 0 1\n0.5 -0.25 2\n");
  const ColouredGeometry g = readPly(dir / "map.ply");
  EXPECT_EQ(g.xyz, (std::vector<float>{0, 0, 1, 0.5f, -0.25f, 2}));
  EXPECT_EQ(g.rgb, std::vector<std::uint8_t>(6, 200));
}

TEST(ReadPly, BadFilesAreErrorsNamingTheFile) {
  const fs::path dir = amos::testing::scratchDirForThisTest("viewer_ply_");
  const std::string header = "ply\nformat binary_little_endian 1.0\nelement vertex 2\nproperty float x\n"
                             "property float y\nproperty float z\n";
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"not_ply.ply", "hello\n"},
      {"big_endian.ply", "ply\nformat binary_big_endian 1.0\nelement vertex 0\nproperty float x\nend_header\n"},
      {"no_xyz.ply", "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nend_header\n1\n"},
      {"truncated.ply", header + "end_header\n" + std::string(12, '\0')},
      {"bad_type.ply", "ply\nformat ascii 1.0\nelement vertex 1\nproperty quad x\nend_header\n1\n"},
      {"bad_number.ply", "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\n"
                         "property float z\nend_header\n1 two 3\n"},
      {"bad_index.ply", "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\n"
                        "property float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n"
                        "0 0 0\n3 0 0 5\n"}};
  for (const auto& [name, text] : cases) {
    test::writeText(dir / name, text);
    try {
      readPly(dir / name);
      ADD_FAILURE() << name << " was read";
    } catch (const core::Error& e) {
      EXPECT_NE(std::string(e.what()).find(name), std::string::npos) << e.what();
    }
  }
  EXPECT_THROW(readPly(dir / "missing.ply"), core::Error);
}

// Counts in the header or the body that claim more than the file holds are errors naming the file and the element,
// found before anything of the claimed size is allocated or looped over (they used to be std::bad_alloc, or a float
// list count of -1 read as 2^64 - 1).
TEST(ReadPly, CountsClaimingMoreThanTheFileHoldsAreErrorsNamingTheFile) {
  const fs::path dir = amos::testing::scratchDirForThisTest("viewer_ply_");
  const std::string xyz = "property float x\nproperty float y\nproperty float z\n";
  const std::string binary = "ply\nformat binary_little_endian 1.0\n";
  const std::string ascii = "ply\nformat ascii 1.0\n";
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"huge_vertex_count.ply", binary + "element vertex 1000000000000000\n" + xyz + "end_header\n" +
                                    std::string(12, '\0')},
      {"vertex_count_beyond_body.ply", binary + "element vertex 2\n" + xyz + "end_header\n" + std::string(20, '\0')},
      {"ascii_vertex_count.ply", ascii + "element vertex 3\n" + xyz + "end_header\n0 0 0\n1 1 1\n"},
      {"overflowing_count.ply", ascii + "element vertex 99999999999999999999999\n" + xyz + "end_header\n0 0 0\n"},
      {"list_count.ply", binary + "element vertex 1\n" + xyz + "element face 1\n"
                             "property list uint int vertex_indices\nend_header\n" + std::string(12, '\0') +
                             std::string("\xff\xff\xff\x7f", 4) + std::string(12, '\0')},
      {"negative_list_count.ply", ascii + "element vertex 1\n" + xyz + "element face 1\n"
                                      "property list float int vertex_indices\nend_header\n0 0 0\n-1 0 0 0\n"},
      {"fractional_list_count.ply", ascii + "element vertex 1\n" + xyz + "element face 1\n"
                                        "property list float int vertex_indices\nend_header\n0 0 0\n2.5 0 0 0\n"}};
  for (const auto& [name, text] : cases) {
    test::writeText(dir / name, text);
    try {
      const ColouredGeometry g = readPly(dir / name);
      ADD_FAILURE() << name << " was read: " << g.vertexCount() << " vertices";
    } catch (const core::Error& e) {
      EXPECT_NE(std::string(e.what()).find(name), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find("claims"), std::string::npos) << e.what();
    }
  }
}

// Elements without properties take no bytes: any count of them is read at once (it used to be a loop of 10^18).
TEST(ReadPly, ElementsWithoutPropertiesAreSkippedWhateverTheirCount) {
  const fs::path dir = amos::testing::scratchDirForThisTest("viewer_ply_");
  test::writeText(dir / "empty_items.ply", "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\n"
                                           "property float y\nproperty float z\nelement junk 1000000000000000000\n"
                                           "element face 1000000000000000000\nend_header\n0 0 0\n");
  const ColouredGeometry g = readPly(dir / "empty_items.ply");
  EXPECT_EQ(g.vertexCount(), 1u);
  EXPECT_TRUE(g.triangles.empty());
}

// Vertex coordinates that are not finite floats are errors naming the file and the vertex; a NaN colour is 0.
TEST(ReadPly, NonFiniteCoordinatesAreErrorsNamingTheFile) {
  const fs::path dir = amos::testing::scratchDirForThisTest("viewer_ply_");
  const std::string header = "ply\nformat ascii 1.0\nelement vertex 2\nproperty double x\nproperty double y\n"
                             "property double z\nproperty float red\nend_header\n0 0 0 nan\n";
  for (const auto& [name, vertex, axis] : {std::tuple{"nan.ply", "nan 0 0 0\n", "x = nan"},
                                           {"inf.ply", "0 -inf 0 0\n", "y = -inf"},
                                           {"beyond_float.ply", "0 0 1e300 0\n", "z = 1e+300"}}) {
    test::writeText(dir / name, header + vertex);
    try {
      readPly(dir / name);
      ADD_FAILURE() << name << " was read";
    } catch (const core::Error& e) {
      EXPECT_NE(std::string(e.what()).find(name), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find(std::string("vertex 1 has ") + axis), std::string::npos) << e.what();
    }
  }
  test::writeText(dir / "finite.ply", header + "1 2 3 0.5\n");
  const ColouredGeometry g = readPly(dir / "finite.ply");
  EXPECT_EQ(g.rgb[0], 0);
  EXPECT_EQ(g.rgb[3], 128);
}

// The ply fuzz target's corpus (fuzz/corpus/ply/: seeds and the inputs of fixed crashes), replayed through its entry
// function: no input may crash or throw anything but core::Error.
TEST(FuzzCorpus, PlyInputsGiveGeometryOrCoreErrors) {
  EXPECT_GE(amos::testing::replayFuzzCorpus("ply", fuzz::readPlyInput), 9u);
}

}  // namespace
}  // namespace amos::viewer
