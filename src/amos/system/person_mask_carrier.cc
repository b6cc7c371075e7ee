#include "amos/system/person_mask_carrier.h"

#include <string>
#include <utility>

#include "amos/core/error.h"

namespace amos::system {

PersonMaskCarrier::PersonMaskCarrier(segmentation::MaskDilationOptions dilation,
                                     dynamic::PriorScheduleOptions schedule)
    : dilation_(std::move(dilation)), schedule_(schedule) {
  schedule_.check();
}

PersonMaskCarrier::Masks PersonMaskCarrier::masksFor(FrameNumber number,
                                                     const segmentation::SegmentationResult& base_result,
                                                     dynamic::FrameFlow flow) {
  const FrameNumber base = schedule_.baseFor(number);
  if (startsFrom(base)) {
    if (!propagator_) propagator_.emplace(base_result.mask.size(), dilation_, schedule_);
    propagator_->reset(base_result.instances);
    base_ = base;
    for (const auto& [k, old_flow] : flows_)  // a segmentation `lag` frames old: carried over the frames since
      if (k > base && k < number) propagator_->step(old_flow);
  }
  if (number > base) propagator_->step(flow);
  remember(number, std::move(flow));
  if (number == base) return {base_result.mask, base_result.dilated_mask};  // exactly what the network gave
  return {propagator_->mask(), propagator_->dilatedMask()};
}

PersonMaskCarrier::Masks PersonMaskCarrier::carryOn(FrameNumber number, dynamic::FrameFlow flow) {
  core::require(canCarry(number), "PersonMaskCarrier::carryOn: frame " + std::to_string(number) +
                                      " is too far from the last segmentation taken (frame " + std::to_string(base_) +
                                      ")");
  propagator_->step(flow);
  remember(number, std::move(flow));
  return {propagator_->mask(), propagator_->dilatedMask()};
}

void PersonMaskCarrier::remember(FrameNumber number, dynamic::FrameFlow flow) {
  flows_.emplace_back(number, std::move(flow));
  // Enough for a segmentation taken as late as canCarry() allows.
  const auto keep = static_cast<std::size_t>(maxAge());
  while (flows_.size() > keep) flows_.pop_front();
}

}  // namespace amos::system
