#include "amos/report/output_folder.h"

#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <csignal>
#include <filesystem>
#include <fstream>

#include "amos/core/error.h"
#include "amos/core/log_capture.h"

namespace amos::report {
namespace {

namespace fs = std::filesystem;

fs::path freshRoot(const std::string& name) {
  const fs::path root = fs::path(AMOS_BINARY_DIR) / "test_outputs" / "output_folder" / name;
  fs::remove_all(root);
  fs::create_directories(root);
  return root;
}

const std::vector<std::string> kOutputs = {"trajectory.txt", "stats.json", "masks"};

OutputFolderRequest request(const fs::path& dir, bool overwrite, const std::string& input = "") {
  return {dir.string(), overwrite, kOutputs, input};
}

std::string errorOf(const OutputFolderRequest& r) {
  try {
    prepareOutputFolder(r);
  } catch (const core::Error& e) {
    return e.what();
  }
  return "";
}

std::string errorOf(const std::string& dir, bool overwrite) { return errorOf(request(dir, overwrite)); }

bool contains(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

void touch(const fs::path& path) { std::ofstream(path) << "x\n"; }

// A finished run's folder: its outputs and its manifest, the lock gone.
void earlierRun(const fs::path& out) {
  prepareOutputFolder(request(out, false));
  touch(out / "trajectory.txt");
  touch(out / "stats.json");
  fs::create_directories(out / "masks");
  touch(out / "masks" / "1.0.png");
}

TEST(OutputFolder, CreatesTheFolderWithItsManifestOnly) {
  const fs::path out = freshRoot("create") / "a" / "b";
  {
    const OutputFolderLock lock = prepareOutputFolder(request(out, false));
    ASSERT_TRUE(fs::is_directory(out));
    EXPECT_TRUE(lock.held());
    EXPECT_TRUE(fs::exists(out / kLockFile));
  }
  EXPECT_FALSE(fs::exists(out / kLockFile));  // removed with the lock
  std::vector<std::string> names;
  for (const auto& e : fs::directory_iterator(out)) names.push_back(e.path().filename().string());
  EXPECT_EQ(names, std::vector<std::string>{kManifestFile});
}

TEST(OutputFolder, APathUnderARegularFileNamesThatFile) {
  const fs::path root = freshRoot("under_file");
  touch(root / "notes.txt");
  const std::string under = errorOf((root / "notes.txt" / "run").string(), false);
  EXPECT_TRUE(contains(under, "notes.txt' is a file")) << under;
  const std::string itself = errorOf((root / "notes.txt").string(), false);
  EXPECT_TRUE(contains(itself, "is a file, not a folder")) << itself;
}

// /proc/self is a folder that nobody, root included, can create files in.
TEST(OutputFolder, AnUnwritableFolderIsAnError) {
  const std::string message = errorOf("/proc/self", false);
  EXPECT_TRUE(contains(message, "cannot write into output folder '/proc/self'")) << message;
}

TEST(OutputFolder, AnEarlierRunIsRefusedWithoutOverwrite) {
  const fs::path out = freshRoot("earlier");
  earlierRun(out);
  const std::string message = errorOf(out.string(), false);
  EXPECT_TRUE(contains(message, "holds an earlier run (trajectory.txt, stats.json, masks)")) << message;
  EXPECT_TRUE(contains(message, "--overwrite")) << message;
  EXPECT_TRUE(fs::exists(out / "trajectory.txt"));
}

// --overwrite removes what the earlier run's manifest lists (and what it left half-written), nothing else.
TEST(OutputFolder, OverwriteRemovesOnlyWhatTheManifestLists) {
  const fs::path out = freshRoot("overwrite");
  earlierRun(out);
  touch(out / "trajectory.txt.partial");  // left by a run killed while writing
  touch(out / "notes.txt");
  fs::create_directories(out / "plots");
  prepareOutputFolder(request(out, true));
  for (const std::string& name : kOutputs) EXPECT_FALSE(fs::exists(out / name)) << name;
  EXPECT_FALSE(fs::exists(out / "trajectory.txt.partial"));
  EXPECT_TRUE(fs::exists(out / "notes.txt"));
  EXPECT_TRUE(fs::is_directory(out / "plots"));
  EXPECT_TRUE(fs::exists(out / kManifestFile));  // the new run's
}

// Files no manifest lists are never removed: a folder of someone else's files is refused, with --overwrite too,
// and says what to do; so are files that have the names of a run's outputs.
TEST(OutputFolder, AFolderWithoutManifestIsNeverEmptied) {
  const fs::path out = freshRoot("foreign");
  touch(out / "data.csv");
  std::string message = errorOf(out.string(), true);
  EXPECT_TRUE(contains(message, "has no run manifest")) << message;
  EXPECT_TRUE(contains(message, "data.csv")) << message;
  EXPECT_TRUE(contains(message, "Give a new or empty --output")) << message;
  EXPECT_TRUE(fs::exists(out / "data.csv"));
  EXPECT_EQ(errorOf(out.string(), false), "");  // beside them, without --overwrite: nothing of theirs is touched

  const fs::path named = freshRoot("foreign_named");
  touch(named / "stats.json");
  for (const bool overwrite : {false, true}) {
    message = errorOf(named.string(), overwrite);
    EXPECT_TRUE(contains(message, "stats.json")) << message;
    EXPECT_TRUE(fs::exists(named / "stats.json"));
  }
  EXPECT_TRUE(contains(errorOf(named.string(), false), "which no run manifest")) << message;
}

TEST(OutputFolder, AManifestNamingAPathOutsideIsRefused) {
  const fs::path out = freshRoot("bad_manifest");
  touch(out / "keep.txt");
  std::ofstream(out / kManifestFile) << R"({"outputs": ["../keep.txt"]})";
  const std::string message = errorOf(out.string(), true);
  EXPECT_TRUE(contains(message, "is not a name of a file in the folder")) << message;
  EXPECT_TRUE(fs::exists(out / "keep.txt"));
}

// The input is never written: the output folder may not be the sequence folder or lie inside it, also through a
// symlink or a path that does not exist yet.
TEST(OutputFolder, AnOutputInsideTheInputIsRefused) {
  const fs::path root = freshRoot("inside_input");
  const fs::path input = root / "sequence";
  fs::create_directories(input / "rgb");
  fs::create_directory_symlink(input, root / "link");
  for (const fs::path& out : {input, input / "rgb", input / "out" / "run", root / "link" / "out",
                              root / "sequence" / ".." / "sequence" / "x"}) {
    const std::string message = errorOf(request(out, false, input.string()));
    EXPECT_TRUE(contains(message, "--output '" + out.string() + "'")) << message;
    EXPECT_TRUE(contains(message, "the input sequence folder")) << message;
  }
  EXPECT_FALSE(fs::exists(input / "out"));
  EXPECT_FALSE(fs::exists(input / ".amos-run.lock"));
  EXPECT_EQ(errorOf(request(root / "sequence_out", false, input.string())), "");  // a sibling with a longer name
  EXPECT_THROW(refuseInsideInput((root / "link" / "map.bin").string(), "--save-map", input.string()), core::Error);
  EXPECT_THROW(refuseInsideInput((root / "link").string(), "--record", (input / "..").string()), core::Error);
  EXPECT_NO_THROW(refuseInsideInput((root / "map.bin").string(), "--save-map", input.string()));
}

// One run per folder: a second lock is refused at once, naming the holder's PID; once the holder has gone, its
// lock is taken.
TEST(OutputFolder, ASecondRunOnTheSameFolderIsRefusedNamingThePid) {
  const fs::path out = freshRoot("locked");
  {
    const OutputFolderLock first = prepareOutputFolder(request(out, false));
    const std::string message = errorOf(out.string(), true);
    EXPECT_TRUE(contains(message, "is in use by another run (PID " + std::to_string(::getpid()) + ",")) << message;
    EXPECT_TRUE(fs::exists(out / kManifestFile));  // the first run's folder is left alone
  }
  EXPECT_NO_THROW(OutputFolderLock::acquire(out.string()));
}

// A lock file left by a process that was killed (SIGKILL: it could not remove it) is taken over with a warning.
TEST(OutputFolder, AStaleLockIsTakenOverWithAWarning) {
  const fs::path out = freshRoot("stale");
  const pid_t child = fork();
  ASSERT_GE(child, 0);
  if (child == 0) {
    const OutputFolderLock lock = OutputFolderLock::acquire(out.string());
    raise(SIGKILL);
  }
  int status = 0;
  waitpid(child, &status, 0);
  ASSERT_TRUE(fs::exists(out / kLockFile));
  core::LogCapture log;
  const OutputFolderLock lock = OutputFolderLock::acquire(out.string());
  EXPECT_TRUE(lock.held());
  bool warned = false;
  for (const std::string& line : log.lines())
    warned |= contains(line, "taking over the lock left by PID " + std::to_string(child) + ", which has ended");
  EXPECT_TRUE(warned);
}

TEST(OutputFolder, AnOutputFileIsCheckedBeforeTheRun) {
  const fs::path root = freshRoot("output_file");
  EXPECT_NO_THROW(checkOutputFile((root / "map.bin").string(), "--save-map"));
  EXPECT_FALSE(fs::exists(root / "map.bin"));
  const auto message = [](const std::string& path) {
    try {
      checkOutputFile(path, "--save-map");
    } catch (const core::Error& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  EXPECT_TRUE(contains(message(root.string()), "is a folder, not a file"));
  EXPECT_TRUE(contains(message((root / "no" / "map.bin").string()), "does not exist"));
  EXPECT_TRUE(contains(message("/proc/self/map.bin"), "cannot write into its folder '/proc/self'"));
}

}  // namespace
}  // namespace amos::report
