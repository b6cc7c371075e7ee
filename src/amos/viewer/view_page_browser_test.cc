// The view page of a finished run in a real browser (headless Chromium, software WebGL): a run folder with the
// dense products (test_run_folder.h) is served by the viewer's server in this process, and a harness page of the
// same origin (written into the run folder, served under /files/) opens the view page in an iframe and uses it as
// a user does: it waits until the page has drawn and loaded its dense layers, then looks at the pixels of the 3D
// view (the trajectory's green, the removed points' magenta), clicks the layer toggles, zooms with the wheel and
// presses F, then T. It reports what it saw as JSON in its DOM, which --dump-dom hands back. Also the live page
// with a dense cloud from the publisher, and report.html with an occupancy grid, opened from disk.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <sstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "amos/testing/scratch_dir.h"
#include "amos/viewer/http_server.h"
#include "amos/viewer/live_state.h"
#include "amos/viewer/run_folder.h"
#include "amos/viewer/snapshot_publisher.h"
#include "amos/report/run_report.h"
#include "amos/viewer/test_run_folder.h"
#include "amos/core/whole_file.h"

namespace amos::viewer {
namespace {

namespace fs = std::filesystem;

std::string chromium() {
  for (const char* name : {"/usr/bin/chromium", "/usr/bin/chromium-browser", "/usr/bin/google-chrome"})
    if (fs::exists(name)) return name;
  return {};
}

bool contains(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

struct Page {
  std::string dom, log;
};

// Loads `url` in headless Chromium and returns the DOM once the page's timers have run (virtual time: waiting in
// the page costs no real time beyond the work; animation frames hardly come) with the browser's log.
Page loadInBrowser(const std::string& url, const fs::path& scratch, const std::string& tag) {
  const fs::path dom = scratch / (tag + ".dom.html"), log = scratch / (tag + ".log");
  const std::string command = "timeout 120 " + chromium() +
                              " --headless=new --no-sandbox --use-gl=angle --use-angle=swiftshader"
                              " --enable-unsafe-swiftshader --user-data-dir=" + (scratch / "profile").string() +
                              " --enable-logging=stderr --v=0 --virtual-time-budget=30000 --window-size=1200,800"
                              " --dump-dom '" + url + "' > " + dom.string() + " 2> " + log.string();
  std::system(command.c_str());
  return {core::readWholeFile(dom).value_or(std::string()), core::readWholeFile(log).value_or(std::string())};
}

std::vector<std::string> consoleMessages(const std::string& log) {
  std::vector<std::string> out;
  std::istringstream lines(log);
  for (std::string line; std::getline(lines, line);)
    if (contains(line, "CONSOLE") && !contains(line, "GL Driver Message")) out.push_back(line);
  return out;
}

// The JSON the harness left in <pre id="result">.
nlohmann::json harnessResult(const std::string& dom) {
  const std::string open = "<pre id=\"result\">";
  const std::size_t begin = dom.find(open);
  if (begin == std::string::npos) return nullptr;
  const std::size_t end = dom.find("</pre>", begin);
  return nlohmann::json::parse(dom.substr(begin + open.size(), end - begin - open.size()), nullptr, false);
}

// The harness: the view page in an 900 x 600 iframe; the steps described at the top of this file.
constexpr char kHarness[] = R"HTML(<!doctype html>
<html><body>
<iframe id="view" src="/?nofollow" width="900" height="600"></iframe>
<pre id="result"></pre>
<script>
'use strict';
const sleep = (ms) => new Promise((r) => setTimeout(r, ms));
const frame = () => document.getElementById('view');
const doc = () => frame().contentDocument;
// Pixels of the 3D view by colour: the trajectory's green (#40d060), the removed points' magenta (#ff40ff), and
// anything that is not the background; with the boxes of the green ones and of all drawn ones as shares of the
// canvas.
function look() {
  const gl = doc().getElementById('canvas3d');
  const c = document.createElement('canvas');
  c.width = gl.width; c.height = gl.height;
  const ctx = c.getContext('2d');
  ctx.drawImage(gl, 0, 0);
  const px = ctx.getImageData(0, 0, c.width, c.height).data;
  const near = (i, r, g, b, tol) => Math.abs(px[i] - r) + Math.abs(px[i + 1] - g) + Math.abs(px[i + 2] - b) < tol;
  let green = 0, magenta = 0, drawn = 0, x0 = 1e9, x1 = -1, y0 = 1e9, y1 = -1, dx0 = 1e9, dx1 = -1, dy0 = 1e9, dy1 = -1;
  for (let y = 0; y < c.height; y++) for (let x = 0; x < c.width; x++) {
    const i = 4 * (y * c.width + x);
    if (!near(i, 0x15, 0x18, 0x1d, 30)) {
      drawn++; dx0 = Math.min(dx0, x); dx1 = Math.max(dx1, x); dy0 = Math.min(dy0, y); dy1 = Math.max(dy1, y);
    }
    if (near(i, 0xff, 0x40, 0xff, 60)) magenta++;
    if (near(i, 0x40, 0xd0, 0x60, 60)) {
      green++; x0 = Math.min(x0, x); x1 = Math.max(x1, x); y0 = Math.min(y0, y); y1 = Math.max(y1, y);
    }
  }
  return {green, magenta, drawn, width: c.width, height: c.height,
          drawn_w: drawn ? (dx1 - dx0 + 1) / c.width : 0, drawn_h: drawn ? (dy1 - dy0 + 1) / c.height : 0,
          traj_w: green ? (x1 - x0 + 1) / c.width : 0, traj_h: green ? (y1 - y0 + 1) / c.height : 0};
}
// The page draws at once on input (animation frames are rare under the browser's virtual time).
const settle = () => sleep(200);
async function click(id) { doc().getElementById(id).click(); await settle(); }
async function main() {
  const out = {};
  for (let i = 0; i < 300; i++) {
    const b = doc() && doc().body;
    if (b && b.dataset.drawn === '1' && b.dataset.dense === 'cloud,mesh,removed') break;
    await sleep(100);
  }
  const body = doc().body;
  out.drawn = body.dataset.drawn || '';
  out.dense = body.dataset.dense || '';
  out.errors = body.dataset.errors || '';
  await settle();
  out.fitted = look();
  await click('show-removed'); out.removed_off = look();
  await click('show-removed');
  await click('show-traj'); out.traj_off = look();
  await click('show-traj');
  await click('show-mesh'); await click('show-cloud'); await click('show-points'); out.dense_off = look();
  await click('show-mesh'); await click('show-cloud'); await click('show-points');
  out.dense_on = look();
  const canvas = doc().getElementById('canvas3d');
  for (let i = 0; i < 5; i++) canvas.dispatchEvent(new WheelEvent('wheel', {deltaY: 300, bubbles: true, cancelable: true}));
  await settle(); out.zoomed_out = look();
  frame().contentWindow.dispatchEvent(new KeyboardEvent('keydown', {key: 'f', bubbles: true}));
  await settle(); out.refitted = look();
  frame().contentWindow.dispatchEvent(new KeyboardEvent('keydown', {key: 't', bubbles: true}));
  await settle(); out.trajectory_fit = look();
  out.topview_paths = doc().querySelectorAll('#topview path').length;
  out.side = doc().getElementById('side').textContent;
  out.errors_after = doc().body.dataset.errors || '';
  document.getElementById('result').textContent = JSON.stringify(out);
}
main().catch((e) => { document.getElementById('result').textContent = JSON.stringify({harness_error: String(e)}); });
</script>
</body></html>
)HTML";

TEST(ViewPageBrowser, FitsTheRunShowsDenseLayersAndTogglesThem) {
  if (chromium().empty()) GTEST_SKIP() << "chromium is not installed (scripts/install_deps.sh installs it)";
  const fs::path scratch = amos::testing::scratchDirForThisTest("viewer_browser_");
  const fs::path run = scratch / "run";
  test::writeRunFolder(run, true);
  test::writeText(run / "harness.html", kHarness);
  LiveState state;
  loadRunFolder(run, state);
  ServerOptions options;
  options.port = 0;
  options.run_folder = run;
  ViewerServer server(state, options);
  const Page page = loadInBrowser(server.url() + "files/harness.html", scratch, "view");
  const nlohmann::json r = harnessResult(page.dom);
  ASSERT_TRUE(r.is_object()) << page.dom.substr(0, 3000) << "\nlog:\n" << page.log;
  ASSERT_FALSE(r.contains("harness_error")) << r.dump();
  EXPECT_EQ(r["drawn"], "1") << r.dump();
  EXPECT_EQ(r["dense"], "cloud,mesh,removed") << r.dump();
  EXPECT_EQ(r["errors"], "") << r.dump();
  EXPECT_EQ(r["errors_after"], "") << r.dump();
  // The fit: the scene (a 2.4 m floor with a wall, the map around it, a trajectory on a 2 m circle; the map also
  // has outliers 100 m away, which would make it a dot if they counted) fills the canvas in one direction, and the
  // trajectory spans a large part of it (with no fit, or one that took in the outliers, a few per cent).
  const nlohmann::json& fitted = r["fitted"];
  EXPECT_GT(std::max(fitted["drawn_w"].get<double>(), fitted["drawn_h"].get<double>()), 0.85) << fitted.dump();
  EXPECT_GT(std::max(fitted["traj_w"].get<double>(), fitted["traj_h"].get<double>()), 0.4) << fitted.dump();
  EXPECT_GT(fitted["magenta"].get<int>(), 50) << fitted.dump();
  // Each toggle hides its layer, and showing it again brings it back.
  EXPECT_EQ(r["removed_off"]["magenta"], 0) << r["removed_off"].dump();
  EXPECT_EQ(r["traj_off"]["green"], 0) << r["traj_off"].dump();
  EXPECT_LT(r["dense_off"]["drawn"].get<int>(), fitted["drawn"].get<int>() / 2) << r["dense_off"].dump();
  EXPECT_NEAR(r["dense_on"]["drawn"].get<double>(), fitted["drawn"].get<double>(), 0.02 * fitted["drawn"].get<double>());
  // Zooming out shrinks the trajectory; F fits it again.
  EXPECT_LT(r["zoomed_out"]["traj_w"].get<double>(), 0.8 * fitted["traj_w"].get<double>()) << r.dump();
  EXPECT_NEAR(r["refitted"]["traj_w"].get<double>(), fitted["traj_w"].get<double>(), 0.03) << r.dump();
  // T fits the trajectory alone: it then fills the canvas in one direction.
  const nlohmann::json& t = r["trajectory_fit"];
  EXPECT_GT(std::max(t["traj_w"].get<double>(), t["traj_h"].get<double>()), 0.7) << t.dump();
  EXPECT_EQ(r["topview_paths"], 2) << r.dump();  // the side panel's top view: estimate and ground truth
  // The side panel: the finished run's stage times (stats.json) and the ground truth.
  const std::string side = r["side"];
  EXPECT_TRUE(contains(side, "median / 95th percentile over the run")) << side;
  EXPECT_TRUE(contains(side, "12.5 / 20.0")) << side;
  EXPECT_TRUE(contains(side, "60 poses")) << side;  // ground truth
  EXPECT_TRUE(contains(side, "dense mesh vertices")) << side;
  for (const std::string& m : consoleMessages(page.log)) ADD_FAILURE() << "console: " << m;
}

// The live page with a dense cloud handed to the publisher (as `run --dense` does): the page fetches and draws it.
TEST(ViewPageBrowser, TheLivePageDrawsTheDenseCloud) {
  if (chromium().empty()) GTEST_SKIP() << "chromium is not installed (scripts/install_deps.sh installs it)";
  const fs::path scratch = amos::testing::scratchDirForThisTest("viewer_browser_");
  LiveState state;
  SnapshotPublisher publisher(state);
  run::RunStart start;
  start.total_frames = 10;
  start.mode = "full";
  publisher.onStart(start);
  const ColouredGeometry cloud = test::gridCloud(-1, 1, 1, 3, 0.5f, 2500, 200, 150, 90);
  publisher.publishDenseCloud(cloud.xyz, cloud.rgb);
  publisher.onEnd({}, report::RunInfo{});
  ServerOptions options;
  options.port = 0;
  ViewerServer server(state, options);
  const Page page = loadInBrowser(server.url() + "?nofollow", scratch, "live");
  EXPECT_TRUE(contains(page.dom, "data-dense=\"live\"")) << page.dom.substr(0, 3000) << "\nlog:\n" << page.log;
  EXPECT_TRUE(contains(page.dom, "data-drawn=\"1\"")) << page.dom.substr(0, 3000);
  EXPECT_TRUE(contains(page.dom, "dense cloud points")) << page.dom.substr(0, 3000);
  EXPECT_FALSE(contains(page.dom, "data-errors")) << page.dom.substr(0, 3000);
  for (const std::string& m : consoleMessages(page.log)) ADD_FAILURE() << "console: " << m;
}

TEST(ViewPageBrowser, ReportHtmlDrawsTheOccupancyGrid) {
  if (chromium().empty()) GTEST_SKIP() << "chromium is not installed (scripts/install_deps.sh installs it)";
  const fs::path scratch = amos::testing::scratchDirForThisTest("viewer_browser_");
  test::writeOccupancy(scratch, 48, 40, 0.05);
  nlohmann::json data = {{"stats", nlohmann::json::object()},
                         {"frames", {{"index", {0, 1}}, {"t", {0.0, 0.1}}, {"frame_ms", {30, 31}}, {"extract_ms", {5, 5}},
                                     {"build_ms", {6, 6}}, {"track_ms", {7, 7}}, {"removed_fraction", {0.1, 0.2}}}},
                         {"trajectory", {{0.0, 0, 0, 0}, {0.1, 0.1, 0, 0}}}};
  addDenseProducts(scratch, data);
  test::writeText(scratch / "report.html", reportHtml(data));
  const Page page = loadInBrowser("file://" + (scratch / "report.html").string(), scratch, "report");
  EXPECT_TRUE(contains(page.dom, "data-occupancy=\"1\"")) << page.dom.substr(0, 3000) << "\nlog:\n" << page.log;
  EXPECT_TRUE(contains(page.dom, "id=\"occupancy-scale\"")) << page.dom.substr(0, 3000);
  EXPECT_TRUE(contains(page.dom, "48 x 40 cells of 5.0 cm")) << page.dom.substr(0, 3000);
  EXPECT_FALSE(contains(page.dom, "data-errors")) << page.dom.substr(0, 3000);
  for (const std::string& m : consoleMessages(page.log)) ADD_FAILURE() << "console: " << m;
}

}  // namespace
}  // namespace amos::viewer
