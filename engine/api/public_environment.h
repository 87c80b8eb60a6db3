// The public Environment's insides (include/quadra/environment.hpp): the
// engine image it holds, shared by its copies, for the public Renderer to
// light with; never installed.
#pragma once

#include <cstdint>
#include <memory>
#include <utility>

#include "quadra/environment.hpp"
#include "shading/environment_image.h"

namespace quadra::api {

struct Environment::Impl {
  // One object per Environment made: the Renderer keeps its preparation
  // while frames ask for this same pointer.
  std::shared_ptr<const EnvironmentImage> image;
  std::uint64_t repaired = 0;  // values the texel rule changed
};

namespace detail {
struct EnvironmentAccess {
  static Environment make(EnvironmentImage image, std::uint64_t repaired) {
    auto impl = std::make_shared<Environment::Impl>();
    impl->image = std::make_shared<const EnvironmentImage>(std::move(image));
    impl->repaired = repaired;
    return Environment(std::move(impl));
  }
  static const std::shared_ptr<const EnvironmentImage>& image(const Environment& environment) {
    return environment.impl_->image;
  }
};
}  // namespace detail

}  // namespace quadra::api
