#pragma once
// Opening a bag and walking one topic's messages with the bag named in every error (rosbag's own exceptions name
// neither the file nor the topic).
#include <rosbag/bag.h>
#include <rosbag/view.h>

#include <cstddef>
#include <functional>
#include <string>
#include <vector>

namespace amos::rosbag {

// Opens `bag` for reading; throws core::Error "bag '<bag>' cannot be read: <reason>" (missing, not a bag, truncated
// or unindexed, an unknown compression).
void openBag(::rosbag::Bag& reader, const std::string& bag);
// The topics of the bag's connections, sorted.
std::vector<std::string> topicsOf(const ::rosbag::Bag& reader);

// Calls `visit(message, position)` for each message on `topic` in bag order until it returns false. A rosbag error
// while reading (a damaged chunk) is rethrown as core::Error naming the bag and the topic.
void forEachMessage(const ::rosbag::Bag& reader, const std::string& bag, const std::string& topic,
                    const std::function<bool(const ::rosbag::MessageInstance&, std::size_t)>& visit);

// The message as T, or core::Error naming the bag, the topic and the type the message has.
template <typename T>
boost::shared_ptr<T> instantiateOrThrow(const ::rosbag::MessageInstance& m, const std::string& bag);

}  // namespace amos::rosbag

#include "amos/rosbag/bag_file_inl.h"
