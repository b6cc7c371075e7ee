// amos-slam vocab: trains the place-recognition vocabulary (place/vocabulary.h) on the ORB descriptors of
// sequences, extracted exactly as `run` extracts them (the --config's ORBextractor settings), and writes it in
// its binary form. Which images it saw is printed and is the vocabulary's provenance (models/README.md).
#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <iostream>
#include <memory>
#include <string>
#include <vector>

#include "amos/config/settings.h"
#include "amos/run/settings_sections.h"
#include "amos/core/stage_timer.h"
#include "amos/feature/orb_extractor.h"
#include "amos/io/dataset.h"
#include "amos/place/vocabulary.h"
#include "amos/system/frame_scheduler.h"
#include "commands.h"

namespace amos::app {
namespace {

struct VocabArgs {
  std::vector<std::string> sequences;
  std::string config, output;
  std::size_t every = 10;
  place::VocabularyOptions vocabulary;
};

void trainVocabulary(const VocabArgs& args) {
  const config::Settings settings = run::loadSettings(args.config);
  const feature::OrbExtractor extractor(settings.orb);
  std::vector<cv::Mat> images;
  std::size_t descriptors = 0;
  core::Stopwatch watch;
  for (const std::string& dir : args.sequences) {
    io::SequenceIndex index = io::indexSequence(dir);
    const std::size_t listed = index.frames.size();
    io::SequenceReader reader(std::move(index), settings.readerOptions());
    std::size_t k = 0, used = 0;
    while (std::optional<io::RgbdFrame> frame = reader.next()) {
      if (k++ % args.every != 0) continue;
      std::vector<cv::KeyPoint> keys;
      cv::Mat d;
      extractor.extract(system::toGray(*frame), keys, d);
      if (d.rows == 0) continue;
      descriptors += d.rows;
      images.push_back(d);
      ++used;
    }
    std::cout << fmt::format("{}: {} of {} frames (every {})\n", dir, used, listed, args.every);
  }
  spdlog::info("training on {} descriptors of {} images", descriptors, images.size());
  const place::Vocabulary vocabulary = place::Vocabulary::train(images, args.vocabulary);
  vocabulary.save(args.output);
  std::cout << fmt::format("vocabulary {}: {} words (branching {}, depth {}) from {} descriptors of {} images in "
                           "{:.1f} s\n",
                           args.output, vocabulary.numWords(), vocabulary.branching(), vocabulary.depth(), descriptors,
                           images.size(), watch.elapsedMs() / 1000.0);
}

}  // namespace

void addVocabCommand(CLI::App& app, int& exit_code) {
  auto args = std::make_shared<VocabArgs>();
  auto* cmd = app.add_subcommand("vocab", "Train the place-recognition vocabulary on the ORB descriptors of sequences");
  cmd->add_option("--sequence", args->sequences, "Sequence folders to train on (one or more)")
      ->required()
      ->check(CLI::ExistingDirectory);
  cmd->add_option("--config", args->config, "Settings file whose ORBextractor.* settings extract the descriptors")
      ->required()
      ->check(CLI::ExistingFile);
  cmd->add_option("--output", args->output, "Vocabulary file to write")->required();
  cmd->add_option("--every", args->every, "Use every Nth frame of each sequence (default 10)")
      ->check(CLI::PositiveNumber);
  cmd->add_option("--branching", args->vocabulary.branching, "Children per tree node (default 10)");
  cmd->add_option("--depth", args->vocabulary.depth, "Tree levels (default 4: up to branching^4 words)");
  cmd->add_option("--seed", args->vocabulary.seed, "Seed of the clustering (default 1)");
  cmd->callback([args, &exit_code] {
    trainVocabulary(*args);
    exit_code = 0;
  });
}

}  // namespace amos::app
