#include "amos/viewer/live_state.h"

#include <gtest/gtest.h>

#include <thread>

namespace amos::viewer {
namespace {

LiveUpdate pointUpdate(std::uint64_t id) {
  LiveUpdate u;
  u.map.points.push_back({id, Eigen::Vector3f(1, 2, 3), 0});
  u.trajectory.push_back({0.1 * id, Eigen::Vector3f(0, 0, 0.01f * id)});
  return u;
}

TEST(LiveState, StateHoldsTheAccumulatedUpdates) {
  LiveState state;
  state.apply(pointUpdate(1));
  state.apply(pointUpdate(2));
  LiveUpdate removal;
  removal.map.removed.push_back(1);
  removal.map.culled.push_back({1, Eigen::Vector3f(1, 2, 3), 5});
  state.apply(removal);
  const nlohmann::json s = state.stateJson();
  EXPECT_EQ(s["seq"], 3);
  ASSERT_EQ(s["points"].size(), 1u);
  EXPECT_EQ(s["points"][0][0], 2);
  EXPECT_EQ(s["culled"].size(), 1u);
  EXPECT_EQ(s["trajectory"].size(), 2u);
}

TEST(LiveState, EventsAfterASeqAreTheLaterUpdates) {
  LiveState state;
  for (std::uint64_t i = 1; i <= 3; ++i) state.apply(pointUpdate(i));
  const EventBatch batch = state.eventsAfter(1, std::chrono::milliseconds(0));
  ASSERT_EQ(batch.events.size(), 2u);
  EXPECT_EQ(batch.events[0].first, 2u);
  const nlohmann::json e = nlohmann::json::parse(batch.events[1].second);
  EXPECT_EQ(e["seq"], 3);
  EXPECT_EQ(e["points"][0][0], 3);
  EXPECT_FALSE(batch.reload);
}

TEST(LiveState, ABrowserTooFarBehindIsToldToReload) {
  LiveState state(4);
  for (std::uint64_t i = 1; i <= 10; ++i) state.apply(pointUpdate(i));
  EXPECT_TRUE(state.eventsAfter(2, std::chrono::milliseconds(0)).reload);
  EXPECT_EQ(state.eventsAfter(6, std::chrono::milliseconds(0)).events.size(), 4u);
  // A seq from another run (the server restarted): reload too.
  EXPECT_TRUE(state.eventsAfter(99, std::chrono::milliseconds(0)).reload);
}

TEST(LiveState, WaitingStreamWakesForAnUpdateAndEndsWhenClosed) {
  LiveState state;
  std::thread writer([&] { state.apply(pointUpdate(1)); });
  const EventBatch batch = state.eventsAfter(0, std::chrono::seconds(10));
  writer.join();
  EXPECT_EQ(batch.events.size(), 1u);
  std::thread closer([&] { state.close(); });
  const EventBatch closed = state.eventsAfter(1, std::chrono::seconds(10));
  closer.join();
  EXPECT_TRUE(closed.closed);
}

TEST(LiveState, ADenseLayerIsAnEventAndReplacesItsOlderVersion) {
  LiveState state;
  ColouredGeometry cloud;
  cloud.xyz = {0, 0, 1, 1, 0, 1};
  cloud.rgb = {255, 0, 0, 0, 255, 0};
  state.setDenseLayer("live", cloud);
  cloud.xyz.resize(3);
  cloud.rgb.resize(3);
  state.setDenseLayer("live", cloud);
  const EventBatch batch = state.eventsAfter(0, std::chrono::milliseconds(0));
  ASSERT_EQ(batch.events.size(), 2u);
  const nlohmann::json last = nlohmann::json::parse(batch.events[1].second);
  EXPECT_EQ(last["dense"]["live"]["vertices"], 1);
  const nlohmann::json s = state.stateJson();
  EXPECT_EQ(s["dense"]["live"]["version"], last["dense"]["live"]["version"]);
  EXPECT_GT(s["dense"]["live"]["version"].get<int>(), nlohmann::json::parse(batch.events[0].second)["dense"]["live"]["version"].get<int>());
  ASSERT_NE(state.denseLayer("live"), nullptr);
  EXPECT_EQ(state.denseLayer("live")->size(), 8u + 15);
  EXPECT_EQ(state.denseLayer("mesh"), nullptr);
}

}  // namespace
}  // namespace amos::viewer
