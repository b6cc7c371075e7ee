// The TUM benchmark's own figures (evaluate_ate.py; evaluate_rpe.py --fixed_delta --delta 1 --delta_unit s) for
// two public trajectory pairs, listed in /work/shared/data/README.md, reproduced by evaluate().
#include <gtest/gtest.h>

#include <ostream>
#include <string>

#include "amos/eval/evaluate.h"
#include "amos/io/trajectory.h"
#include "amos/testing/shared_data.h"

namespace amos::eval {
namespace {

struct Reference {
  const char* name;
  const char* gt_file;
  const char* est_file;
  double ate_rmse_m;
  std::size_t ate_pairs;
  double rpe_trans_rmse_m, rpe_rot_rmse_deg;
  std::size_t rpe_pairs;
};

const Reference kReferences[] = {
    {"fr2_desk_ORB", "rgbd_dataset_freiburg2_desk_groundtruth.txt", "evo_testdata_fr2_desk_ORB.txt", 0.008144, 2223, 0.007161,
     0.455005, 1998},
    {"fr1_xyz_rgbdslam", "rgbd_dataset_freiburg1_xyz_groundtruth.txt", "evo_testdata_freiburg1_xyz-rgbdslam.txt", 0.013473, 786,
     0.021217, 0.934480, 753},
};

std::string trajectoryPath(const std::string& name) { return testing::dataPath("trajectories/" + name); }

void PrintTo(const Reference& ref, std::ostream* os) { *os << ref.name; }

class TumReference : public ::testing::TestWithParam<Reference> {};

TEST_P(TumReference, ReproducesTheBenchmarkScripts) {
  AMOS_REQUIRE_DATA("trajectories");
  const Reference& ref = GetParam();
  const auto gt = io::readTumTrajectory(trajectoryPath(ref.gt_file));
  const auto est = io::readTumTrajectory(trajectoryPath(ref.est_file));
  const EvaluationResult r = evaluate(gt, est);
  // The README's figures are printed with 6 decimals (%f), so they carry +-5e-7 of rounding.
  EXPECT_NEAR(r.ate_rmse_m, ref.ate_rmse_m, 2e-6);
  EXPECT_EQ(r.ate_pairs, ref.ate_pairs);
  EXPECT_NEAR(r.rpe_trans_rmse_m, ref.rpe_trans_rmse_m, 2e-6);
  EXPECT_NEAR(r.rpe_rot_rmse_deg, ref.rpe_rot_rmse_deg, 2e-4);
  EXPECT_EQ(r.rpe_pairs, ref.rpe_pairs);
  std::printf("%s: ATE %.9f m (%zu pairs), RPE %.9f m %.7f deg (%zu pairs)\n", ref.est_file, r.ate_rmse_m,
              r.ate_pairs, r.rpe_trans_rmse_m, r.rpe_rot_rmse_deg, r.rpe_pairs);
}

INSTANTIATE_TEST_SUITE_P(ReadmeRows, TumReference, ::testing::ValuesIn(kReferences),
                         [](const ::testing::TestParamInfo<Reference>& info) { return std::string(info.param.name); });

}  // namespace
}  // namespace amos::eval
