#pragma once
// Settings sections that config does not know: sections of modules it must not include (the dense map's, whose
// module stands below config and is built only with Open3D). Whoever reads the settings (the program: run's
// settings_sections.h; a library user) makes a SectionRegistry naming each such section's option struct and the
// function that lists its keys, and hands it to loadSettings; the Settings read then hold one value of each
// (Settings::section<Options>()), read, checked, reported by key and written like the built-in sections. The
// registry is a plain value made where it is used: nothing is registered globally.
#include <any>
#include <functional>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include "amos/config/key_list.h"
#include "amos/core/camera.h"

namespace amos::config {

// One added section: its options held by value (Settings stays a copyable value), the function that binds its keys
// to the options held, and the options' own check().
struct AddedSection {
  std::string title;
  std::any options;
  std::function<void(std::any& options, KeySection& section)> list_keys;
  // The options' checkFor(camera) when they have one (bounds that depend on the image), else their check().
  std::function<void(const std::any& options, const core::CameraIntrinsics& camera)> check;

  KeySection keys();
};

template <typename Options, typename = void>
struct HasCheckFor : std::false_type {};
template <typename Options>
struct HasCheckFor<Options, std::void_t<decltype(std::declval<const Options&>().checkFor(
                                std::declval<const core::CameraIntrinsics&>()))>> : std::true_type {};

class SectionRegistry {
 public:
  // Options: copyable, default-constructible with its defaults, with `void check() const` throwing
  // core::InvalidOption (or `void checkFor(const core::CameraIntrinsics&) const`, given the settings' camera).
  // list_keys(options, section) adds the section's keys (section.add(name, &options.member, meaning)). Adding the
  // same Options twice throws core::Error.
  template <typename Options>
  SectionRegistry& add(std::string title, void (*list_keys)(Options&, KeySection&)) {
    requireNew(typeid(Options).name());
    sections_.push_back(AddedSection{
        std::move(title), Options{},
        [list_keys](std::any& options, KeySection& section) { list_keys(*std::any_cast<Options>(&options), section); },
        [](const std::any& any, const core::CameraIntrinsics& camera) {
          const auto& options = std::any_cast<const Options&>(any);
          if constexpr (HasCheckFor<Options>::value) {
            options.checkFor(camera);
          } else {
            options.check();
          }
        }});
    return *this;
  }

  // The sections with their options at their defaults.
  const std::vector<AddedSection>& sections() const { return sections_; }

 private:
  void requireNew(const char* type_name) const;

  std::vector<AddedSection> sections_;
};

}  // namespace amos::config
