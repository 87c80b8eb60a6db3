// The public Environment (include/quadra/environment.hpp): the engine's
// EnvironmentImage behind a shared pointer, made by the rules --env applies
// (shading/environment_source.h), so that the Renderer's cache of its
// preparation (api/renderer.h RenderSettings::environment) sees one image
// for all the copies the embedder passes around.
#include <memory>
#include <string>
#include <utility>

#include "api/public_environment.h"
#include "core/error.h"
#include "core/memory_budget.h"
#include "shading/environment_source.h"

namespace quadra::api {

namespace {

// The engine's errors as the public type (its messages already name the
// source); a failed internal check as in the public Renderer.
template <typename Body>
auto publicErrors(Body&& body) {
  try {
    return body();
  } catch (const quadra::Error& error) {
    throw Error(error.what());
  } catch (const std::logic_error& error) {
    throw Error(std::string("quadra: ") + error.what());
  }
}

}  // namespace

Environment::Environment(std::shared_ptr<const Impl> impl) : impl_(std::move(impl)) {}

Environment Environment::fromTexels(std::span<const float> rgb, int width, int height) {
  constexpr const char* kName = "environment texels";
  return publicErrors([&] {
    checkEnvironmentSize(kName, width, height);
    const std::size_t values = std::size_t(width) * std::size_t(height) * 3;
    if (rgb.size() != values)
      throw Error(std::string(kName) + ": " + std::to_string(rgb.size()) + " floats given, " +
                  std::to_string(width) + "x" + std::to_string(height) + " texels need " +
                  std::to_string(values));
    EnvironmentImage image;
    image.name = "texels";
    image.width = width;
    image.height = height;
    image.rgb.assign(rgb.begin(), rgb.end());
    const TexelRepairs repairs = applyTexelRule(image.rgb.data(), image.rgb.size());
    return detail::EnvironmentAccess::make(std::move(image), repairs.total());
  });
}

Environment Environment::load(const std::string& source, std::uint64_t maxMemory) {
  return publicErrors([&] {
    MemoryBudget budget(maxMemory, source);
    TexelRepairs repairs;
    EnvironmentImage image = loadEnvironment(source, budget, &repairs);
    return detail::EnvironmentAccess::make(std::move(image), repairs.total());
  });
}

int Environment::width() const {
  return impl_->image->width;
}
int Environment::height() const {
  return impl_->image->height;
}
const std::string& Environment::name() const {
  return impl_->image->name;
}
std::span<const float> Environment::texels() const {
  return impl_->image->rgb;
}
std::uint64_t Environment::repairedValues() const {
  return impl_->repaired;
}

}  // namespace quadra::api
