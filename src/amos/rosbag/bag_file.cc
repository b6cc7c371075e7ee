#include "amos/rosbag/bag_file.h"

#include <fmt/format.h>

#include <algorithm>

#include "amos/core/error.h"

namespace amos::rosbag {

void openBag(::rosbag::Bag& reader, const std::string& bag) {
  try {
    reader.open(bag, ::rosbag::bagmode::Read);
  } catch (const ::rosbag::BagException& e) {
    throw core::Error(fmt::format("bag '{}' cannot be read: {}", bag, e.what()));
  }
}

std::vector<std::string> topicsOf(const ::rosbag::Bag& reader) {
  std::vector<std::string> topics;
  ::rosbag::View all(reader);
  for (const ::rosbag::ConnectionInfo* c : all.getConnections()) topics.push_back(c->topic);
  std::sort(topics.begin(), topics.end());
  topics.erase(std::unique(topics.begin(), topics.end()), topics.end());
  return topics;
}

void forEachMessage(const ::rosbag::Bag& reader, const std::string& bag, const std::string& topic,
                    const std::function<bool(const ::rosbag::MessageInstance&, std::size_t)>& visit) {
  try {
    ::rosbag::View view(reader, ::rosbag::TopicQuery(topic));
    std::size_t position = 0;
    for (const ::rosbag::MessageInstance& m : view) {
      if (!visit(m, position++)) return;
    }
  } catch (const ::rosbag::BagException& e) {
    throw core::Error(fmt::format("bag '{}', topic '{}': {}", bag, topic, e.what()));
  } catch (const ros::Exception& e) {  // a message that does not deserialise (a damaged chunk)
    throw core::Error(fmt::format("bag '{}', topic '{}': {}", bag, topic, e.what()));
  }
}

}  // namespace amos::rosbag
