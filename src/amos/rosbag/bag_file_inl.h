#pragma once
// instantiateOrThrow's definition (a template over the message type).
#include <fmt/format.h>
#include <ros/message_traits.h>

#include "amos/core/error.h"

namespace amos::rosbag {

template <typename T>
boost::shared_ptr<T> instantiateOrThrow(const ::rosbag::MessageInstance& m, const std::string& bag) {
  boost::shared_ptr<T> message = m.instantiate<T>();
  core::require(message != nullptr,
                fmt::format("bag '{}': topic '{}' holds {} messages; expected {}", bag, m.getTopic(), m.getDataType(),
                            ros::message_traits::DataType<T>::value()));
  return message;
}

}  // namespace amos::rosbag
