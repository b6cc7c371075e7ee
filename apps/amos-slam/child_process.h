#pragma once
// For the tests of the program (*_test.cc here): amos-slam run in a child process, its stderr read line by line;
// the output folders and synthetic input those tests share.
#include <fcntl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "amos/synth/sequence.h"
#include "amos/testing/scratch_dir.h"

namespace amos::app {

// A folder for one test's run outputs: <group>/<name> inside this process's scratch folder (testing::scratchDir,
// so two test processes never share one), absent (its parent exists), as `run --output` is given it.
inline std::filesystem::path testOutputDir(const std::string& group, const std::string& name) {
  static const std::filesystem::path root = testing::scratchDir("amos_app_tests");
  const std::filesystem::path dir = root / group / name;
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir.parent_path());
  return dir;
}

// A synthetic sequence (synth preset, seed 1, `frames` frames), rendered once into the build folder's cache.
inline std::string syntheticSequence(const std::string& preset, int frames) {
  return synth::cachedSequence((std::filesystem::path(AMOS_BINARY_DIR) / "test_outputs" / "synth_cache").string(),
                               preset, 1, frames);
}

// `run` of `sequence` with configs/tum3.yaml in `mode`, a progress line for every frame.
inline std::vector<std::string> runArgs(const std::string& sequence, const std::string& mode,
                                        const std::filesystem::path& output) {
  return {"run", "--sequence", sequence, "--config", std::string(AMOS_SOURCE_DIR) + "/configs/tum3.yaml",
          "--mode", mode, "--output", output.string(), "--progress-every", "1"};
}

struct Finished {
  int status = 0;  // as waitpid gives it
  std::string out, err;
};

inline std::string readFile(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

// Runs amos-slam with `args`: stdout to a file (empty: to a pipe whose reader has gone away, as in
// `amos-slam run ... | head -0`), stderr through a pipe that is read line by line; `on_line` sees each stderr line
// and may signal the child (its pid is given).
inline Finished runChild(const std::vector<std::string>& args, const std::filesystem::path& stdout_file,
                         const std::function<void(const std::string&, pid_t)>& on_line = {}) {
  int err_pipe[2], out_pipe[2];
  if (pipe(err_pipe) != 0 || pipe(out_pipe) != 0) throw std::runtime_error("pipe");
  close(out_pipe[0]);  // nobody reads the child's stdout pipe
  const pid_t pid = fork();
  if (pid == 0) {
    const int out = stdout_file.empty() ? out_pipe[1] : open(stdout_file.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    dup2(out, STDOUT_FILENO);
    dup2(err_pipe[1], STDERR_FILENO);
    close(err_pipe[0]);
    std::vector<char*> argv{const_cast<char*>(AMOS_SLAM_EXE)};
    for (const std::string& a : args) argv.push_back(const_cast<char*>(a.c_str()));
    argv.push_back(nullptr);
    execv(AMOS_SLAM_EXE, argv.data());
    _exit(127);
  }
  close(err_pipe[1]);
  close(out_pipe[1]);
  Finished f;
  std::FILE* err = fdopen(err_pipe[0], "r");
  char buffer[4096];
  while (std::fgets(buffer, sizeof(buffer), err) != nullptr) {
    f.err += buffer;
    if (on_line) on_line(buffer, pid);
  }
  std::fclose(err);
  waitpid(pid, &f.status, 0);
  if (!stdout_file.empty()) f.out = readFile(stdout_file);
  return f;
}

}  // namespace amos::app
