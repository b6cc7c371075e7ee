// The corpora of the sequence-index, trajectory and png fuzz targets (fuzz/corpus/), replayed through the targets' entry
// functions: no input may crash or throw anything but core::Error.
#include <gtest/gtest.h>

#include "amos/testing/fuzz_corpus.h"
#include "fuzz/io_inputs.h"

namespace amos::io {
namespace {

TEST(FuzzCorpus, SequenceIndexInputsGiveFramesOrCoreErrors) {
  EXPECT_GE(testing::replayFuzzCorpus("sequence_index", fuzz::readSequenceIndexInput), 5u);
}

TEST(FuzzCorpus, TrajectoryInputsGivePosesOrCoreErrors) {
  EXPECT_GE(testing::replayFuzzCorpus("trajectory", fuzz::readTrajectoryInput), 4u);
}

TEST(FuzzCorpus, PngInputsGiveImagesOrEmptyMats) {
  EXPECT_GE(testing::replayFuzzCorpus("png", fuzz::decodePngInput), 14u);
}

}  // namespace
}  // namespace amos::io
