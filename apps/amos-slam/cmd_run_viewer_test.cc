// `amos-slam run --viewer` and `amos-slam view` as a user runs them: the endpoints fetched while a run goes (the
// map grows, the pose moves, the frame image decodes), report.html written and parsable, `view` refusing paths
// outside the run, and a real browser (headless Chromium) drawing the live page and report.html without a script
// error. Only with the viewer module (AMOS_BUILD_VIEWER).
#ifdef AMOS_HAVE_VIEWER
#include <gtest/gtest.h>

#include <opencv2/imgcodecs.hpp>

#include <algorithm>
#include <csignal>
#include <cstdlib>
#include <filesystem>
#include <optional>
#include <regex>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "amos/synth/sequence.h"
#include "child_process.h"
// After every Eigen header: httplib.h brings <resolv.h>, whose `_res` macro breaks Eigen's templates.
#include <httplib.h>

namespace amos::app {
namespace {

namespace fs = std::filesystem;

// 120 frames replayed at 30 Hz (--realtime): four seconds in which the viewer is looked at.
std::string viewerSequence() { return syntheticSequence("walking_xyz", 120); }

fs::path viewerOutputDir(const std::string& name) { return testOutputDir("viewer", name); }

std::vector<std::string> viewerRunArgs(const fs::path& output) {
  std::vector<std::string> args = runArgs(viewerSequence(), "geometry", output);
  for (const char* a : {"--realtime", "--viewer", "--viewer-port", "0", "--viewer-hold"}) args.emplace_back(a);
  return args;
}

// The port in "viewer: http://127.0.0.1:PORT/".
std::optional<int> viewerPort(const std::string& line) {
  static const std::regex address("viewer: http://127\\.0\\.0\\.1:([0-9]+)/");
  std::smatch m;
  if (!std::regex_search(line, m, address)) return std::nullopt;
  return std::stoi(m[1]);
}

// The frame number of a progress line "frame N/TOTAL", or 0.
int progressFrame(const std::string& line) {
  static const std::regex progress("frame ([0-9]+)/");
  std::smatch m;
  return std::regex_search(line, m, progress) ? std::stoi(m[1]) : 0;
}

nlohmann::json getState(int port) {
  httplib::Client c("127.0.0.1", port);
  const auto r = c.Get("/api/state");
  if (!r || r->status != 200) return nlohmann::json();
  return nlohmann::json::parse(r->body);
}

bool viewerContains(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

nlohmann::json reportData(const fs::path& report) {
  const std::string html = readFile(report);
  const std::string open = "<script id=\"amos-report-data\" type=\"application/json\">";
  const std::size_t begin = html.find(open);
  if (begin == std::string::npos) return nlohmann::json();
  const std::size_t end = html.find("</script>", begin);
  return nlohmann::json::parse(html.substr(begin + open.size(), end - begin - open.size()));
}

TEST(RunViewer, EndpointsShowTheRunWhileItGoes) {
  const fs::path out = viewerOutputDir("endpoints");
  int port = 0;
  nlohmann::json early, late, final_state;
  cv::Mat frame_image;
  const Finished f = runChild(viewerRunArgs(out), out.string() + ".stdout", [&](const std::string& line, pid_t pid) {
    if (const auto p = viewerPort(line)) port = *p;
    const int frame = progressFrame(line);
    if (port > 0 && early.is_null() && frame >= 40) early = getState(port);
    if (port > 0 && late.is_null() && frame >= 100) {
      late = getState(port);
      httplib::Client c("127.0.0.1", port);
      if (const auto r = c.Get("/api/frame.jpg"); r && r->status == 200)
        frame_image = cv::imdecode(std::vector<unsigned char>(r->body.begin(), r->body.end()), cv::IMREAD_COLOR);
    }
    if (port > 0 && viewerContains(line, "still serving")) {
      final_state = getState(port);
      kill(pid, SIGTERM);
    }
  });
  ASSERT_GT(port, 0) << f.err;
  ASSERT_TRUE(WIFEXITED(f.status)) << f.err;
  EXPECT_EQ(WEXITSTATUS(f.status), 0) << f.err;
  ASSERT_FALSE(early.is_null()) << f.err;
  ASSERT_FALSE(late.is_null()) << f.err;
  ASSERT_FALSE(final_state.is_null()) << f.err;
  // The map and the trajectory grow, the camera moves.
  EXPECT_GT(early["points"].size(), 0u);
  EXPECT_GT(final_state["trajectory"].size(), early["trajectory"].size());
  // The map changed since (it does not only grow: culling and fusion remove points, more so when --realtime
  // drops frames on a loaded machine).
  EXPECT_NE(final_state["points"], early["points"]);
  EXPECT_GT(final_state["keyframes"].size(), 0u);
  ASSERT_TRUE(early["frame"].is_object());
  ASSERT_TRUE(late["frame"].is_object());
  EXPECT_GT(late["frame"]["index"].get<int>(), early["frame"]["index"].get<int>());
  EXPECT_NE(late["frame"]["T_wc"], early["frame"]["T_wc"]);
  EXPECT_EQ(early["info"]["mode"], "geometry");
  EXPECT_TRUE(final_state["summary"].contains("evaluation"));
  EXPECT_FALSE(final_state["ground_truth"].empty());
  // The frame image decodes, at the camera's size.
  EXPECT_EQ(frame_image.cols, 640);
  EXPECT_EQ(frame_image.rows, 480);
  // report.html is written, its data block parses and holds the run.
  const nlohmann::json data = reportData(out / "report.html");
  ASSERT_TRUE(data.is_object());
  EXPECT_EQ(data["frames"]["index"].size(), data["stats"]["frames"].get<std::size_t>());
  EXPECT_FALSE(data["ate"]["error_m"].empty());
  EXPECT_FALSE(data["overlays"].empty());
  EXPECT_EQ(data["settings"]["options"]["mode"], "geometry");
}

// With --viewer-hold and stdout in a file (not a terminal), the summary is in the file when the run ends, while
// the viewer still serves: not only once Ctrl-C has ended the program.
TEST(RunViewer, HeldRunHasWrittenItsSummary) {
  const fs::path out = viewerOutputDir("held_summary");
  std::vector<std::string> args = runArgs(syntheticSequence("static_xyz", 40), "none", out);
  for (const char* a : {"--viewer", "--viewer-port", "0", "--viewer-hold"}) args.emplace_back(a);
  const fs::path stdout_file = out.string() + ".stdout";
  std::string while_held;
  const Finished f = runChild(args, stdout_file, [&](const std::string& line, pid_t pid) {
    if (viewerContains(line, "still serving")) {
      while_held = readFile(stdout_file);
      kill(pid, SIGINT);
    }
  });
  ASSERT_TRUE(WIFEXITED(f.status)) << f.err;
  EXPECT_EQ(WEXITSTATUS(f.status), 0) << f.err;
  EXPECT_TRUE(viewerContains(while_held, "frames 40  tracked 40")) << while_held;
  EXPECT_TRUE(viewerContains(while_held, "outputs written to " + out.string())) << while_held;
}

// A viewer port in use (here by another viewer) is an error at start naming the port; nothing runs.
TEST(RunViewer, APortInUseIsRefusedAtStart) {
  const fs::path out = viewerOutputDir("port_in_use");
  int port = 0;
  Finished second;
  std::vector<std::string> first = runArgs(syntheticSequence("static_xyz", 40), "none", out / "first");
  for (const char* a : {"--viewer", "--viewer-port", "0", "--viewer-hold"}) first.emplace_back(a);
  const Finished f = runChild(first, out.string() + ".stdout", [&](const std::string& line, pid_t pid) {
    if (const auto p = viewerPort(line)) port = *p;
    if (viewerContains(line, "still serving")) {
      std::vector<std::string> args = runArgs(syntheticSequence("static_xyz", 40), "none", out / "second");
      args.insert(args.end(), {"--viewer", "--viewer-port", std::to_string(port)});
      second = runChild(args, out.string() + ".second");
      kill(pid, SIGINT);
    }
  });
  ASSERT_GT(port, 0) << f.err;
  ASSERT_TRUE(WIFEXITED(second.status));
  EXPECT_EQ(WEXITSTATUS(second.status), 1) << second.err;
  EXPECT_TRUE(viewerContains(second.err, "port " + std::to_string(port) + " is in use")) << second.err;
  EXPECT_FALSE(viewerContains(second.err, "frame 1/")) << second.err;
}

// --load-map passes through the viewer: the page shows the map the run started from and says where it came from.
TEST(RunViewer, ALoadedMapIsShownFromTheStart) {
  const fs::path first = viewerOutputDir("map_first_half"), second = viewerOutputDir("map_second_half");
  const fs::path map_file = first.parent_path() / "first_half.map";
  std::vector<std::string> save = runArgs(viewerSequence(), "geometry", first);
  save.insert(save.end(), {"--max-frames", "60", "--save-map", map_file.string()});
  const Finished saved = runChild(save, first.string() + ".stdout");
  ASSERT_TRUE(WIFEXITED(saved.status) && WEXITSTATUS(saved.status) == 0) << saved.err;
  ASSERT_TRUE(fs::exists(map_file)) << saved.err;

  // Every frame processed (no --realtime): a slow build (sanitizers) would drop most of them.
  std::vector<std::string> args = viewerRunArgs(second);
  args.erase(std::find(args.begin(), args.end(), "--realtime"));
  args.insert(args.end(), {"--first-frame", "60", "--load-map", map_file.string(), "--localize"});
  int port = 0;
  nlohmann::json at_start, at_end;
  const Finished f = runChild(args, second.string() + ".stdout", [&](const std::string& line, pid_t pid) {
    if (const auto p = viewerPort(line)) port = *p;
    if (port > 0 && at_start.is_null() && progressFrame(line) >= 1) at_start = getState(port);
    if (port > 0 && viewerContains(line, "still serving")) {
      at_end = getState(port);
      kill(pid, SIGTERM);
    }
  });
  ASSERT_TRUE(WIFEXITED(f.status)) << f.err;
  ASSERT_TRUE(at_start.is_object()) << f.err;
  const nlohmann::json& loaded = at_start["info"]["loaded_map"];
  ASSERT_TRUE(loaded.is_object()) << at_start["info"].dump();
  EXPECT_EQ(loaded["file"], map_file.string());
  EXPECT_EQ(loaded["localize"], true);
  EXPECT_GT(loaded["keyframes"].get<int>(), 2);
  EXPECT_GT(loaded["points"].get<int>(), 100);
  // The page shows the loaded map, to which localising adds nothing.
  EXPECT_EQ(at_end["keyframes"].size(), loaded["keyframes"].get<std::size_t>());
  EXPECT_EQ(at_end["points"].size(), loaded["points"].get<std::size_t>());
  EXPECT_GT(at_end["trajectory"].size(), 40u);
}

TEST(ViewCommand, ServesAFinishedRunAndNothingOutsideIt) {
  const fs::path root = viewerOutputDir("view");
  const fs::path run = root / "run";
  fs::create_directories(run / "overlays");
  std::ofstream(run / "trajectory.txt") << "1 0 0 0 0 0 0 1\n2 0.1 0 0 0 0 0 1\n";
  std::ofstream(run / "stats.json") << R"({"frames": 2, "mode": "none"})";
  std::ofstream(run / "overlays" / "1.png") << "x";
  std::ofstream(root / "secret.txt") << "SECRET";
  std::vector<std::pair<std::string, int>> answers;
  nlohmann::json state;
  const Finished f = runChild({"view", run.string(), "--viewer-port", "0"}, root / "stdout",
                              [&](const std::string& line, pid_t pid) {
    const auto port = viewerPort(line);
    if (!port) return;
    state = getState(*port);
    httplib::Client c("127.0.0.1", *port);
    for (const std::string path : {"/files/stats.json", "/files/../secret.txt", "/files/%2e%2e/secret.txt",
                                   "/files//etc/passwd", "/files/overlays/../../secret.txt"}) {
      const auto r = c.Get(path.c_str());
      answers.emplace_back(path, r ? (viewerContains(r->body, "SECRET") || viewerContains(r->body, "root:") ? -1 : r->status) : 0);
    }
    kill(pid, SIGINT);
  });
  ASSERT_TRUE(WIFEXITED(f.status)) << f.err;
  EXPECT_EQ(WEXITSTATUS(f.status), 0) << f.err;
  ASSERT_EQ(answers.size(), 5u) << f.err;
  EXPECT_EQ(answers[0].second, 200);
  for (std::size_t i = 1; i < answers.size(); ++i) {
    EXPECT_NE(answers[i].second, 200) << answers[i].first;
    EXPECT_NE(answers[i].second, -1) << answers[i].first << " handed out a file outside the run";
  }
  EXPECT_EQ(state["trajectory"].size(), 2u);
  EXPECT_EQ(state["files"], nlohmann::json::array({"overlays/1.png"}));
}

// ---------------------------------------------------------------- a real browser

std::string chromium() {
  for (const char* name : {"/usr/bin/chromium", "/usr/bin/chromium-browser", "/usr/bin/google-chrome"})
    if (fs::exists(name)) return name;
  return {};
}

struct BrowserResult {
  std::string dom, log;
};

// Loads `url` in headless Chromium (software WebGL) and returns the DOM after the page ran, with the browser's
// log (console messages).
BrowserResult loadInBrowser(const std::string& browser, const std::string& url, const fs::path& scratch,
                            const std::string& tag) {
  const fs::path dom = scratch / (tag + ".dom.html"), log = scratch / (tag + ".log");
  const std::string command = "timeout 120 " + browser +
                              " --headless=new --no-sandbox --use-gl=angle --use-angle=swiftshader --enable-unsafe-swiftshader"
                              " --user-data-dir=" + (scratch / "profile").string() +
                              " --enable-logging=stderr --v=0 --timeout=20000 --window-size=1200,800 --dump-dom '" +
                              url + "' > " + dom.string() + " 2> " + log.string();
  std::system(command.c_str());
  return {readFile(dom), readFile(log)};
}

// Console messages other than the software renderer's performance notes.
std::vector<std::string> consoleMessages(const std::string& log) {
  std::vector<std::string> out;
  std::istringstream lines(log);
  for (std::string line; std::getline(lines, line);)
    if (viewerContains(line, "CONSOLE") && !viewerContains(line, "GL Driver Message")) out.push_back(line);
  return out;
}

void expectDrawnWithoutErrors(const BrowserResult& r, const std::string& what) {
  EXPECT_TRUE(viewerContains(r.dom, "data-drawn=\"1\"")) << what << " did not draw; DOM:\n"
                                                   << r.dom.substr(0, 2000) << "\nlog:\n" << r.log;
  EXPECT_FALSE(viewerContains(r.dom, "data-errors")) << what << ":\n" << r.dom.substr(0, 2000);
  EXPECT_FALSE(viewerContains(r.log, "Uncaught")) << what << ":\n" << r.log;
  for (const std::string& m : consoleMessages(r.log)) ADD_FAILURE() << what << " console: " << m;
}

TEST(Browser, LivePageDrawsTheRunAndReportHtmlLoads) {
  const std::string browser = chromium();
  if (browser.empty()) GTEST_SKIP() << "chromium is not installed (scripts/install_deps.sh installs it)";
  const fs::path out = viewerOutputDir("browser");
  const fs::path scratch = viewerOutputDir("browser_scratch");
  fs::create_directories(scratch);
  int port = 0;
  std::optional<BrowserResult> live;
  const Finished f = runChild(viewerRunArgs(out), out.string() + ".stdout", [&](const std::string& line, pid_t pid) {
    if (const auto p = viewerPort(line)) port = *p;
    // The page is opened while the run goes (frame 20 of 120) and follows it.
    if (port > 0 && !live && progressFrame(line) >= 20)
      live = loadInBrowser(browser, "http://127.0.0.1:" + std::to_string(port) + "/", scratch, "live");
    if (viewerContains(line, "still serving")) kill(pid, SIGTERM);
  });
  ASSERT_TRUE(WIFEXITED(f.status)) << f.err;
  ASSERT_TRUE(live) << f.err;
  expectDrawnWithoutErrors(*live, "the live page");
  EXPECT_TRUE(viewerContains(live->dom, "frames per second")) << live->dom.substr(0, 2000);
  ASSERT_TRUE(fs::exists(out / "report.html"));
  expectDrawnWithoutErrors(loadInBrowser(browser, "file://" + (out / "report.html").string(), scratch, "report"),
                           "report.html");
}

}  // namespace
}  // namespace amos::app
#endif  // AMOS_HAVE_VIEWER
