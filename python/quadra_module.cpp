// The Python module `quadra` (issue 15 item 6): pybind11 bindings of the
// public C++ API (include/quadra/*.hpp) and nothing else, with numpy arrays
// in and out. Renders go straight into numpy-owned arrays through the public
// Target (RGBA32F), DepthTarget and AovTargets, with the GIL released. Errors: the
// public API's quadra::api::Error becomes quadra.Error (a RuntimeError) with
// the same one-line message; a wrong dtype, shape or option name is a
// ValueError naming the argument. Documented in docs/api.md "Python".
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <algorithm>
#include <array>
#include <cstring>
#include <mutex>
#include <optional>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "quadra/quadra.hpp"

namespace py = pybind11;
namespace api = quadra::api;

namespace {

[[noreturn]] void argumentError(const std::string& message) {
  throw py::value_error(message);
}

std::string dtypeName(const py::array& array) {
  return py::str(array.dtype()).cast<std::string>();
}

std::string shapeText(const py::array& array) {
  std::string text = "(";
  for (py::ssize_t axis = 0; axis < array.ndim(); ++axis)
    text += (axis ? ", " : "") + std::to_string(array.shape(axis));
  return text + (array.ndim() == 1 ? ",)" : ")");
}

// A C-contiguous float32 (N, columns) array, or a ValueError naming `name`.
// Only an array of another layout is copied (the Scene copies anyway).
py::array_t<float, py::array::c_style> vertexArray(const char* name, const py::array& array,
                                                   py::ssize_t columns) {
  if (!array.dtype().is(py::dtype::of<float>()))
    argumentError(std::string(name) + ": dtype " + dtypeName(array) + ", expected float32");
  if (array.ndim() != 2 || array.shape(1) != columns)
    argumentError(std::string(name) + ": shape " + shapeText(array) + ", expected (N, " +
                  std::to_string(columns) + ")");
  return py::array_t<float, py::array::c_style>::ensure(array);
}

std::span<const float> spanOf(const py::array_t<float, py::array::c_style>& array) {
  return {array.data(), std::size_t(array.size())};
}

// Optional attributes keep their arrays alive until addMesh has copied them.
struct MeshArrays {
  py::array_t<float, py::array::c_style> positions, normals, uvs, colors;
  py::array indices;
  api::MeshData data;
};

MeshArrays meshArrays(const py::array& positions, const py::array& indices,
                      const std::optional<py::array>& normals, const std::optional<py::array>& uvs,
                      const std::optional<py::array>& colors) {
  MeshArrays arrays;
  arrays.positions = vertexArray("positions", positions, 3);
  arrays.data.positions = spanOf(arrays.positions);
  if (normals) {
    arrays.normals = vertexArray("normals", *normals, 3);
    arrays.data.normals = spanOf(arrays.normals);
  }
  if (uvs) {
    arrays.uvs = vertexArray("uvs", *uvs, 2);
    arrays.data.uvs = spanOf(arrays.uvs);
  }
  if (colors) {
    arrays.colors = vertexArray("colors", *colors, 4);
    arrays.data.colors = spanOf(arrays.colors);
  }
  if (indices.ndim() != 1 && !(indices.ndim() == 2 && indices.shape(1) == 3))
    argumentError("indices: shape " + shapeText(indices) + ", expected (M,) or (M, 3)");
  if (indices.dtype().is(py::dtype::of<std::uint32_t>())) {
    auto packed = py::array_t<std::uint32_t, py::array::c_style>::ensure(indices);
    arrays.data.indices32 = {packed.data(), std::size_t(packed.size())};
    arrays.indices = std::move(packed);
  } else if (indices.dtype().is(py::dtype::of<std::uint16_t>())) {
    auto packed = py::array_t<std::uint16_t, py::array::c_style>::ensure(indices);
    arrays.data.indices16 = {packed.data(), std::size_t(packed.size())};
    arrays.indices = std::move(packed);
  } else {
    argumentError("indices: dtype " + dtypeName(indices) + ", expected uint16 or uint32");
  }
  return arrays;
}

// A (4, 4) float32 or float64 matrix as written in maths (m[row, column],
// the translation in m[:3, 3]) to the API's column-major Matrix4.
api::Matrix4 matrixOf(const char* name, const py::array& array) {
  if (array.ndim() != 2 || array.shape(0) != 4 || array.shape(1) != 4)
    argumentError(std::string(name) + ": shape " + shapeText(array) + ", expected (4, 4)");
  const bool isFloat32 = array.dtype().is(py::dtype::of<float>());
  if (!isFloat32 && !array.dtype().is(py::dtype::of<double>()))
    argumentError(std::string(name) + ": dtype " + dtypeName(array) +
                  ", expected float32 or float64");
  const auto values = py::array_t<double, py::array::c_style>::ensure(array);
  api::Matrix4 matrix{};
  for (int row = 0; row < 4; ++row)
    for (int column = 0; column < 4; ++column)
      matrix[std::size_t(column * 4 + row)] = float(values.at(row, column));
  return matrix;
}

py::array_t<float> arrayOf(const api::Matrix4& matrix) {
  py::array_t<float> array({4, 4});
  auto out = array.mutable_unchecked<2>();
  for (int row = 0; row < 4; ++row)
    for (int column = 0; column < 4; ++column)
      out(row, column) = matrix[std::size_t(column * 4 + row)];
  return array;
}

template <typename Enum>
Enum choiceOf(const char* name, const std::string& value,
              std::initializer_list<std::pair<const char*, Enum>> choices) {
  std::string names;
  for (const auto& [text, choice] : choices) {
    if (value == text) return choice;
    names += (names.empty() ? "" : ", ") + std::string(text);
  }
  argumentError(std::string(name) + ": '" + value + "' is not one of " + names);
}

// The Scene with a count of renders reading it: changing it during one (from
// another Python thread, the GIL being released) is refused, not a race.
// The count changes only with the GIL held, as every change of the scene
// happens, so a change sees every render that has begun.
struct PyScene {
  api::Scene scene;
  int renders = 0;

  api::Scene& forChange() {
    if (renders != 0) throw api::Error("scene: changed while a render reads it");
    return scene;
  }
};

// Counts one render of the scene for its lifetime (see PyScene).
class ReadingScene {
 public:
  explicit ReadingScene(PyScene& scene) : scene_(scene) { ++scene_.renders; }
  ~ReadingScene() { --scene_.renders; }
  ReadingScene(const ReadingScene&) = delete;
  ReadingScene& operator=(const ReadingScene&) = delete;

 private:
  PyScene& scene_;
};

struct PyCamera {
  api::CameraData data;
};

// An environment for shading="pbr": keeping one (instead of passing an array
// or a name to each render) keeps the renderer's preparation of it.
struct PyEnvironment {
  api::Environment environment;
};

// A C-contiguous float32 (H, W, 3) array of texels as an Environment (the
// API copies them), or a ValueError naming `name`.
api::Environment environmentOf(const char* name, const py::array& texels) {
  if (!texels.dtype().is(py::dtype::of<float>()))
    argumentError(std::string(name) + ": dtype " + dtypeName(texels) + ", expected float32");
  if (texels.ndim() != 3 || texels.shape(2) != 3)
    argumentError(std::string(name) + ": shape " + shapeText(texels) + ", expected (H, W, 3)");
  const auto packed = py::array_t<float, py::array::c_style>::ensure(texels);
  return api::Environment::fromTexels({packed.data(), std::size_t(packed.size())},
                                      int(texels.shape(1)), int(texels.shape(0)));
}

// render's env: None (the renderer's builtin:studio), an Environment, a
// source string (as --env) or a texel array.
std::optional<api::Environment> environmentArgument(const py::object& env) {
  if (env.is_none()) return std::nullopt;
  if (py::isinstance<PyEnvironment>(env)) return env.cast<const PyEnvironment&>().environment;
  if (py::isinstance<py::str>(env)) return api::Environment::load(env.cast<std::string>());
  if (py::isinstance<py::array>(env)) return environmentOf("env", env.cast<py::array>());
  argumentError(
      "env: expected an Environment, a file name or builtin:NAME, or an (H, W, 3) "
      "float32 array, got " +
      std::string(py::str(py::type::of(env).attr("__name__"))));
}

api::TextureData textureData(const py::array& texels, bool srgb, const std::string& wrapU,
                             const std::string& wrapV, const std::string& filter,
                             py::array& packed) {
  if (texels.ndim() != 3 || texels.shape(2) != 4)
    argumentError("texels: shape " + shapeText(texels) + ", expected (H, W, 4)");
  api::TextureData data;
  const auto& dtype = texels.dtype();
  if (dtype.is(py::dtype::of<std::uint8_t>()))
    data.format = srgb ? api::TextureFormat::Rgba8Srgb : api::TextureFormat::Rgba8Unorm;
  else if (dtype.kind() == 'f' && dtype.itemsize() == 2)
    data.format = api::TextureFormat::Rgba16F;
  else if (dtype.is(py::dtype::of<float>()))
    data.format = api::TextureFormat::Rgba32F;
  else
    argumentError("texels: dtype " + dtypeName(texels) + ", expected uint8, float16 or float32");
  packed = py::array::ensure(texels, py::array::c_style);
  data.height = int(texels.shape(0));
  data.width = int(texels.shape(1));
  data.texels = {static_cast<const std::byte*>(packed.data()), std::size_t(packed.nbytes())};
  const std::initializer_list<std::pair<const char*, api::Wrap>> wraps = {
      {"repeat", api::Wrap::Repeat},
      {"mirrored_repeat", api::Wrap::MirroredRepeat},
      {"clamp_to_edge", api::Wrap::ClampToEdge}};
  data.wrapU = choiceOf("wrap_u", wrapU, wraps);
  data.wrapV = choiceOf("wrap_v", wrapV, wraps);
  data.filter = choiceOf<api::Filter>("filter", filter,
                                      {{"nearest", api::Filter::Nearest},
                                       {"bilinear", api::Filter::Bilinear},
                                       {"trilinear", api::Filter::Trilinear},
                                       {"anisotropic", api::Filter::Anisotropic}});
  return data;
}

// One frame at a time per Renderer (renderer.hpp); the mutex makes two
// Python threads sharing one wait for each other instead of racing.
struct PyRenderer {
  explicit PyRenderer(const api::RendererOptions& options) : renderer(options) {}
  api::Renderer renderer;
  std::mutex busy;
};

struct RenderResult {
  py::object color = py::none();
  py::object depth = py::none();
  // The AOVs asked for (docs/cli.md "AOVs"), else None.
  py::object normal = py::none(), position = py::none(), uv = py::none(), mask = py::none();
  py::object primitiveId = py::none(), nodeId = py::none(), materialId = py::none();
};

// A new array of `shape`, or `previous` (the same field of an earlier
// RenderResult) when it is a C-contiguous writable array of this dtype and
// shape: a new 1080p frame's arrays cost the kernel zeroing 40 MB of fresh
// pages on first touch.
template <typename T>
py::array_t<T> outputArray(const std::optional<RenderResult>& out, py::object RenderResult::*field,
                           const std::vector<py::ssize_t>& shape) {
  if (out) {
    const py::object& previous = (*out).*field;
    if (py::isinstance<py::array>(previous)) {
      const auto a = previous.cast<py::array>();
      if (a.dtype().is(py::dtype::of<T>()) && a.writeable() && (a.flags() & py::array::c_style) &&
          a.ndim() == py::ssize_t(shape.size()) &&
          std::equal(shape.begin(), shape.end(), a.shape()))
        return previous.cast<py::array_t<T>>();
    }
  }
  return py::array_t<T>(shape);
}

// A contiguous array as the bytes of a target whose rows are width pixels.
template <typename T>
std::span<std::byte> bytesOf(py::array_t<T>& array) {
  return {reinterpret_cast<std::byte*>(array.mutable_data()), std::size_t(array.nbytes())};
}

// The AOV names of the CLI's --aov (docs/cli.md "AOVs") that the public API has.
enum class AovName { Normal, Position, Uv, Id, Mask };

// The AOVs `names` asks for: arrays in `result` (reused from `out` when they
// fit) and the API's targets over them.
api::AovTargets aovArrays(const std::vector<std::string>& names, int width, int height,
                          const std::optional<RenderResult>& out, RenderResult& result) {
  api::AovTargets targets;
  const std::size_t w = std::size_t(width);
  for (const std::string& name : names) {
    const AovName aov = choiceOf<AovName>("aovs", name,
                                          {{"N", AovName::Normal},
                                           {"P", AovName::Position},
                                           {"uv", AovName::Uv},
                                           {"id", AovName::Id},
                                           {"mask", AovName::Mask}});
    // One float plane of `channels` per pixel, its array in result.*field.
    const auto floats = [&](py::object RenderResult::*field, api::AovTarget& target,
                            py::ssize_t channels) {
      std::vector<py::ssize_t> shape{height, width};
      if (channels > 1) shape.push_back(channels);
      auto array = outputArray<float>(out, field, shape);
      target = {.bytes = bytesOf(array), .rowStride = w * std::size_t(channels) * 4};
      result.*field = std::move(array);
    };
    const auto ids = [&](py::object RenderResult::*field, api::AovTarget& target) {
      auto array = outputArray<std::uint32_t>(out, field, {height, width});
      target = {.bytes = bytesOf(array), .rowStride = w * 4};
      result.*field = std::move(array);
    };
    switch (aov) {
      case AovName::Normal:
        floats(&RenderResult::normal, targets.normal, 3);
        break;
      case AovName::Position:
        floats(&RenderResult::position, targets.position, 3);
        break;
      case AovName::Uv:
        floats(&RenderResult::uv, targets.uv, 2);
        break;
      case AovName::Mask:
        floats(&RenderResult::mask, targets.mask, 1);
        break;
      case AovName::Id:
        ids(&RenderResult::primitiveId, targets.primitiveId);
        ids(&RenderResult::nodeId, targets.nodeId);
        ids(&RenderResult::materialId, targets.materialId);
        break;
    }
  }
  return targets;
}

// render's lighting keywords, named as the CLI's options.
struct LightingArguments {
  py::object env;
  float envRotation, envIntensity;
  bool lights;
  std::string background;
  std::optional<std::array<float, 3>> backgroundColor;
  float exposure;
  std::optional<std::string> tonemap;
};

void applyLighting(const LightingArguments& a, api::RenderOptions& options) {
  options.environment = environmentArgument(a.env);
  options.environmentRotation = a.envRotation;
  options.environmentIntensity = a.envIntensity;
  options.punctualLights = a.lights;
  options.background = choiceOf<api::Background>("background", a.background,
                                                 {{"env", api::Background::Environment},
                                                  {"color", api::Background::Color},
                                                  {"transparent", api::Background::Transparent}});
  if (a.backgroundColor)
    options.clearColor = {(*a.backgroundColor)[0], (*a.backgroundColor)[1], (*a.backgroundColor)[2],
                          1.0f};
  options.exposure = a.exposure;
  if (a.tonemap)
    options.toneMap = choiceOf<api::ToneMap>("tonemap", *a.tonemap,
                                             {{"pbr-neutral", api::ToneMap::PbrNeutral},
                                              {"aces", api::ToneMap::Aces},
                                              {"none", api::ToneMap::None}});
}

RenderResult render(PyRenderer& self, PyScene& scene, int width, int height,
                    const std::optional<PyCamera>& camera, int samples, const std::string& shading,
                    const std::array<float, 4>& clearColor, bool depth,
                    const std::vector<std::string>& aovs, std::optional<std::uint64_t> maxMemory,
                    const std::optional<RenderResult>& out, const std::string& format,
                    const LightingArguments& lighting) {
  // Checked before the arrays are made (the public API's own check, with
  // its limit, comes after a possibly huge allocation).
  if (width < 1 || height < 1 || width > 8192 || height > 8192)
    argumentError("width, height: " + std::to_string(width) + "x" + std::to_string(height) +
                  " is not within 1..8192 pixels each way");
  api::RenderOptions options;
  options.samples = samples;
  options.clearColor = clearColor;
  if (maxMemory) options.maxMemory = *maxMemory;
  options.shading = choiceOf<api::Shading>(
      "shading", shading,
      {{"unlit", api::Shading::Unlit}, {"lit", api::Shading::Lit}, {"pbr", api::Shading::Pbr}});
  const api::PixelFormat pixelFormat = choiceOf<api::PixelFormat>(
      "format", format,
      {{"rgba32f", api::PixelFormat::Rgba32F}, {"rgba8srgb", api::PixelFormat::Rgba8Srgb}});
  applyLighting(lighting, options);
  RenderResult result;
  const api::AovTargets aovTargets = aovArrays(aovs, width, height, out, result);
  if (camera) scene.forChange().setCamera(camera->data);
  api::Target target{.width = width,
                     .height = height,
                     .rowStride = std::size_t(width) * api::bytesPerPixel(pixelFormat),
                     .format = pixelFormat};
  if (pixelFormat == api::PixelFormat::Rgba32F) {
    auto color = outputArray<float>(out, &RenderResult::color, {height, width, 4});
    target.pixels = bytesOf(color);
    result.color = std::move(color);
  } else {
    auto color = outputArray<std::uint8_t>(out, &RenderResult::color, {height, width, 4});
    target.pixels = bytesOf(color);
    result.color = std::move(color);
  }
  std::optional<api::DepthTarget> depthTarget;
  if (depth) {
    auto depthArray = outputArray<float>(out, &RenderResult::depth, {height, width});
    depthTarget =
        api::DepthTarget{.bytes = bytesOf(depthArray), .rowStride = std::size_t(width) * 4};
    result.depth = std::move(depthArray);
  }
  {
    const ReadingScene reading(scene);  // counted and uncounted with the GIL held
    py::gil_scoped_release released;
    std::lock_guard lock(self.busy);
    self.renderer.render(scene.scene, target, depthTarget ? &*depthTarget : nullptr, options,
                         &aovTargets);
  }
  return result;
}

}  // namespace

PYBIND11_MODULE(quadra, m) {
  m.doc() = "quadra, a CPU rasterizer: glTF or numpy scenes rendered into numpy arrays";
  m.attr("__version__") = quadra::version();
  py::register_exception<api::Error>(m, "Error", PyExc_RuntimeError);

  py::class_<PyCamera>(m, "Camera", "Looks down its own -Z with +Y up; `world` places it.")
      .def(py::init([](const std::string& projection, float yfov, float ymag, float znear,
                       float zfar, const std::optional<py::array>& world) {
             PyCamera camera;
             camera.data.projection = choiceOf<api::CameraData::Projection>(
                 "projection", projection,
                 {{"perspective", api::CameraData::Projection::Perspective},
                  {"orthographic", api::CameraData::Projection::Orthographic}});
             camera.data.yfov = yfov;
             camera.data.ymag = ymag;
             camera.data.znear = znear;
             camera.data.zfar = zfar;
             if (world) camera.data.world = matrixOf("world", *world);
             return camera;
           }),
           py::kw_only(), py::arg("projection") = "perspective", py::arg("yfov") = 0.8f,
           py::arg("ymag") = 1.0f, py::arg("znear") = 0.1f, py::arg("zfar") = 0.0f,
           py::arg("world") = py::none())
      .def_property_readonly("world", [](const PyCamera& c) { return arrayOf(c.data.world); });

  m.def(
      "look_at",
      [](const std::array<float, 3>& eye, const std::array<float, 3>& target,
         const std::array<float, 3>& up) { return arrayOf(api::lookAt(eye, target, up)); },
      py::arg("eye"), py::arg("target"), py::arg("up") = std::array<float, 3>{0, 1, 0},
      "Camera-to-world (4, 4) float32 matrix of a camera at eye looking at target.");

  py::class_<PyEnvironment>(
      m, "Environment",
      "The light of shading=\"pbr\": an equirectangular panorama of linear RGB radiance "
      "(docs/lighting.md \"Environments\"). Environment(texels): an (H, W, 3) float32 array, "
      "row 0 the top (+Y), the centre column facing -Z; Environment(source): builtin:NAME or a "
      ".hdr or .exr file, as the CLI's --env. Checked and repaired as --env is (NaN and "
      "negative values become 0). A renderer keeps its preparation of one Environment across "
      "renders.")
      .def(py::init([](const py::array& texels) {
             return PyEnvironment{environmentOf("texels", texels)};
           }),
           py::arg("texels"))
      .def(py::init([](const std::string& source, std::optional<std::uint64_t> maxMemory) {
             return PyEnvironment{
                 api::Environment::load(source, maxMemory.value_or(api::kDefaultMaxMemory))};
           }),
           py::arg("source"), py::kw_only(), py::arg("max_memory") = py::none())
      .def_property_readonly("width", [](const PyEnvironment& e) { return e.environment.width(); })
      .def_property_readonly("height",
                             [](const PyEnvironment& e) { return e.environment.height(); })
      .def_property_readonly("name", [](const PyEnvironment& e) { return e.environment.name(); })
      .def_property_readonly(
          "texels",
          [](const PyEnvironment& e) {
            const std::span<const float> texels = e.environment.texels();
            py::array_t<float> array({e.environment.height(), e.environment.width(), 3});
            std::memcpy(array.mutable_data(), texels.data(), texels.size_bytes());
            return array;
          },
          "(H, W, 3) float32 copy of the texels as quadra lights with them")
      .def_property_readonly(
          "repaired_values", [](const PyEnvironment& e) { return e.environment.repairedValues(); },
          "how many values (channels) the texel rule changed");

  py::class_<PyScene>(m, "Scene")
      .def(py::init<>())
      .def(
          "add_mesh",
          [](PyScene& self, const py::array& positions, const py::array& indices,
             const std::optional<py::array>& normals, const std::optional<py::array>& uvs,
             const std::optional<py::array>& colors) {
            const MeshArrays arrays = meshArrays(positions, indices, normals, uvs, colors);
            return self.forChange().addMesh(arrays.data).index;
          },
          py::arg("positions"), py::arg("indices"), py::kw_only(), py::arg("normals") = py::none(),
          py::arg("uvs") = py::none(), py::arg("colors") = py::none())
      .def(
          "update_mesh",
          [](PyScene& self, std::uint32_t mesh, const py::array& positions,
             const py::array& indices, const std::optional<py::array>& normals,
             const std::optional<py::array>& uvs, const std::optional<py::array>& colors) {
            const MeshArrays arrays = meshArrays(positions, indices, normals, uvs, colors);
            self.forChange().updateMesh({mesh}, arrays.data);
          },
          py::arg("mesh"), py::arg("positions"), py::arg("indices"), py::kw_only(),
          py::arg("normals") = py::none(), py::arg("uvs") = py::none(),
          py::arg("colors") = py::none())
      .def(
          "add_texture",
          [](PyScene& self, const py::array& texels, bool srgb, const std::string& wrapU,
             const std::string& wrapV, const std::string& filter) {
            py::array packed;
            const auto data = textureData(texels, srgb, wrapU, wrapV, filter, packed);
            return self.forChange().addTexture(data).index;
          },
          py::arg("texels"), py::kw_only(), py::arg("srgb") = true, py::arg("wrap_u") = "repeat",
          py::arg("wrap_v") = "repeat", py::arg("filter") = "trilinear")
      .def(
          "update_texture",
          [](PyScene& self, std::uint32_t texture, const py::array& texels, bool srgb,
             const std::string& wrapU, const std::string& wrapV, const std::string& filter) {
            py::array packed;
            const auto data = textureData(texels, srgb, wrapU, wrapV, filter, packed);
            self.forChange().updateTexture({texture}, data);
          },
          py::arg("texture"), py::arg("texels"), py::kw_only(), py::arg("srgb") = true,
          py::arg("wrap_u") = "repeat", py::arg("wrap_v") = "repeat",
          py::arg("filter") = "trilinear")
      .def(
          "add_material",
          [](PyScene& self, const std::array<float, 4>& baseColor,
             std::optional<std::uint32_t> texture, const std::string& alphaMode, float alphaCutoff,
             bool doubleSided) {
            api::MaterialData data;
            data.baseColor = baseColor;
            if (texture) data.texture = api::TextureHandle{*texture};
            data.alphaMode = choiceOf<api::AlphaMode>("alpha_mode", alphaMode,
                                                      {{"opaque", api::AlphaMode::Opaque},
                                                       {"mask", api::AlphaMode::Mask},
                                                       {"blend", api::AlphaMode::Blend}});
            data.alphaCutoff = alphaCutoff;
            data.doubleSided = doubleSided;
            return self.forChange().addMaterial(data).index;
          },
          py::kw_only(), py::arg("base_color") = std::array<float, 4>{1, 1, 1, 1},
          py::arg("texture") = py::none(), py::arg("alpha_mode") = "opaque",
          py::arg("alpha_cutoff") = 0.5f, py::arg("double_sided") = false)
      .def(
          "add_instance",
          [](PyScene& self, std::uint32_t mesh, std::uint32_t material,
             const std::optional<py::array>& transform) {
            const api::Matrix4 matrix =
                transform ? matrixOf("transform", *transform) : api::kIdentity;
            return self.forChange().addInstance({mesh}, {material}, matrix).index;
          },
          py::arg("mesh"), py::arg("material"), py::arg("transform") = py::none())
      .def(
          "set_transform",
          [](PyScene& self, std::uint32_t instance, const py::array& transform) {
            self.forChange().setTransform({instance}, matrixOf("transform", transform));
          },
          py::arg("instance"), py::arg("transform"))
      .def(
          "set_camera",
          [](PyScene& self, const PyCamera& camera) { self.forChange().setCamera(camera.data); },
          py::arg("camera"))
      .def(
          "set_animation_time",
          [](PyScene& self, double seconds, int animation) {
            self.forChange().setAnimationTime(animation, seconds);
          },
          py::arg("seconds"), py::arg("animation") = 0,
          "Poses a loaded scene `seconds` into one of its glTF animations (-1: the rest "
          "pose), as `quadra render --sequence` poses its frames.")
      .def_property_readonly(
          "animations",
          [](const PyScene& s) {
            std::vector<std::string> names;
            for (int a = 0; a < s.scene.animationCount(); ++a)
              names.push_back(s.scene.animationName(a));
            return names;
          },
          "The glTF animations' names, by index (\"\" when unnamed).")
      .def(
          "animation_duration",
          [](const PyScene& s, int animation) { return s.scene.animationDuration(animation); },
          py::arg("animation"), "Seconds to the animation's last key.")
      .def_property_readonly("mesh_count", [](const PyScene& s) { return s.scene.meshCount(); })
      .def_property_readonly("instance_count",
                             [](const PyScene& s) { return s.scene.instanceCount(); });

  m.def(
      "load",
      [](const std::string& path, const std::vector<std::string>& allowedPaths,
         std::optional<std::uint64_t> maxMemory, int sceneIndex) {
        api::LoadOptions options;
        options.allowedPaths = allowedPaths;
        if (maxMemory) options.maxMemory = *maxMemory;
        options.scene = sceneIndex;
        auto scene = std::make_unique<PyScene>();
        {
          py::gil_scoped_release released;
          scene->scene = api::load(path, options);
        }
        return scene;
      },
      py::arg("path"), py::kw_only(), py::arg("allowed_paths") = std::vector<std::string>{},
      py::arg("max_memory") = py::none(), py::arg("scene") = -1,
      "Loads a .gltf or .glb file into a Scene. allowed_paths: folders besides the file's own "
      "its URIs may read; max_memory: bytes the load may allocate (default 8 GiB); scene: the "
      "glTF scene (-1: the file's default).");

  py::class_<RenderResult>(m, "RenderResult")
      .def_readonly("color", &RenderResult::color,
                    "(H, W, 4) float32, premultiplied linear RGBA, row 0 the top")
      .def_readonly("depth", &RenderResult::depth,
                    "(H, W) float32 window depth in [0, 1], 1 where nothing is drawn; or None")
      .def_readonly(
          "normal", &RenderResult::normal,
          "aovs 'N': (H, W, 3) float32 world-space unit normal (docs/cli.md \"AOVs\"); or None")
      .def_readonly("position", &RenderResult::position,
                    "aovs 'P': (H, W, 3) float32 world-space position; or None")
      .def_readonly("uv", &RenderResult::uv, "aovs 'uv': (H, W, 2) float32 TEXCOORD_0; or None")
      .def_readonly("mask", &RenderResult::mask,
                    "aovs 'mask': (H, W) float32 depth-writing coverage; or None")
      .def_readonly("primitive_id", &RenderResult::primitiveId,
                    "aovs 'id': (H, W) uint32 triangle index, 0xFFFFFFFF where none; or None")
      .def_readonly("node_id", &RenderResult::nodeId,
                    "aovs 'id': (H, W) uint32 node (glTF) or instance index; or None")
      .def_readonly("material_id", &RenderResult::materialId,
                    "aovs 'id': (H, W) uint32 material index; or None");

  py::class_<PyRenderer>(m, "Renderer")
      .def(py::init([](int threads) {
             return std::make_unique<PyRenderer>(api::RendererOptions{.threads = threads});
           }),
           py::kw_only(), py::arg("threads") = 0)
      .def_property_readonly("threads",
                             [](const PyRenderer& r) { return r.renderer.threadCount(); })
      .def(
          "render",
          [](PyRenderer& self, PyScene& scene, int width, int height,
             const std::optional<PyCamera>& camera, int samples, const std::string& shading,
             const std::array<float, 4>& clearColor, bool depth,
             const std::vector<std::string>& aovs, std::optional<std::uint64_t> maxMemory,
             const std::optional<RenderResult>& out, const std::string& format,
             const py::object& env, float envRotation, float envIntensity, bool lights,
             const std::string& background,
             const std::optional<std::array<float, 3>>& backgroundColor, float exposure,
             const std::optional<std::string>& tonemap) {
            return render(self, scene, width, height, camera, samples, shading, clearColor, depth,
                          aovs, maxMemory, out, format,
                          {env, envRotation, envIntensity, lights, background, backgroundColor,
                           exposure, tonemap});
          },
          py::arg("scene"), py::kw_only(), py::arg("width"), py::arg("height"),
          py::arg("camera") = py::none(), py::arg("samples") = 1, py::arg("shading") = "unlit",
          py::arg("clear_color") = std::array<float, 4>{0, 0, 0, 0}, py::arg("depth") = true,
          py::arg("aovs") = std::vector<std::string>{}, py::arg("max_memory") = py::none(),
          py::arg("out") = py::none(), py::arg("format") = "rgba32f", py::arg("env") = py::none(),
          py::arg("env_rotation") = 0.0f, py::arg("env_intensity") = 1.0f, py::arg("lights") = true,
          py::arg("background") = "env", py::arg("background_color") = py::none(),
          py::arg("exposure") = 0.0f, py::arg("tonemap") = py::none(),
          "Renders scene into new numpy arrays (no copy after the render). camera: sets the "
          "scene's camera first (as scene.set_camera), else the scene's own is used. out: an "
          "earlier RenderResult whose arrays are overwritten when of this size. aovs: names of "
          "the CLI's --aov (N, P, uv, id, mask) whose arrays the result also holds. max_memory: "
          "bytes the frame may hold (default 8 GiB), as the CLI's --max-memory. shading: unlit, "
          "lit or pbr. format: color as rgba32f (float32 radiance x 2^exposure) or rgba8srgb "
          "(uint8, tone mapped, the CLI's PNG bytes). The CLI's render options, for pbr: env "
          "(an Environment, a file or builtin:NAME, or an (H, W, 3) float32 array; default "
          "builtin:studio), env_rotation, env_intensity, lights, background (env, color, "
          "transparent), background_color (r, g, b), exposure (every shading), tonemap "
          "(pbr-neutral, aces, none; default pbr-neutral for pbr, else none).");
}
